#include "quant/subband_gains.h"

#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "meshwave/semiregular.h"

namespace meshwave {
namespace {

constexpr int kMeasuredLevels = 5;

TriMesh RegularTorus(int n, int m) {
  TriMesh t;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.positions.push_back({(3 + std::cos(v)) * std::cos(u),
                             (3 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  }
  auto id = [&](int i, int j) {
    return static_cast<uint32_t>(((i + n) % n) * m + (j + m) % m);
  };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      t.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return t;
}

// Energy at the finest level of the response to a unit impulse (each axis
// in turn, global frame) at `index` of subband j (j = -1: base vertex).
double ImpulseEnergy(const WaveletTransform& t, const Pyramid& zero, int j,
                     uint32_t index) {
  double energy = 0;
  for (int axis = 0; axis < 3; ++axis) {
    Pyramid p = zero;
    if (j < 0) {
      p.base[index][axis] = 1.0;
    } else {
      p.subbands[j][index][axis] = 1.0;
    }
    for (const Vec3& x : t.Inverse(p)) energy += x.squaredNorm();
  }
  return energy / 3;
}

SubbandGains Measure(const TransformSettings& settings, int levels) {
  SubbandGains gains;
  gains.subband.assign(levels, 1.0);
  if (levels == 0) return gains;
  const int measured = std::min(levels, kMeasuredLevels);
  const TriMesh torus = RegularTorus(4, 6);
  auto h = SemiRegularHierarchy::Build(static_cast<uint32_t>(torus.positions.size()),
                                       torus.faces, measured);
  TransformSettings global = settings;
  global.frames = FrameMode::kGlobal;
  // SAWT's gains are taken as f1's: on the regular torus f1 is the
  // butterfly, and the calibration of the packet index corrects the rest.
  if (global.predictor == Predictor::kSawt) global.predictor = Predictor::kButterfly;
  auto t = WaveletTransform::Create(*h, global);
  Pyramid zero;
  zero.hierarchy = *h;
  zero.settings = global;
  zero.base.assign((*h)->vertex_count(0), Vec3::Zero());
  for (int j = 0; j < measured; ++j) {
    zero.subbands.emplace_back((*h)->subband_size(j), Vec3::Zero());
  }
  // The torus is regular, so one coefficient per subband stands for all.
  std::vector<double> g(measured);
  for (int j = 0; j < measured; ++j) g[j] = ImpulseEnergy(*t, zero, j, 0);
  const double base = ImpulseEnergy(*t, zero, -1, 0);
  const double finest = g[measured - 1];
  // Distance m from the finest subband: measured for m < 5, 4x per level after.
  for (int j = 0; j < levels; ++j) {
    const int m = levels - 1 - j;
    gains.subband[j] = m < measured ? g[measured - 1 - m] / finest
                                    : g[0] / finest * std::pow(4.0, m - (measured - 1));
  }
  gains.base = base / finest * std::pow(4.0, levels - measured);
  return gains;
}

}  // namespace

SubbandGains ComputeSubbandGains(const TransformSettings& settings, int levels) {
  static std::mutex mutex;
  static std::map<std::tuple<int, int, int>, SubbandGains> cache;
  const auto key = std::make_tuple(static_cast<int>(settings.predictor),
                                   static_cast<int>(settings.update), levels);
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  SubbandGains gains = Measure(settings, levels);
  std::lock_guard<std::mutex> lock(mutex);
  cache.emplace(key, gains);
  return gains;
}

}  // namespace meshwave
