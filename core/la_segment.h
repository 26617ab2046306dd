#pragma once
// A log-aesthetic (LA) curve segment in intrinsic form (DESIGN.md sections 2 and 5).
//
// The segment is a function of arc length s in [0, L]. Its radius of curvature
// rho = 1/|kappa| follows the LA law between the two end curvatures:
//   alpha != 0:  rho(s)^alpha is linear in s      (kappa = sign * (c0 s + c1)^(-1/alpha))
//   alpha == 0:  log rho(s) is linear in s
//   alpha = +-inf, or kappa_start == kappa_end: a circular arc (a line if kappa = 0).
// The curvature keeps one sign; it may be 0 at one end only if alpha < 0 (an
// inflection end, seed 003 section 2.2). Curvature is signed, left turn positive.
//
// The tangent angle theta(s) has a closed form (the integral of kappa); positions
// are integrals of (cos theta, sin theta) by adaptive Gauss-Legendre quadrature, except
// next to an inflection end (kappa = 0, singular law), where a power series gives them
// exactly (inflectionOffset). The closed forms are written with log1p/expm1 so
// that near-circular segments (curvature ratio close to 1) lose no precision.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/geometry.h"

namespace la {

/// Default accuracy of positions, relative to the segment length.
inline constexpr double kDefaultRelativeTolerance = 1e-10;

/// Dense samples of a curve, uniform in arc length: for drawing and export.
struct CurveSamples {
  std::vector<double> s;      // arc length from the segment start
  std::vector<Vec2> point;
  std::vector<Vec2> tangent;  // unit tangent
  std::vector<double> theta;  // tangent angle (continuous, not wrapped)
  std::vector<double> kappa;  // signed curvature
  void clear();
  void reserve(std::size_t n);
  std::size_t size() const { return s.size(); }
};

class LaSegment {
 public:
  /// Throws std::invalid_argument when the parameters do not describe an LA segment
  /// (non-positive length, curvatures of opposite sign, a zero end with alpha >= 0,
  /// a circle alpha with unequal end curvatures, NaN).
  LaSegment(double alpha, double length, Vec2 start, double theta0, double kappa_start,
            double kappa_end);

  /// A circular arc (a line if kappa == 0): alpha = inf.
  static LaSegment arc(double length, Vec2 start, double theta0, double kappa);

  /// The segment of the law (alpha, end curvatures) whose total turning is |turning|
  /// (its length follows: at a fixed law the turning grows linearly with it). Throws
  /// std::invalid_argument as the constructor does, and when the law does not turn.
  static LaSegment withTurning(double alpha, double turning, Vec2 start, double theta0, double kappa_start,
                               double kappa_end);

  double alpha() const { return alpha_; }
  double length() const { return length_; }
  const Vec2& start() const { return start_; }
  double theta0() const { return theta0_; }
  double kappaStart() const { return kappa_start_; }
  double kappaEnd() const { return kappa_end_; }
  /// The largest |kappa| on the segment: at an end, its curvature being monotone.
  double maxAbsKappa() const { return std::max(std::abs(kappa_start_), std::abs(kappa_end_)); }
  /// +1 for a left-turning segment, -1 for right, 0 for a straight line.
  double turnSign() const { return sign_; }
  bool isCircular() const { return law_ == Law::kConstant; }
  /// A straight line (a circular arc of zero curvature).
  bool isStraight() const { return sign_ == 0.0; }

  double kappa(double s) const;
  /// d kappa / ds; infinite at an inflection end where the law is singular (alpha < -1).
  double dkappa(double s) const;
  double theta(double s) const;
  /// theta(s) and kappa(s) together, for the cost of about one of them (they share the
  /// law's logarithm): for inner loops that need both.
  void thetaKappa(double s, double& theta, double& kappa) const;
  Vec2 tangent(double s) const { return unitVector(theta(s)); }
  /// Position at arc length s, to relative_tolerance * length.
  Vec2 position(double s, double relative_tolerance = kDefaultRelativeTolerance) const;
  Vec2 end(double relative_tolerance = kDefaultRelativeTolerance) const {
    return position(length_, relative_tolerance);
  }
  /// Total turning theta(L) - theta(0).
  double turning() const { return theta(length_) - theta0_; }

