#pragma once
// The logarithmic curvature graph (LCG) of a sampled curve and its least-squares
// slope alpha (DESIGN.md section 2 "LCG"; seed 003 section 3.1, step 4 of the
// pipeline in DESIGN.md section 3).
//
// The LCG plots
//   x = log rho,   y = log(rho * |ds/drho|),   rho = 1/|kappa|.
// With drho/ds = -sign(kappa) * kappa' / kappa^2 (kappa' = dkappa/ds) this is
//   rho * |ds/drho| = |kappa| / |kappa'|,
// so, written in curvature only (no division by a small kappa' before the log):
//   x = -log|kappa|,   y = log|kappa| - log|kappa'|.
// For an LA curve, rho^alpha = c0 s + c1 (alpha != 0), rho |ds/drho| = |alpha / c0| rho^alpha,
// so the LCG is exactly the line y = alpha x + log|alpha / c0|; for alpha = 0
// (log rho = c0 s + c1) it is the horizontal line y = -log|c0|.
// Both x and y shift by log k when the curve is scaled by k, so the slope is
// scale-free and the intercept moves by (1 - alpha) log k.
//
// The seed fits the LCG of each smoothed piece "by least squares" and takes the
// slope as alpha (seed 003 section 3.1). Here: ordinary least squares of y on x,
// centred (two passes) so that a large log rho offset does not cancel the spread.
// The paper does not say how the points are sampled; the caller chooses (the pipeline
// samples uniformly in arc length, DESIGN.md section 3 step 4).
//
// Points where kappa == 0 (an inflection: x = +inf), kappa' == 0 (a curvature
// extremum or a circle: y = +inf) or any input is non-finite are left out of the
// output, never turned into NaN or inf. A circle therefore has no LCG points at all;
// a set of points whose x all coincide (rho constant but kappa' not 0, e.g. noise on a
// circle) is a vertical LCG, alpha = +-inf, reported as bad input by fitLcg.

#include <limits>
#include <span>
#include <vector>

#include "core/la_segment.h"
#include "core/solve_report.h"

namespace la {

/// One point of the LCG: x = log rho, y = log(rho |ds/drho|).
struct LcgPoint {
  double log_rho;
  double log_rho_ds_drho;
};

/// LCG points from curvature kappa and its arc-length derivative dkappa = dkappa/ds at
/// the same sample points (e.g. from an analytic curve). Samples with kappa == 0,
/// dkappa == 0 or a non-finite value are skipped, so the result may be shorter than the
/// input and is in input order. Throws std::invalid_argument if the sizes differ.
std::vector<LcgPoint> lcgFromDerivative(std::span<const double> kappa,
                                        std::span<const double> dkappa);

/// LCG points from curvature samples kappa at arc lengths s (any spacing, strictly
/// increasing). dkappa/ds is estimated by second-order finite differences on the
/// non-uniform grid: three-point central at interior samples, three-point one-sided at
/// the two ends (exact for kappa quadratic in s; error O(h^2)). Then as
/// lcgFromDerivative: samples where kappa or the estimate is 0 or non-finite are
/// skipped (a non-finite neighbour makes the estimate non-finite). Fewer than 3 samples give an empty result (no second-order
/// difference exists). Throws std::invalid_argument if the sizes differ or s is not
/// finite and strictly increasing.
std::vector<LcgPoint> lcgFromSamples(std::span<const double> s, std::span<const double> kappa);

/// LCG points of an LA segment from its own curvature and derivative, at `samples`
/// points evenly along it (lcgFromDerivative skips its zero-curvature end).
std::vector<LcgPoint> lcgOfSegment(const LaSegment& segment, int samples);

/// The least-squares line y = alpha x + intercept through LCG points.
struct LcgFit {
  double alpha = std::numeric_limits<double>::quiet_NaN();      // slope
  double intercept = std::numeric_limits<double>::quiet_NaN();  // y at x = 0 (rho = 1)
  double r2 = std::numeric_limits<double>::quiet_NaN();         // 1 - SS_res / SS_tot on y
  int points_used = 0;                                          // finite points in the fit
  /// kConverged on success, with residual = RMS of the y residuals (log units);
  /// kBadInput (message says why) when fewer than 3 finite points are given, or when
  /// all x coincide to rounding (vertical LCG: a circle, alpha = +-inf).
  SolveReport report;
};

/// Fits y = alpha x + intercept by ordinary least squares (seed 003 section 3.1).
/// Non-finite points are ignored. R^2 = 1 - SS_res / SS_tot with SS_res summed from
/// the residuals themselves (not as SS_tot - alpha * S_xy, which cancels when the
/// fit is good). When the residuals are at rounding level (the points are on the line
/// to machine precision; this includes SS_tot = SS_res = 0, all y equal) R^2 = 1.
/// Note: R^2 measures the share of the y spread the line explains, so for a nearly
/// horizontal LCG (alpha ~ 0) any small error (finite differences, noise) drives it
/// towards 0 although the fit is good; report.residual (RMS, log units) is the
/// absolute measure of straightness.
LcgFit fitLcg(std::span<const LcgPoint> points);

}  // namespace la
