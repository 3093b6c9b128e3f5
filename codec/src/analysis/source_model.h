// The one interface every fitted source model of a wavelet coefficient
// (single Laplacian, Laplacian mixture, generalized Gaussian; Satti et al. 2011)
// offers to the histogram and distortion-rate code: a zero-mean symmetric
// density known through its mass and squared error on intervals of x >= 0.
#ifndef MESHWAVE_ANALYSIS_SOURCE_MODEL_H_
#define MESHWAVE_ANALYSIS_SOURCE_MODEL_H_

#include <cmath>
#include <limits>

namespace meshwave {

class SourceModel {
 public:
  virtual ~SourceModel() = default;
  // Mass of the density on [a, b], 0 <= a <= b (b may be +infinity).
  virtual double Mass(double a, double b) const = 0;
  // Integral over [a, b] (0 <= a <= b < infinity) of (x - r)^2 f(x) dx.
  virtual double SquaredError(double a, double b, double r) const = 0;
  // Standard deviation of the whole density.
  virtual double Sigma() const = 0;

  // Mass on any interval of the real line, by symmetry.
  double SignedMass(double a, double b) const {
    if (b <= a) return 0.0;
    if (a >= 0) return Mass(a, b);
    if (b <= 0) return Mass(-b, -a);
    return Mass(0, -a) + Mass(0, b);
  }
};

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace meshwave

#endif  // MESHWAVE_ANALYSIS_SOURCE_MODEL_H_
