#pragma once
// A plane curve given as a function of its arc length s in [0, L], as much of it as
// drawing and export need (cubic Bezier approximation, curvature comb, CSV samples):
// position, tangent angle theta(s), signed curvature kappa(s), dense samples.
//
// LA segments (core/la_segment.h) are seen through LaSegmentView, which adds no
// virtual functions to LaSegment itself; ALP curves (core/alp_curve.h) implement the
// interface directly.

#include <algorithm>
#include <cmath>

#include "core/la_segment.h"

namespace la {

class ArcLengthCurve {
 public:
  virtual ~ArcLengthCurve() = default;
  virtual double length() const = 0;
  /// Position at arc length s, accurate to relative_tolerance * length().
  virtual Vec2 position(double s, double relative_tolerance = kDefaultRelativeTolerance) const = 0;
  virtual double theta(double s) const = 0;
  virtual double kappa(double s) const = 0;
  /// n >= 2 samples uniform in arc length, the last at s = L, appended to `out` with s
  /// offset by s_offset (positions to the default relative tolerance).
  virtual void sample(int n, CurveSamples& out, double s_offset = 0.0) const = 0;
  /// Total variation of theta, integral_0^L |kappa| ds: how much the curve bends, which
  /// sets how many Bezier pieces it needs. For a curve whose curvature keeps one sign
  /// it is |theta(L) - theta(0)|.
  virtual double totalTurning() const = 0;
  /// The largest |kappa| on [0, L] (for scaling a curvature comb).
  virtual double maxAbsKappa() const = 0;
};

/// An LA segment as an ArcLengthCurve; holds a reference, so the segment must outlive it.
class LaSegmentView final : public ArcLengthCurve {
 public:
  explicit LaSegmentView(const LaSegment& segment) : segment_(segment) {}
  double length() const override { return segment_.length(); }
  Vec2 position(double s, double relative_tolerance = kDefaultRelativeTolerance) const override {
    return segment_.position(s, relative_tolerance);
  }
  double theta(double s) const override { return segment_.theta(s); }
  double kappa(double s) const override { return segment_.kappa(s); }
  void sample(int n, CurveSamples& out, double s_offset = 0.0) const override { segment_.sample(n, out, s_offset); }
  // Curvature keeps one sign and is monotone along an LA segment.
  double totalTurning() const override { return std::abs(segment_.turning()); }
  double maxAbsKappa() const override {
    return segment_.maxAbsKappa();
  }

 private:
  const LaSegment& segment_;
};

}  // namespace la
