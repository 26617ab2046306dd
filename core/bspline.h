#pragma once
// Cubic B-spline curves, open (clamped) or closed (periodic), with derivatives to the
// third order and the per-span polynomial form that the segmentation's root finding
// needs. Evaluation by the Cox-de Boor recurrence with derivatives (Piegl & Tiller,
// The NURBS Book, algorithm A2.3).
//
// A periodic spline with n spans over breaks b_0 < ... < b_n has n distinct control
// points; it is stored as the equivalent unclamped spline with n + 3 control points
// (the first three repeated at the end) over the periodically extended knots, so
// both kinds share one evaluator. `controlIndex(k)` maps a stored control point to
// its distinct one.

#include <algorithm>
#include <array>
#include <vector>

#include "core/geometry.h"

namespace la {

class CubicBSpline {
 public:
  static constexpr int kDegree = 3;

  /// Open spline: knots.size() == control.size() + 4, non-decreasing, usually clamped
  /// (first and last knot repeated 4 times). Throws std::invalid_argument otherwise.
  CubicBSpline(std::vector<double> knots, std::vector<Vec2> control);
  /// Open clamped spline with the given breaks b_0 < ... < b_n (n spans, n + 3 control points).
  static CubicBSpline clamped(const std::vector<double>& breaks, std::vector<Vec2> control);
  /// Closed periodic spline: breaks.size() == control.size() + 1 >= 4.
  static CubicBSpline periodic(const std::vector<double>& breaks, const std::vector<Vec2>& control);

  bool isPeriodic() const { return periodic_count_ > 0; }
  double tMin() const { return knots_[kDegree]; }
  double tMax() const { return knots_[knots_.size() - 1 - kDegree]; }
  const std::vector<double>& knots() const { return knots_; }
  const std::vector<Vec2>& control() const { return control_; }
  /// Number of free control points (distinct ones for a periodic spline).
  int freeControlCount() const { return isPeriodic() ? periodic_count_ : static_cast<int>(control_.size()); }
  int controlIndex(int stored) const { return isPeriodic() ? stored % periodic_count_ : stored; }

  /// Breaks: the distinct knots in [tMin, tMax], i.e. span boundaries.
  std::vector<double> breaks() const;
  /// Knot span index i (knots[i] <= t < knots[i+1]) for t in [tMin, tMax] (a periodic t is wrapped).
  int span(double t) const;
  /// The same for a t already wrapped (wrap()), found by walking from span `hint`: a step
  /// or two for parameters taken in order along the curve (the smoothing's hot loops)
  /// instead of a binary search.
  int spanFrom(double wrapped, int hint) const {
    const int last = static_cast<int>(control_.size()) - 1;
    int i = std::clamp(hint, kDegree, last);
    while (i < last && wrapped >= knots_[i + 1]) ++i;
    while (i > kDegree && wrapped < knots_[i]) --i;
    return i;
  }
  double wrap(double t) const;  // into [tMin, tMax) for periodic, clamped for open

  /// Nonzero basis functions of span i at t and their derivatives up to `order` (<= 3):
  /// ders[d][j] = d^d N_{i-3+j} / dt^d. Lower orders cost less (the fitting's hot loop
  /// needs only values).
  void basis(int span, double t, double ders[4][4], int order = 3) const;

  Vec2 point(double t) const { return evaluate(t, 0); }
  /// d-th derivative with respect to t (d = 0..3).
  Vec2 evaluate(double t, int derivative) const;
  /// Point and derivatives up to `order` at once (higher entries are zero).
  std::array<Vec2, 4> derivatives(double t, int order = 3) const;
  /// Signed curvature at t.
  double curvature(double t) const;
  /// Signed curvature and its derivative with respect to arc length at t.
  void curvatureAndSlope(double t, double& kappa, double& dkappa_ds) const;

  /// Taylor coefficients of span i about its start knot: C(t) = sum_k c[k] (t - knots[i])^k.
  std::array<Vec2, 4> spanPolynomial(int span) const;

 private:
  std::vector<double> knots_;
  std::vector<Vec2> control_;
  int periodic_count_ = 0;  // distinct control points of a periodic spline, 0 if open
};

}  // namespace la
