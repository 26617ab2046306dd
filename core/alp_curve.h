#pragma once
// A curve defined by its curvature as an explicit Bezier function of arc length: an
// ALP (arc-length parameterization) curve of Yoshida & Saito (seed 000 section 3,
// seed 004 section 3; DESIGN.md section 4).
//
// With tau = s / L on [0, 1] (L the length, s_t in the papers) and n + 1 control
// curvatures kappa_i,
//   polynomial (seed 000 eq. 4, 7):  kappa(s) = K(tau) = sum_i B_i^n(tau) kappa_i
//   rational   (seed 000 eq. 9, 10): kappa(s) = K_R(tau) = sum_i B_i^n(tau) w_i kappa_i
//                                                         / sum_i B_i^n(tau) w_i,  w_i > 0.
// (Seed 004 eq. 1 writes kappa(s) = s_t K(tau), a slip: kappa = K(s / s_t) is what
// makes theta_d = s_t * integral_0^1 K, its eq. 4 and seed 000 eq. 6.)
// theta(s) = theta0 + integral_0^s kappa (seed 000 eq. 2). For the polynomial the
// integral is a Bezier function of degree n + 1 (closed form, bernsteinIntegral),
// theta_d = L sum kappa_i / (n + 1) (eq. 6). For the rational one (eq. 11 needs the
// same integral) it is a piecewise Chebyshev series built at construction: K_R
// interpolated on panels until the series' tail is below 1e-14 max|kappa_i|, then
// integrated term by term.
// Positions P(s) = start + integral_0^s (cos theta, sin theta) (eq. 3) are computed
// by adaptive Gauss-Legendre from a table of positions at panel boundaries, built
// at construction to kTableRelativeTolerance.
//
// The curvature may change sign (an inflection, seed 000 section 3.4) and need not be
// monotone: core/alp_hermite.h has the checks.

#include <vector>

#include "core/arc_length_curve.h"
#include "core/bernstein.h"
#include "core/geometry.h"
#include "core/la_segment.h"  // CurveSamples, kDefaultRelativeTolerance

namespace la {

class AlpCurve final : public ArcLengthCurve {
 public:
  /// weights empty = polynomial; else one positive weight per control curvature.
  /// Throws std::invalid_argument for no control curvatures, a weight count that does
  /// not match, a non-positive weight, a non-positive length, or anything not finite.
  AlpCurve(std::vector<double> control_kappa, std::vector<double> weights, double length, Vec2 start, double theta0);

  int degree() const { return static_cast<int>(control_kappa_.size()) - 1; }
  bool isRational() const { return !weights_.empty(); }
  double length() const override { return length_; }
  const Vec2& start() const { return start_; }
  double theta0() const { return theta0_; }
  const std::vector<double>& controlKappa() const { return control_kappa_; }
  /// Empty for a polynomial curve.
  const std::vector<double>& weights() const { return weights_; }

  /// Curvature at arc length s (clamped to [0, L]).
  double kappa(double s) const override;
  /// d kappa / ds.
  double dkappa(double s) const;
  double theta(double s) const override;
  Vec2 tangent(double s) const { return unitVector(theta(s)); }
  /// Position at arc length s (clamped to [0, L]), to relative_tolerance * length.
  Vec2 position(double s, double relative_tolerance = kDefaultRelativeTolerance) const override;
  /// position(L), computed once at construction.
  Vec2 end() const { return end_; }
  /// Total turning theta(L) - theta(0) (theta_d of seed 000 eq. 6, 11).
  double turning() const { return turning_; }

  /// n >= 2 samples uniform in arc length, the last exactly at s = L; appended to
  /// `out` (not cleared), with s offset by s_offset. Positions are accurate to
  /// relative_tolerance * length. Throws std::invalid_argument for n < 2.
  void sample(int n, CurveSamples& out, double s_offset = 0.0) const override {
    sample(n, out, s_offset, kDefaultRelativeTolerance);
  }
  void sample(int n, CurveSamples& out, double s_offset, double relative_tolerance) const;
  CurveSamples sample(int n) const;

  /// integral_0^L |kappa| ds (ArcLengthCurve).
  double totalTurning() const override { return total_turning_; }
  /// max |kappa| on [0, L] (ArcLengthCurve).
  double maxAbsKappa() const override { return max_abs_kappa_; }

  /// The curvature function in tau = s / L as Bezier coefficients: K itself for the
  /// polynomial; for the rational one the numerator sum B_i w_i kappa_i (the
  /// denominator is weights()).
  const BernsteinCoefficients& curvatureNumerator() const { return numerator_; }
  /// A Bezier function of tau with the sign of d kappa / ds: dK/dtau for the
  /// polynomial; for the rational one the numerator N' D - N D' of dK_R/dtau
  /// (degree 2n - 1 here, of true degree 2n - 2; seed 000 section 3.4).
  BernsteinCoefficients curvatureDerivativeNumerator() const;

  /// Accuracy of the position table built at construction, relative to the length
  /// (20-point sums round to a few 1e-16 of it: a margin of ~100).
  static constexpr double kTableRelativeTolerance = 1e-13;

 private:
  // K(tau) and dK/dtau.
  double curvatureAt(double tau) const;
  double curvatureDerivativeAt(double tau) const;
  // integral_0^tau K, i.e. (theta(tau L) - theta0) / L.
  double unitTurningAt(double tau) const;

  std::vector<double> control_kappa_, weights_;
  double length_;
  Vec2 start_;
  double theta0_;

  BernsteinCoefficients numerator_;     // w_i kappa_i (or kappa_i)
  BernsteinCoefficients d_numerator_;   // its derivative in tau
  BernsteinCoefficients d_weights_;     // derivative of the denominator (rational)
  BernsteinCoefficients turning_poly_;  // polynomial: integral of K, degree n + 1
  std::vector<double> theta_breaks_;    // rational: panels of the turning quadrature in tau
  std::vector<double> unit_turning_;    // rational: integral_0^{theta_breaks_k} K_R
  std::vector<double> theta_series_;    // rational: per panel, Chebyshev series of the integral since its start
  std::vector<double> breaks_;          // panels of the position table in tau, 0 .. 1
  std::vector<Vec2> table_;             // position at each break
  Vec2 end_;
  double turning_ = 0.0, total_turning_ = 0.0, max_abs_kappa_ = 0.0;
};

}  // namespace la
