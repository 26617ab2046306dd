#include "core/la_segment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/quadrature.h"

namespace la {
namespace {

// The sampler's series path (panelBySeries) is used only where the turning over a
// panel is at most this many radians: then a degree-11 Taylor polynomial of
// (cos, sin) is exact to 1e-17 and 4-point Gauss-Legendre on the panel to ~1e-14 h.
constexpr double kSeriesMaxTurning = 0.1;
// ... and where the series of the turning in the law's local variable x converges
// at least this fast (ratio of successive terms).
constexpr double kSeriesMaxRatio = 0.1;
// At most this turning per panel, Simpson's rule on the panel's two ends (whose
// tangents the sampler has anyway) and its midpoint suffices: its error is h f/2880 with
// f ~ turning^4, below 3e-12 h as the 2-point Gauss-Legendre rule it replaces was at
// 0.01 rad (h f/4320); it needs one series evaluation less per panel.
constexpr double kSimpsonTurning = 0.009;
// The inflection series (panelNearInflection, position) is used up to this turning from the
// inflection point: its terms fall like turning^k / k!, below 1e-17 after ~20 terms.
constexpr double kInflectionSeriesMaxTurning = 1.0;
constexpr int kInflectionSeriesMaxTerms = 40;
// The sampler evaluates theta and kappa exactly at least every this many samples.
constexpr int kResyncSamples = 16;

std::string describe(double alpha, double length, double k0, double k1) {
  return "alpha=" + std::to_string(alpha) + " length=" + std::to_string(length) +
         " kappa_start=" + std::to_string(k0) + " kappa_end=" + std::to_string(k1);
}

// kSeriesRatioLimit[T] = 1e-17^(1/(T+1)): a series whose terms fall by a ratio r is
// truncated after degree T with a tail below 1e-17 of its first term when r is at most this.
const std::array<double, 64> kSeriesRatioLimit = [] {
  std::array<double, 64> limit{};
  for (std::size_t t = 0; t < limit.size(); ++t) limit[t] = std::pow(1e-17, 1.0 / (t + 1.0));
  return limit;
}();

// cos and sin of a small angle (|a| <= kSeriesMaxTurning) by Taylor polynomials in
// a^2 (terms to a^12 and a^11: the next are below 1e-17 there).
inline void smallSinCos(double a, double& c, double& s) {
  constexpr double c2 = -1.0 / 2, c4 = 1.0 / 24, c6 = -1.0 / 720, c8 = 1.0 / 40320, c10 = -1.0 / 3628800,
                   c12 = 1.0 / 479001600;
  constexpr double s3 = -1.0 / 6, s5 = 1.0 / 120, s7 = -1.0 / 5040, s9 = 1.0 / 362880, s11 = -1.0 / 39916800;
  const double a2 = a * a;
  c = 1.0 + a2 * (c2 + a2 * (c4 + a2 * (c6 + a2 * (c8 + a2 * (c10 + a2 * c12)))));
  s = a * (1.0 + a2 * (s3 + a2 * (s5 + a2 * (s7 + a2 * (s9 + a2 * s11)))));
}

// The same for |a| <= kSimpsonTurning / 2 (a Simpson panel's midpoint): terms to a^6
// and a^5 suffice (the next are below 1e-20 there).
inline void tinySinCos(double a, double& c, double& s) {
  constexpr double c2 = -1.0 / 2, c4 = 1.0 / 24, c6 = -1.0 / 720;
  constexpr double s3 = -1.0 / 6, s5 = 1.0 / 120;
  const double a2 = a * a;
  c = 1.0 + a2 * (c2 + a2 * (c4 + a2 * c6));
  s = a * (1.0 + a2 * (s3 + a2 * s5));
}

// v turned by the angle whose cosine and sine are c and s.
inline Vec2 rotated(const Vec2& v, double c, double s) { return {c * v.x() - s * v.y(), s * v.x() + c * v.y()}; }

}  // namespace

void CurveSamples::clear() {
  s.clear();
  point.clear();
  tangent.clear();
  theta.clear();
  kappa.clear();
}

void CurveSamples::reserve(std::size_t n) {
  s.reserve(n);
  point.reserve(n);
  tangent.reserve(n);
  theta.reserve(n);
  kappa.reserve(n);
}

LaSegment::LaSegment(double alpha, double length, Vec2 start, double theta0,
                     double kappa_start, double kappa_end)
    : alpha_(alpha), length_(length), start_(start), theta0_(theta0),
      kappa_start_(kappa_start), kappa_end_(kappa_end) {
  auto fail = [&](const std::string& why) {
    throw std::invalid_argument("LA segment: " + why + " (" +
                                describe(alpha, length, kappa_start, kappa_end) + ")");
  };
  if (std::isnan(alpha)) fail("alpha is NaN");
  if (!(std::isfinite(length) && length > 0.0)) fail("length must be positive and finite");
  if (!allFinite(start) || !std::isfinite(theta0)) fail("start or theta0 not finite");
  if (!std::isfinite(kappa_start) || !std::isfinite(kappa_end)) fail("curvature not finite");
  if (kappa_start * kappa_end < 0.0) fail("end curvatures of opposite sign");

  series_[0] = kappa_series_[0] = 1.0;  // the circle's turning is exactly kappa * tau
  const double a0 = std::abs(kappa_start), a1 = std::abs(kappa_end);
  sign_ = (kappa_start + kappa_end > 0.0) ? 1.0 : (kappa_start + kappa_end < 0.0 ? -1.0 : 0.0);

  if (std::isinf(alpha) || a0 == a1) {
    if (a0 != a1) fail("alpha = inf (circle) needs equal end curvatures");
    law_ = Law::kConstant;
    kappa_ref_ = a0;
    return;
  }
  if ((a0 == 0.0 || a1 == 0.0) && !(alpha < 0.0))
    fail("a zero end curvature (inflection end) needs alpha < 0");

  if (alpha == 0.0) {
    law_ = Law::kExponential;
    for (int k = 1; k <= kSeriesTerms; ++k) series_[k] = -series_[k - 1] / (k + 1.0);
    kappa_series_[0] = 1.0;  // e^-x
    for (int k = 1; k <= kSeriesTerms; ++k) kappa_series_[k] = -kappa_series_[k - 1] / k;
    kappa_ref_ = a0;
    growth_ = std::log(a0 / a1) / length;  // log rho grows by log(rho1/rho0) over L
    return;
  }
  law_ = Law::kPower;
  exponent_ = 1.0 - 1.0 / alpha;
  series_rate_ = std::max({1.0, std::abs(exponent_), std::abs(1.0 / alpha)});
  for (int k = 1; k <= kSeriesTerms; ++k) series_[k] = series_[k - 1] * (exponent_ - k) / (k + 1.0);
  kappa_series_[0] = 1.0;  // binomial series of (1 + x)^(-1/alpha)
  for (int k = 1; k <= kSeriesTerms; ++k) kappa_series_[k] = kappa_series_[k - 1] * (-1.0 / alpha - (k - 1)) / k;
  if (a0 > 0.0) {
    kappa_ref_ = a0;
    v0_ = 1.0;
    v1_ = (a1 == 0.0) ? 0.0 : std::exp(alpha * std::log(a0 / a1));
    if (!std::isfinite(v1_)) fail("alpha too large for this curvature ratio (rho^alpha overflows)");
    dv_ = (v1_ - 1.0) / length;
  } else {
    kappa_ref_ = a1;
    v0_ = 0.0;
    v1_ = 1.0;
    dv_ = 1.0 / length;
  }
}

double LaSegment::v(double s) const {
  const double u = s / length_;
  if (v0_ == 0.0) return u;
  // Written from the end that keeps the digits: near v1 << 1 the start form 1 + (v1-1)u
  // would round v1 away at u = 1.
  return v1_ >= 0.5 ? 1.0 + (v1_ - 1.0) * u : (1.0 - u) + v1_ * u;
}

double LaSegment::logV(double s) const {
  if (v0_ == 1.0 && v1_ >= 0.5) return std::log1p((v1_ - 1.0) * (s / length_));
  return std::log(v(s));
}

LaSegment LaSegment::arc(double length, Vec2 start, double theta0, double kappa) {
  return LaSegment(std::numeric_limits<double>::infinity(), length, start, theta0, kappa, kappa);
}

LaSegment LaSegment::withTurning(double alpha, double turning, Vec2 start, double theta0, double kappa_start,
                                 double kappa_end) {
  const double unit = std::abs(LaSegment(alpha, 1.0, Vec2::Zero(), 0.0, kappa_start, kappa_end).turning());
  if (!(unit > 0.0) || !(std::abs(turning) > 0.0))
    throw std::invalid_argument("LaSegment::withTurning: the law or the turning is zero");
  return LaSegment(alpha, std::abs(turning) / unit, start, theta0, kappa_start, kappa_end);
}

double LaSegment::kappa(double s) const {
  switch (law_) {
    case Law::kConstant:
      return kappa_start_;
    case Law::kExponential:
      return sign_ * kappa_ref_ * std::exp(-growth_ * s);
    case Law::kPower:
      return sign_ * kappa_ref_ * std::exp(-logV(s) / alpha_);
  }
  return 0.0;
}

double LaSegment::dkappa(double s) const {
  switch (law_) {
    case Law::kConstant:
      return 0.0;
    case Law::kExponential:
      return -growth_ * kappa(s);
    case Law::kPower:
      return sign_ * kappa_ref_ * (-1.0 / alpha_) * std::pow(std::max(v(s), 0.0), -1.0 / alpha_ - 1.0) * dv_;
  }
  return 0.0;
}

double LaSegment::unitTurning(double s) const {
  switch (law_) {
    case Law::kConstant:
      return s;
    case Law::kExponential:
      return -std::expm1(-growth_ * s) / growth_;
    case Law::kPower:
      if (v0_ == 0.0) return std::pow(v(s), exponent_) / (exponent_ * dv_);
      // integral of v(t)^(-1/alpha) dt with v(0) = 1, written to stay exact as dv -> 0
      {
        const double y = logV(s);
        return exponent_ == 0.0 ? y / dv_ : std::expm1(exponent_ * y) / (exponent_ * dv_);
      }
  }
  return 0.0;
}

double LaSegment::theta(double s) const { return theta0_ + sign_ * kappa_ref_ * unitTurning(s); }

void LaSegment::thetaKappa(double s, double& th, double& k) const {
  if (law_ == Law::kPower && v0_ == 0.0) {  // inflection start: both from log v (-inf at s = 0)
    const double y = std::log(v(s));
    th = theta0_ + sign_ * kappa_ref_ * std::exp(exponent_ * y) / (exponent_ * dv_);
    k = sign_ * kappa_ref_ * std::exp(-y / alpha_);
    return;
  }
  if (law_ != Law::kPower) {
    th = theta(s);
    k = kappa(s);
    return;
  }
  const double y = logV(s);  // shared by both closed forms
  th = theta0_ + sign_ * kappa_ref_ * (exponent_ == 0.0 ? y / dv_ : std::expm1(exponent_ * y) / (exponent_ * dv_));
  k = sign_ * kappa_ref_ * std::exp(-y / alpha_);
}

Vec2 LaSegment::integratePositionAdaptive(double s0, double s1, double abs_tol) const {
  auto tangent_at = [this](double t) -> Vec2 { return unitVector(theta(t)); };
  return integrateAdaptive(tangent_at, s0, s1, abs_tol).value;
}

// (inline: the sampler's hot loop calls it)
inline Vec2 LaSegment::PanelStep::simpsonDelta(double h, const Vec2& tangent_start, const Vec2& tangent_end) const {
  return (h / 6.0) * (tangent_start + 4.0 * rotated(tangent_start, mid_cos, mid_sin) + tangent_end);
}

Vec2 LaSegment::integratePositionInSteps(double s0, double s1, double abs_tol) const {
  // Each step starts from the exact theta and kappa at its start and is the longest that
  // the series holds on, halving from twice the last one (the first from half the panel,
  // which the caller found too long): a few steps where adaptive quadrature evaluated the
  // tangent 30 to 70 times (29% of the paper-only fit of a 1,000-point stroke, in the
  // alpha search's samples). Steps shorter than kMinStep of the interval (towards a cusp)
  // leave the rest to the adaptive rule.
  constexpr double kMinStep = 1.0 / 256.0;
  Vec2 sum = Vec2::Zero();
  double a = s0, h = 0.5 * (s1 - s0);
  while (a < s1) {
    double th, k;
    thetaKappa(a, th, k);
    const Vec2 tangent = unitVector(th);
    PanelStep step;
    for (h = std::min(h, s1 - a); !panelBySeries(a, h, k, tangent, step); h *= 0.5)
      if (h < kMinStep * (s1 - s0)) return sum + integratePositionAdaptive(a, s1, abs_tol * (s1 - a) / (s1 - s0));
    if (step.simpson) {
      double c, sn;
      smallSinCos(step.turning, c, sn);
      sum += step.simpsonDelta(h, tangent, rotated(tangent, c, sn));
    } else {
      sum += step.delta;
    }
    a = h >= s1 - a ? s1 : a + h;
    h *= 2.0;
  }
  return sum;
}

Vec2 LaSegment::position(double s, double relative_tolerance) const {
  if (s == 0.0) return start_;
  if (law_ == Law::kConstant) {  // exact chord of a circular arc (or a line)
    const double half = 0.5 * kappa_start_ * s;
    const double chord = (half == 0.0) ? s : 2.0 * std::sin(half) / kappa_start_;
    return start_ + chord * unitVector(theta0_ + half);
  }
  const double abs_tol = relative_tolerance * length_;
  if (law_ == Law::kPower && (v0_ == 0.0 || v1_ == 0.0) && s > 0.0 && s <= length_) {
    // Next to an inflection end kappa ~ r^(-1/alpha) (r the distance from it) is
    // singular, and adaptive quadrature bisects towards it some 20 times at 1e-14.
    // Within kInflectionSeriesMaxTurning of the inflection the series of
    // inflectionOffset is exact up to rounding; beyond, the tangent is smooth on the
    // scale of the distance from the inflection and the adaptive rule needs few panels.
    const double reach = inflectionSeriesReach();
    if (v0_ == 0.0) {
      const double r = std::min(s, reach);
      const Vec2 near = start_ + inflectionOffset(r, theta0_, sign_);
      return r < s ? near + integratePositionAdaptive(r, s, abs_tol) : near;
    }
    const double split = std::max(length_ - reach, 0.0);
    if (split < s) {  // the series backwards from the end, as in panelNearInflection
      const double heading = theta(length_) + std::numbers::pi, r = length_ - s;
      const Vec2 delta = (r > 0.0 ? inflectionOffset(r, heading, -sign_) : Vec2::Zero()) -
                         inflectionOffset(length_ - split, heading, -sign_);
      return start_ + (split > 0.0 ? integratePositionAdaptive(0.0, split, abs_tol) : Vec2::Zero()) + delta;
    }
  }
  return start_ + integratePositionAdaptive(0.0, s, abs_tol);
}

double LaSegment::inflectionSeriesReach() const {
  // The turning from the inflection, kappa_ref L (r/L)^e / e (see inflectionOffset),
  // equals kInflectionSeriesMaxTurning at r = L (e kInflectionSeriesMaxTurning / (kappa_ref L))^(1/e).
  return length_ * std::exp(std::log(exponent_ * kInflectionSeriesMaxTurning / (kappa_ref_ * length_)) / exponent_);
}

LaSegment LaSegment::reversed() const {
  return LaSegment(alpha_, length_, end(), theta(length_) + std::numbers::pi, -kappa_end_,
                   -kappa_start_);
}

bool LaSegment::panelBySeries(double s0, double h, double kappa_start, const Vec2& tangent_start,
                              PanelStep& step) const {
  // Turning over [s0, s0 + tau] is kappa(s0) * tau * G(x), x the law's local variable
  // proportional to tau, G(x) = sum_k g_k x^k with g_0 = 1 and a two-term recurrence:
  //   power law:       x = dv tau / v(s0), G = ((1+x)^e - 1)/(e x), g_k = g_{k-1}(e-k)/(k+1)
  //   exponential law: x = g tau,          G = (1 - e^-x)/x,       g_k = -g_{k-1}/(k+1)
  // and the curvature at s0 + h is kappa(s0) times (1+x)^(-1/alpha), resp. e^-x.
  double x_end = 0.0, ratio_bound = 0.0;
  if (law_ == Law::kPower) {
    const double v_start = v(s0);
    if (!(v_start > 0.0)) return false;
    x_end = dv_ * h / v_start;
    ratio_bound = std::abs(x_end) * series_rate_;
  } else if (law_ == Law::kExponential) {
    x_end = growth_ * h;
    ratio_bound = std::abs(x_end);
  }
  if (ratio_bound > kSeriesMaxRatio) return false;

  const double k_h = kappa_start * h;  // turning of the panel to first order
  // enough terms that the tail is below 1e-17 of the panel length (and relative): with
  // |k_h| <= 1 (a larger panel turning fails the kSeriesMaxTurning test below anyway)
  int terms = 0;
  while (terms < kSeriesTerms && ratio_bound > kSeriesRatioLimit[terms]) ++terms;
  auto turningAt = [&](double t) {  // turning over [s0, s0 + t h]
    const double x = x_end * t;
    double g = series_[terms];
    for (int k = terms - 1; k >= 0; --k) g = g * x + series_[k];
    return k_h * t * g;
  };
  // G at x_end and x_end/2 and the curvature ratio: three independent Horner chains in
  // one loop (each is latency-bound alone).
  const double x_half = 0.5 * x_end;
  double g_end = series_[terms], g_half = series_[terms], ratio = kappa_series_[terms];
  for (int k = terms - 1; k >= 0; --k) {
    g_end = g_end * x_end + series_[k];
    g_half = g_half * x_half + series_[k];
    ratio = ratio * x_end + kappa_series_[k];
  }
  step.turning = k_h * g_end;
  if (std::abs(step.turning) > kSeriesMaxTurning) return false;
  step.kappa_ratio = ratio;

  step.simpson = std::abs(step.turning) <= kSimpsonTurning;
  if (step.simpson) {  // the caller completes delta with the end tangent
    tinySinCos(0.5 * k_h * g_half, step.mid_cos, step.mid_sin);
    return true;
  }
  const auto& rule = gaussLegendre<4>();
  double cx = 0.0, cy = 0.0;
  for (int j = 0; j < 4; ++j) {
    double c, sn;
    smallSinCos(turningAt(rule.node[j]), c, sn);
    cx += rule.weight[j] * c;
    cy += rule.weight[j] * sn;
  }
  const double ct = tangent_start.x(), st = tangent_start.y();
  step.delta = h * Vec2(ct * cx - st * cy, st * cx + ct * cy);
  return true;
}

Vec2 LaSegment::inflectionOffset(double r, double heading, double turn_sign) const {
  // Within distance r of the inflection point the turning from it is
  // T(t) = kappa_ref L (t/L)^e / e (unitTurning with v = t/L), so with t = r w
  //   integral_0^r e^{i (heading + turn_sign T(t))} dt = r e^{i heading} sum_k (i turn_sign T(r))^k / (k! (k e + 1)),
  // the series of inflection_segment.cpp, exact up to rounding.
  const double turning = turn_sign * kappa_ref_ * length_ * std::exp(exponent_ * std::log(r / length_)) / exponent_;
  double cr = 1.0, ci = 0.0, sr = 0.0, si = 0.0;  // (i turning)^k / k!, the sum
  for (int k = 0; k < kInflectionSeriesMaxTerms && std::abs(cr) + std::abs(ci) > 1e-18; ++k) {
    const double w = 1.0 / (k * exponent_ + 1.0);
    sr += cr * w;
    si += ci * w;
    const double scale = turning / (k + 1);
    const double next_r = -ci * scale, next_i = cr * scale;
    cr = next_r;
    ci = next_i;
  }
  const double c = std::cos(heading), sn = std::sin(heading);
  return r * Vec2(c * sr - sn * si, sn * sr + c * si);
}

bool LaSegment::panelNearInflection(double s0, double s1, Vec2& delta) const {
  if (law_ != Law::kPower || !(v0_ == 0.0 || v1_ == 0.0)) return false;
  const bool at_start = (v0_ == 0.0);
  const double r_far = at_start ? s1 : length_ - s0;  // the panel's far end from the inflection
  const double turning_far = kappa_ref_ * length_ * std::exp(exponent_ * std::log(r_far / length_)) / exponent_;
  if (!(turning_far <= kInflectionSeriesMaxTurning)) return false;
  if (at_start) {
    delta = inflectionOffset(s1, theta0_, sign_) - (s0 > 0.0 ? inflectionOffset(s0, theta0_, sign_) : Vec2::Zero());
  } else {
    // measured backwards from the end, where the tangent angle is theta(L)
    const double theta_end = theta(length_), r1 = length_ - s1;
    delta = inflectionOffset(length_ - s0, theta_end + std::numbers::pi, -sign_) -
            (r1 > 0.0 ? inflectionOffset(r1, theta_end + std::numbers::pi, -sign_) : Vec2::Zero());
    delta = -delta;
  }
  return true;
}

void LaSegment::sample(int n, CurveSamples& out, double s_offset, double relative_tolerance) const {
  if (n < 2) throw std::invalid_argument("LaSegment::sample: need at least 2 samples");
  const double h = length_ / (n - 1);
  const double panel_tol = relative_tolerance * length_ / (n - 1);
  // theta, kappa and the tangent are carried from sample to sample by the panel series,
  // relative to the last exact evaluation (every kResyncSamples samples, or sooner if
  // the turning since then would leave smallSinCos's range), so rounding cannot pile up.
  Vec2 p = start_;
  double th = theta0_, k = kappa_start_;
  double th_exact = theta0_, k_exact = kappa_start_, turned = 0.0, ratio = 1.0;
  Vec2 tangent = unitVector(theta0_), tangent_exact = tangent;
  int since_exact = 0;
  for (int i = 0; i < n; ++i) {
    const double s = (i == n - 1) ? length_ : i * h;
    if (i > 0) {
      const double s_prev = (i - 1) * h;
      PanelStep step;
      const bool series = panelBySeries(s_prev, s - s_prev, k, tangent, step);
      const Vec2 tangent_start = tangent;
      ++since_exact;
      if (series && i < n - 1 && since_exact < kResyncSamples &&
          std::abs(turned + step.turning) <= kSeriesMaxTurning) {
        turned += step.turning;
        ratio *= step.kappa_ratio;
        th = th_exact + turned;
        k = k_exact * ratio;
        double c, sn;
        smallSinCos(turned, c, sn);
        tangent = rotated(tangent_exact, c, sn);
      } else {
        thetaKappa(s, th, k);
        tangent = unitVector(th);
        th_exact = th;
        k_exact = k;
        tangent_exact = tangent;
        turned = 0.0;
        ratio = 1.0;
        since_exact = 0;
      }
      Vec2 delta;
      if (series && step.simpson) {
        delta = step.simpsonDelta(s - s_prev, tangent_start, tangent);
      } else if (series) {
        delta = step.delta;
      } else if (!panelNearInflection(s_prev, s, delta)) {
        delta = integratePositionInSteps(s_prev, s, panel_tol);
      }
      p += delta;
    }
    out.s.push_back(s_offset + s);
    out.point.push_back(p);
    out.tangent.push_back(tangent);
    out.theta.push_back(th);
    out.kappa.push_back(k);
  }
}

CurveSamples LaSegment::sample(int n) const {
  CurveSamples out;
  out.reserve(static_cast<std::size_t>(std::max(n, 0)));
  sample(n, out);
  return out;
}

}  // namespace la
