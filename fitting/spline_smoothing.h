#pragma once
// Stage 2 of the pipeline (DESIGN.md section 3): a cubic B-spline that stays within
// a distance tolerance of the stroke's points, with as few knots and as little
// curvature wiggle as that allows.
//
// Least squares with a fairness penalty: minimize
//   sum_i |C(t_i) - X_i|^2  +  w * N * integral |C'''(t)|^2 dt,   t in [0, 1],
// a sparse symmetric system in the control points (bandwidth 3; the periodic case
// wraps around). The jerk penalty w is scale-free: t is normalized and the data term
// grows with N. Knots start uniform and are added at the middle of every span whose
// worst point is out of tolerance (in a span of few points only where a neighbour
// misses on the same side: a lone outlier is not chased); between solves the parameters t_i move to the foot
// points (Newton on (C(t) - X) . C'(t) = 0). Once within tolerance, w is raised
// (bisection on log w) until the residuals reach the noise level of the points, which
// removes the curvature wiggles the noise made and keeps the curvature of clean data.
// An open spline's ends are free; where that misses the tolerance (by more than
// SmoothingOptions::through_ends_beyond times it), it is fitted again through the first
// and last points, kept where that keeps the tolerance.

#include <vector>

#include "core/bspline.h"
#include "core/solve_report.h"

namespace la {

struct SmoothingOptions {
  double tolerance = 0.0;    // max distance from any point to the spline (absolute, > 0)
  int initial_spans = 4;
  int max_spans = 400;
  int max_rounds = 30;
  int foot_point_steps = 2;  // Newton steps per point per round
  double fairness = 1e-14;   // w, the starting jerk weight (just enough to keep empty spans defined)
  double max_fairness = 1e-2;
  int fairness_steps = 6;    // bisection steps on log w (0: keep w fixed)
  double fairness_margin = 0.9;  // use at most this fraction of the tolerance when raising w
  double noise_sigma = 0.0;      // estimated noise of the points; w is raised only while the
                                 // rms residual stays below sigma sqrt(2) (0: never raised)
  // An open spline that misses the tolerance with its ends free, by more than this many
  // tolerances, is fitted again through the first and last points, kept where that keeps
  // the tolerance (a free end can fall short of its point along the tangent, which no
  // knot cures; INFINITY: the ends stay free).
  double through_ends_beyond = 1.0;
};

struct SmoothingResult {
  CubicBSpline spline;
  std::vector<double> parameters;  // foot-point parameter of each input point
  double max_error = 0.0;          // max |C(t_i) - X_i|
  double rms_error = 0.0;
  double fairness = 0.0;           // the w finally used
  int rounds = 0;
  SolveReport report;              // kConverged when max_error <= tolerance
};

/// Points in order; closed gives a periodic spline (the last point is not repeated).
SmoothingResult smoothWithBSpline(const std::vector<Vec2>& points, bool closed, const SmoothingOptions& options);

}  // namespace la
