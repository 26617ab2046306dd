#pragma once
// What every stage of one fit shares (fitting/pipeline.h runs them): the options as the
// user gave them, the tolerance as used, the points' noise, the stroke's size, the
// time spent per stage and what the fit may still spend.
//
// The tolerance has one meaning everywhere: the largest distance the curve may pass
// from any point of the stroke, in the stroke's units, after the noise floor raised it
// (FitResult::tolerance reports it). Stages that work inside it (the spline of stage 2,
// the model selection of stage 7) derive their own margins from it where they say so.

#include <chrono>

#include "fitting/budget.h"
#include "fitting/g2_joints.h"
#include "fitting/pipeline.h"
#include "fitting/stroke_noise.h"

namespace la {

inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Stage 6's options (also for closing stage 7's chain and the user's edits).
inline G2Options g2OptionsOf(const FitOptions& options, double diagonal) {
  G2Options g2;
  g2.method = options.g2;
  g2.threshold = options.g2_threshold;
  g2.diagonal = diagonal;
  return g2;
}

/// Whether stage 7 bends no tighter than the tolerance (ChainFitOptions::max_curvature).
enum class RadiusBound {
  kBoundThenFree,  // bounded; a part that misses the tolerance on the bound is fitted again without it, kept if closer
  kFree,           // not bounded
  kStrict,         // bounded, no part fitted again: the bound wins over the tolerance
};

struct FitContext {
  const FitOptions& options;
  double tolerance = 0.0;  // absolute max distance, as used
  Noise noise;
  double diagonal = 0.0;   // of the cleaned stroke's bounding box
  StageTimings& timings;
  /// Once it is spent (the time budget, FitOptions::time_budget_ms, or a path's share of
  /// work), stage 7 stops editing and keeps the best G2 chain it has.
  Budget budget{};
  RadiusBound radius_bound = RadiusBound::kBoundThenFree;

  G2Options g2() const { return g2OptionsOf(options, diagonal); }
};

}  // namespace la