  /// The same curve traversed from its end to its start.
  LaSegment reversed() const;

  /// n >= 2 samples uniform in arc length, the last exactly at s = L; appended to
  /// `out` (which is not cleared), with s offset by s_offset. Positions are accurate
  /// to relative_tolerance * length.
  void sample(int n, CurveSamples& out, double s_offset = 0.0,
              double relative_tolerance = kDefaultRelativeTolerance) const;
  CurveSamples sample(int n) const;

 private:
  enum class Law { kConstant, kPower, kExponential };

  // Integral of |kappa| / kappa_ref from 0 to s, i.e. the turning per unit kappa_ref.
  double unitTurning(double s) const;
  // The power law's v(s) = (rho(s)/rho_ref)^alpha, linear in s, and its logarithm.
  double v(double s) const;
  double logV(double s) const;
  Vec2 integratePositionAdaptive(double s0, double s1, double abs_tol) const;
  // The position change over [s0, s1], a panel of the sampler that turns or bends too
  // far for the series: in shorter steps on which it holds, else by adaptive quadrature.
  Vec2 integratePositionInSteps(double s0, double s1, double abs_tol) const;
  // One panel of the sampler; returns false where the series is not accurate enough.
  struct PanelStep {
    double turning;      // theta change
    double kappa_ratio;  // kappa at the panel's end over kappa at its start
    // Small turning: Simpson's rule, which the caller completes with the end tangent;
    // (mid_cos, mid_sin) rotate the start tangent to the midpoint's. Otherwise `delta`.
    bool simpson;
    double mid_cos, mid_sin;
    Vec2 delta;          // position change over the panel (4-point Gauss-Legendre)
    // Simpson's position change over a panel of length h, from its end tangents.
    Vec2 simpsonDelta(double h, const Vec2& tangent_start, const Vec2& tangent_end) const;
  };
  bool panelBySeries(double s0, double h, double kappa_start, const Vec2& tangent_start, PanelStep& step) const;
  // The position change over [s0, s1] near an inflection end (power law with v = 0 at
  // one end), by the power series of the standard inflection form; false where there is
  // no inflection end or [s0, s1] reaches too far from it for the series.
  bool panelNearInflection(double s0, double s1, Vec2& delta) const;
  Vec2 inflectionOffset(double r, double heading, double turn_sign) const;
  // The distance from the inflection end within which panelNearInflection applies.
  double inflectionSeriesReach() const;

  double alpha_, length_;
  Vec2 start_;
  double theta0_, kappa_start_, kappa_end_;

  // Precomputed law. kPower: |kappa| = kappa_ref * v(s)^(-1/alpha), v linear from v0 to v1,
  // v = (rho/rho_ref)^alpha, reference end the start (v0 = 1) unless kappa_start = 0
  // (v0 = 0, reference the end). kExponential: |kappa| = kappa_ref * exp(-g*s).
  Law law_ = Law::kConstant;
  double sign_ = 0.0;
  double kappa_ref_ = 0.0;
  double v0_ = 1.0, v1_ = 1.0, dv_ = 0.0;  // v at s = 0 and s = L, slope
  double exponent_ = 0.0;  // e = 1 - 1/alpha, power of v in the turning integral
  double series_rate_ = 1.0;  // max(1, |e|, |1/alpha|): the series' ratio per unit of |x|
  // Taylor coefficients g_k of the turning over a panel in the law's local variable
  // (see panelBySeries); they depend on alpha only.
  static constexpr int kSeriesTerms = 24;
  std::array<double, kSeriesTerms + 1> series_{};
  std::array<double, kSeriesTerms + 1> kappa_series_{};  // of kappa(s0 + h) / kappa(s0) in x
  double growth_ = 0.0;    // g of the exponential law
};

/// The tangent's turn from the end of `a` to the start of `b`, wrapped to (-pi, pi]: 0
/// at a G1 joint, the corner's angle at a corner.
inline double turnBetween(const LaSegment& a, const LaSegment& b) { return wrapAngle(b.theta0() - a.theta(a.length())); }

}  // namespace la
