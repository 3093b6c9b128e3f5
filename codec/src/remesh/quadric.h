// A quadric error form (Garland-Heckbert): the weighted sum of squared
// distances of a point to a set of planes, as x'Ax + 2b'x + c.
#ifndef MESHWAVE_REMESH_QUADRIC_H_
#define MESHWAVE_REMESH_QUADRIC_H_

#include <Eigen/Dense>
#include <cmath>

#include "meshwave/mesh.h"

namespace meshwave::remesh {

struct Quadric {
  // Symmetric A (xx xy xz yy yz zz), b, c.
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  double bx = 0, by = 0, bz = 0, c = 0;

  // weight · (n·p + d)² for a unit normal n.
  static Quadric Plane(const Vec3& n, double d, double weight) {
    Quadric q;
    q.xx = weight * n.x() * n.x();
    q.xy = weight * n.x() * n.y();
    q.xz = weight * n.x() * n.z();
    q.yy = weight * n.y() * n.y();
    q.yz = weight * n.y() * n.z();
    q.zz = weight * n.z() * n.z();
    q.bx = weight * d * n.x();
    q.by = weight * d * n.y();
    q.bz = weight * d * n.z();
    q.c = weight * d * d;
    return q;
  }

  Quadric& operator+=(const Quadric& o) {
    xx += o.xx;
    xy += o.xy;
    xz += o.xz;
    yy += o.yy;
    yz += o.yz;
    zz += o.zz;
    bx += o.bx;
    by += o.by;
    bz += o.bz;
    c += o.c;
    return *this;
  }
  friend Quadric operator+(Quadric a, const Quadric& b) { return a += b; }

  double Error(const Vec3& p) const {
    const double x = p.x(), y = p.y(), z = p.z();
    return xx * x * x + 2 * xy * x * y + 2 * xz * x * z + yy * y * y +
           2 * yz * y * z + zz * z * z + 2 * (bx * x + by * y + bz * z) + c;
  }

  // The point of least error, when A is well conditioned (planes that pin
  // a point down, not a line or a plane).
  bool Minimizer(Vec3* p) const {
    Eigen::Matrix3d a;
    a << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    const double trace = xx + yy + zz;
    if (!(trace > 0)) return false;
    const double det = a.determinant();
    // Relative to the scale of A: a near-singular form (flat or cylindrical
    // neighbourhood) has no well-defined optimum, so the caller falls back.
    if (!(std::abs(det) > 1e-9 * trace * trace * trace)) return false;
    *p = -a.inverse() * Vec3(bx, by, bz);
    return p->allFinite();
  }
};

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_QUADRIC_H_
