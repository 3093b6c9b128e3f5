#include "scaled_distance.h"

#include "meshwave/metrics.h"

namespace meshwave::cli {

proto::ScaledDistance Scaled(double distance, double diagonal) {
  proto::ScaledDistance out;
  out.set_absolute(distance);
  out.set_percent_of_diagonal(100 * distance / diagonal);
  out.set_psnr_db(PsnrDb(diagonal, distance));
  return out;
}

}  // namespace meshwave::cli
