// The encoder's choice of SAWT filters (the rate-distortion criterion of Denis
// et al. 2010a): per (level, region),
// the filter l minimising E_k[|c_p - f_l(c)|^2] + lambda R_k(f_l), with E_k
// the mean squared prediction error (x + y + z) over the region's odd
// vertices and R_k the bits the adaptive index code would spend on l at
// that point of the stream (wavelet/sawt_index_model.h).
#ifndef MESHWAVE_WAVELET_SAWT_CHOICE_H_
#define MESHWAVE_WAVELET_SAWT_CHOICE_H_

#include <array>
#include <memory>
#include <span>

#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "meshwave/wavelet.h"
#include "wavelet/sawt_plan.h"
#include "wavelet/sawt_regions.h"  // ForEachCodedSawtChoice

namespace meshwave {

// The encoder passes lambda = EncodeOptions::sawt_lambda_scale * step0^2
// (step0 the finest quantisation step; docs/ANALYSIS.md "SAWT" has the
// sweep that chose the constant). Levels are chosen finest first, as the forward transform runs: with an
// update step, the coarser levels' positions depend on the finer choices.
Result<std::shared_ptr<const SawtPlan>> ChooseSawtFilters(
    const SemiRegularHierarchy& hierarchy, SawtRegions regions,
    std::span<const Vec3> positions, UpdateWeights update, double lambda);

// How many coded (level, region) pairs use each filter.
std::array<uint32_t, kSawtFilterCount> SawtFilterUsage(const SemiRegularHierarchy& h,
                                                       const SawtPlan& plan);

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_SAWT_CHOICE_H_
