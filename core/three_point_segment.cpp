#include "core/three_point_segment.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "core/quadrature.h"
#include "core/root_finding.h"

namespace la {
namespace {

// Composite Gauss-Legendre in tau = theta/theta_d with kPanelNodes nodes per panel.
// rho(tau) = (1 + A tau)^p has a branch point at tau* = -1/A outside [0, 1]; a panel
// of width w whose near end is at distance delta >= w / kSingularWidthRatio from it
// has a Bernstein ellipse parameter >= 2.8, so 16 nodes give ~1e-15 relative error.
// Panels also keep (rate of log rho) * width <= kMaxLogRhoChange so that the nearly
// exponential rho of alpha ~ 1 is resolved. Both constants from the standard GL error
// bound rho_B^(-2n); checked against the adaptive rule in three_point_segment_test.
constexpr int kPanelNodes = 16;
constexpr double kSingularWidthRatio = 3.0;
constexpr double kMaxLogRhoChange = 8.0;
// The exponentials in the law overflow past ~709; keep |alpha m| and |(alpha-1) m| below.
constexpr double kMaxExponent = 600.0;
// Panels are built this much narrower than allowed, so the layout stays valid while
// Newton moves m towards the singular end and is rebuilt less often.
constexpr double kLayoutMargin = 0.6;
constexpr int kLogBaseNodes = 24;
constexpr double kLogBasePanelChange = 12.0;
// The moment series (StandardForm::evalMoments): terms below kMomentNegligible of the
// first are dropped (|w_k| < pi^k/k!, so ~35 terms at theta_d ~ pi, fewer when small);
// the recurrence's bounded error must stay below kMomentTolerance of |E| (units of
// kRounding, the double epsilon) or the quadrature is used instead.
constexpr int kMomentMaxTerms = 64;
constexpr double kMomentNegligible = 1e-18;
constexpr double kMomentTolerance = 1e-14;
constexpr double kRounding = 1.1e-16;

struct StandardEval {
  Vec2 end = Vec2::Zero();     // E(m)
  Vec2 d_end = Vec2::Zero();   // dE/dm
  double length = 0.0;         // S(m) = integral of rho dtheta
  double d_length = 0.0;       // dS/dm
  double chordAngle() const { return std::atan2(end.y(), end.x()); }
  double dChordAngle() const { return cross(end, d_end) / end.squaredNorm(); }
};

/// The standard-form curve of one (alpha, theta_d), evaluated for any shape m on a
/// panel layout that is rebuilt only when m moves out of the layout's safe range, so
/// cos/sin of the nodes are reused across Newton iterations.
class StandardForm {
 public:
  StandardForm(double alpha, double theta_d) : alpha_(alpha), theta_d_(theta_d) {}

  StandardEval eval(double m) {
    const Law law = lawAt(m);
    // One panel of fixed nodes (cos/sin reused) when rho is tame in tau; otherwise
    // the log-base form, whose integrand is smooth however close the branch point is.
    if (!law.unit_alpha && !singlePanelValid(law)) {
      StandardEval out;
      if (evalMoments(law, out)) return out;
      return evalLogBase<kLogBaseNodes>(law, kLogBasePanelChange);
    }
    if (!layoutValid(law)) buildLayout(law);
    double ex = 0, ey = 0, dx = 0, dy = 0, len = 0, dlen = 0;
    for (std::size_t k = 0; k < tau_.size(); ++k) {
      const double t = tau_[k];
      double rho, drho;
      if (law.unit_alpha) {
        rho = std::exp(m * t);
        drho = t * rho;
      } else {
        // b = 1 + A tau; near b -> 0 (A -> -1) written from the end so no digits cancel
        const bool far = law.a >= -0.5;
        const double b = far ? 1.0 + law.a * t : law.b_end - law.a * tau_c_[k];
        rho = std::exp(law.p * (far ? std::log1p(law.a * t) : std::log(b)));
        drho = rho * t * law.b_end / b;  // d rho/dm = rho tau (1 + A) / b
      }
      const double wr = weight_[k] * rho, wd = weight_[k] * drho;
      ex += wr * cos_[k];
      ey += wr * sin_[k];
      dx += wd * cos_[k];
      dy += wd * sin_[k];
      len += wr;
      dlen += wd;
    }
    StandardEval out;
    out.end = theta_d_ * Vec2(ex, ey);
    out.d_end = theta_d_ * Vec2(dx, dy);
    out.length = theta_d_ * len;
    out.d_length = theta_d_ * dlen;
    return out;
  }

 private:
  // rho(tau) = b(tau)^p with b = 1 + A tau, A = exp((alpha-1) m) - 1, p = 1/(alpha-1).
  // b vanishes at the branch point tau* = -1/A, outside [0, 1]: before the start
  // (A > 0) or past the end (A < 0), at `distance` from that end of the interval.
  enum class Side { kNone, kStart, kEnd };
  struct Law {
    bool unit_alpha = false;
    double a = 0.0, p = 0.0, b_end = 1.0, m = 0.0;
    Side side = Side::kNone;
    double distance = INFINITY;
  };
  Law lawAt(double m) const {
    Law law;
    law.m = m;
    law.unit_alpha = (alpha_ == 1.0);
    if (law.unit_alpha) return law;
    law.a = std::expm1((alpha_ - 1.0) * m);
    law.b_end = std::exp((alpha_ - 1.0) * m);
    law.p = 1.0 / (alpha_ - 1.0);
    if (law.a > 0.0) {
      law.side = Side::kStart;
      law.distance = 1.0 / law.a;
    } else if (law.a < 0.0) {
      law.side = Side::kEnd;
      law.distance = law.b_end / -law.a;  // (1 + A)/|A| without cancellation
    }
    return law;
  }
  // Widest panel allowed at distance delta from the branch point: |b| = |A| delta there,
  // so the rate of log rho is |p| / delta (|m| for alpha = 1).
  static double maxWidth(const Law& law, double delta) {
    if (law.unit_alpha) return law.m == 0.0 ? INFINITY : kMaxLogRhoChange / std::abs(law.m);
    return delta * std::min(kSingularWidthRatio, kMaxLogRhoChange / std::abs(law.p));
  }
  // Near the branch point, for p > -2 (alpha < 1/2 or alpha > 1), by moments instead of
  // quadrature: no exp/log/sin per node. Measure sigma from the end of [0, 1] where b is
  // larger (sigma = tau if B = 1 + A < 1, else 1 - tau) and write b = b_max (1 - a sigma)
  // with c = b_min/b_max = e^{-|(alpha-1) m|} and a = 1 - c. With the moments
  //   I_k = integral_0^1 sigma^k (1 - a sigma)^p dsigma,  J_k = the same with p - 1,
  // which obey (integrate d/dsigma [sigma^k (1 - a sigma)^(p+1)] by parts, and use
  // a sigma = 1 - (1 - a sigma))
  //   I_0 = (1 - c^(p+1)) / (a (p + 1)),  I_k = (k I_{k-1} - c^(p+1)) / (a (k + p + 1)),
  //   J_0 = (1 - c^p) / (a p),            J_{k+1} = (J_k - I_k) / a,
  // and d rho/dm = tau B b^(p-1), expanding e^{i theta_d tau} gives (w_k = (+-i theta_d)^k/k!)
  //   B < 1:  E = theta_d sum w_k I_k,                   dE/dm = theta_d B sum w_k J_{k+1},
  //   B > 1:  E = theta_d e^m e^{i theta_d} sum w_k I_k, dE/dm = theta_d e^m e^{i theta_d} sum w_k (J_k - J_{k+1})
  // (the lengths are the k = 0 terms; for B > 1 the sign of w_k's i is -). The forward
  // recurrence subtracts c^(p+1) from k I_{k-1}: harmless near the branch point (c
  // small), ruinous near the circle (c ~ 1). Its error growth is tracked term by term,
  // and the call fails (the caller integrates instead) when the bound exceeds
  // kMomentTolerance of |E|. (dE/dm only steers Newton and need not be as exact.)
  bool evalMoments(const Law& law, StandardEval& out) const {
    const double p = law.p;
    const double log_b = (alpha_ - 1.0) * law.m;  // log B
    if (!(p > -2.0) || log_b == 0.0) return false;
    const double log_c = -std::abs(log_b);
    const double a = -std::expm1(log_c);
    const double c_p1 = std::exp((p + 1.0) * log_c);
    // (1 - c^q) / q = -log c expm1(q log c) / (q log c), exact also as q -> 0
    auto oneMinusPowerOver = [&](double q) {
      const double x = q * log_c;
      return x == 0.0 ? -log_c : -log_c * std::expm1(x) / x;
    };
    double i_k = oneMinusPowerOver(p + 1.0) / a;
    double j_k = oneMinusPowerOver(p) / a;
    const double i_0 = i_k, j_0 = j_k;
    const double omega = log_b > 0.0 ? -theta_d_ : theta_d_;
    double wr = 1.0, wi = 0.0;  // w_k
    double fr = i_k, fi = 0.0, gr = 0.0, gi = 0.0;
    double growth = 1.0;        // bound on the relative error of I_k, in units of rounding
    double error = i_k;         // sum of |w_k| I_k growth_k
    double j_1 = 0.0;
    for (int k = 1; k < kMomentMaxTerms; ++k) {
      // dE/dm term of index k - 1 (weights still w_{k-1}), from J_k = (J_{k-1} - I_{k-1}) / a
      const double j_next = (j_k - i_k) / a;
      const double dj = log_b > 0.0 ? j_k - j_next : j_next;
      gr += wr * dj;
      gi += wi * dj;
      if (k == 1) j_1 = j_next;
      j_k = j_next;
      const double ki = k * i_k, num = ki - c_p1;
      if (!(num > 0.0)) return false;  // cancelled away: the recurrence is no use here
      growth = ki / num * (growth + 1.0);
      i_k = num / (a * (k + p + 1.0));
      const double scale = omega / k;  // w_k = w_{k-1} i omega / k
      const double nr = -wi * scale, ni = wr * scale;
      wr = nr;
      wi = ni;
      fr += wr * i_k;
      fi += wi * i_k;
      const double size = (std::abs(wr) + std::abs(wi)) * i_k;
      error += size * growth;
      if (size < kMomentNegligible * i_0) break;
    }
    const double f_norm = std::hypot(fr, fi);
    if (!(error * kRounding <= kMomentTolerance * f_norm)) return false;
    if (log_b < 0.0) {
      const double b = std::exp(log_b);
      out.end = theta_d_ * Vec2(fr, fi);
      out.d_end = theta_d_ * b * Vec2(gr, gi);
      out.length = theta_d_ * i_0;
      out.d_length = theta_d_ * b * j_1;
    } else {  // times e^m e^{i theta_d}
      const double scale = theta_d_ * std::exp(law.m), ct = std::cos(theta_d_), st = std::sin(theta_d_);
      out.end = scale * Vec2(ct * fr - st * fi, st * fr + ct * fi);
      out.d_end = scale * Vec2(ct * gr - st * gi, st * gr + ct * gi);
      out.length = scale * i_0;
      out.d_length = scale * (j_0 - j_1);
    }
    return true;
  }

  // In l = log b (b = 1 + A tau) the integrals become
  //   E = theta_d / A  integral_0^{(alpha-1)m} e^{(p+1) l} e^{i theta_d tau(l)} dl,  tau = (e^l - 1)/A,
  //   dE/dm = theta_d (1+A)/A integral e^{p l} tau e^{i theta_d tau} dl,
  // an entire integrand: the singularity of b^p at b = 0 is pushed to l = -inf. On each
  // panel the exponents (and theta) change by at most kLogBasePanelChange, which
  // kLogBaseNodes nodes resolve to ~1e-17 (GL error ~ (change/2)^(2n) / (2n)!; 16 nodes
  // lost ~1e-13 at |m| = 30 and 1e-7 in m on three_point_segment_test's
  // RoundTripNearTheBranchPoint with the moment path off). Used where the moment
  // series (evalMoments) does not apply.
  template <int Nodes>
  StandardEval evalLogBase(const Law& law, double panel_change) const {
    const double range = (alpha_ - 1.0) * law.m;  // log(1 + A), exactly
    // d/dl of the exponents is at most |p + 1| (and 1 for tau); of theta it is
    // theta_d e^l / |A|, large only near the top of l's range. Panels are graded from
    // there: each keeps (exponent rate + theta rate at its top) * width at most
    // kLogBasePanelChange.
    const double exp_rate = std::max({std::abs(law.p + 1.0), std::abs(law.p), 1.0});
    const double lo = std::min(0.0, range), hi = std::max(0.0, range);
    const auto& rule = gaussLegendre<Nodes>();
    double ex = 0, ey = 0, dx = 0, dy = 0, len = 0, dlen = 0;
    for (double top = hi; top > lo;) {
      const double theta_rate = theta_d_ * std::exp(top) / std::abs(law.a);
      const double bottom = std::max(lo, top - panel_change / (exp_rate + theta_rate));
      const double width = top - bottom;
      for (int k = 0; k < Nodes; ++k) {
        const double l = bottom + width * rule.node[k];
        const double em1 = std::expm1(l);
        const double tau = em1 / law.a;
        const double w = width * rule.weight[k] * std::exp(law.p * l);  // rho dl at the node
        const double wr = w * (1.0 + em1);                              // rho db = rho e^l dl
        const double c = std::cos(theta_d_ * tau), sn = std::sin(theta_d_ * tau);
        ex += wr * c;
        ey += wr * sn;
        dx += w * tau * c;
        dy += w * tau * sn;
        len += wr;
        dlen += w * tau;
      }
      top = bottom;
    }
    const double scale = theta_d_ * (range > 0.0 ? 1.0 : -1.0) / law.a;  // orientation of dl, and 1/A
    StandardEval out;
    out.end = scale * Vec2(ex, ey);
    out.d_end = scale * law.b_end * Vec2(dx, dy);
    out.length = scale * len;
    out.d_length = scale * law.b_end * dlen;
    return out;
  }
  bool singlePanelValid(const Law& law) const {
    return maxWidth(law, law.distance) >= 1.0;
  }

  bool layoutValid(const Law& law) const {
    if (cuts_.empty()) return false;
    for (std::size_t i = 0; i + 1 < cuts_.size(); ++i) {
      // cuts_ are distances from the end the layout was graded towards
      const double lo = cuts_[i], hi = cuts_[i + 1];
      const double near = (law.side == layout_side_ || law.side == Side::kNone) ? lo : 1.0 - hi;
      if (hi - lo > maxWidth(law, law.distance + near)) return false;
    }
    return true;
  }
  void buildLayout(const Law& law) {
    // March from the end nearest the branch point (where rho varies fastest), each
    // panel as wide as allowed: the widths grow geometrically.
    constexpr int kMaxPanels = 400;  // past ~1e-200 of the interval; never reached for |m| <= 30
    layout_side_ = law.side;
    cuts_.assign(1, 0.0);
    double x = 0.0;
    while (x < 1.0) {
      const double w = kLayoutMargin * maxWidth(law, law.distance + x);
      x = (w >= 1.0 - x || static_cast<int>(cuts_.size()) >= kMaxPanels) ? 1.0 : x + w;
      cuts_.push_back(x);
    }
    const auto& rule = gaussLegendre<kPanelNodes>();
    tau_.clear();
    tau_c_.clear();
    weight_.clear();
    cos_.clear();
    sin_.clear();
    const std::size_t nodes = kPanelNodes * (cuts_.size() - 1);  // one allocation each
    for (auto* v : {&tau_, &tau_c_, &weight_, &cos_, &sin_}) v->reserve(nodes);
    const bool from_end = (law.side == Side::kEnd);
    for (std::size_t i = 0; i + 1 < cuts_.size(); ++i) {
      const double lo = cuts_[i], w = cuts_[i + 1] - cuts_[i];
      for (int k = 0; k < kPanelNodes; ++k) {
        const double x_node = lo + w * rule.node[k];  // distance from the marching end
        const double t = from_end ? 1.0 - x_node : x_node;
        tau_.push_back(t);
        tau_c_.push_back(from_end ? x_node : 1.0 - x_node);
        weight_.push_back(w * rule.weight[k]);
        const Vec2 u = unitVector(theta_d_ * t);
        cos_.push_back(u.x());
        sin_.push_back(u.y());
      }
    }
  }

  double alpha_, theta_d_;
  Side layout_side_ = Side::kNone;
  std::vector<double> cuts_, tau_, tau_c_, weight_, cos_, sin_;
};

double maxShape(double alpha, const ThreePointOptions& options) {
  return std::min(options.max_log_radius_ratio,
                  kMaxExponent / std::max({std::abs(alpha), std::abs(alpha - 1.0), 1.0}));
}

std::string rangeText(const ChordAngleRange& r) {
  return "(" + std::to_string(r.lo) + ", " + std::to_string(r.hi) + ") rad";
}

SegmentSolve badInput(SolveReport report) {
  SegmentSolve out;
  out.report = std::move(report);
  out.report.status = SolveStatus::kBadInput;
  return out;
}

// M(q) = integral_0^1 tau^q e^{i theta tau} dtau = sum_k (i theta)^k / (k! (k + q + 1))
// for q > -1, as (real, imaginary). The terms fall like theta^k / k!: for theta < pi
// they are below 1e-18 after ~35 terms; the largest is ~e^pi, so ~2 digits cancel at
// worst (the same series as inflection_segment.cpp's).
Vec2 powerMoment(double q, double theta) {
  constexpr int kMaxTerms = 60;
  constexpr double kNegligibleTerm = 1e-18;
  double cr = 1.0, ci = 0.0;  // (i theta)^k / k!
  Vec2 sum = Vec2::Zero();
  for (int k = 0; k < kMaxTerms && std::abs(cr) + std::abs(ci) >= kNegligibleTerm; ++k) {
    const double w = 1.0 / (k + q + 1.0);
    sum += Vec2(cr * w, ci * w);
    const double scale = theta / (k + 1);
    const double next_r = -ci * scale, next_i = cr * scale;
    cr = next_r;
    ci = next_i;
  }
  return sum;
}

std::complex<double> toComplex(const Vec2& v) { return {v.x(), v.y()}; }

}  // namespace

ChordAngleRange chordAngleLimits(double alpha, double theta_d) {
  // The limit shapes are powers of tau: for alpha > 1, rho -> const * tau^p as m -> +inf
  // (rho(0) -> 0); for alpha < 0, rho -> const * tau^p as m -> -inf (rho(0) -> inf,
  // integrable since p > -1: the inflection-start segment). So one limit is arg M(p)
  // and the other theta_d minus it (reversal: m -> -m, phi -> theta_d - phi). For
  // 0 <= alpha <= 1, tau^p is not integrable and the limits are 0 and theta_d.
  if (std::isnan(alpha) || !(theta_d > 0.0 && theta_d < std::numbers::pi)) return {};
  if (std::isinf(alpha)) return {0.5 * theta_d, 0.5 * theta_d};
  if (!(alpha < 0.0 || alpha > 1.0)) return {0.0, theta_d};
  const Vec2 moment = powerMoment(1.0 / (alpha - 1.0), theta_d);
  const double limit = std::atan2(moment.y(), moment.x());
  return alpha < 0.0 ? ChordAngleRange{limit, theta_d - limit} : ChordAngleRange{theta_d - limit, limit};
}

ChordAngleRange reachableChordAngles(double alpha, double theta_d, const ThreePointOptions& options) {
  if (std::isnan(alpha) || !(theta_d > 0.0 && theta_d < std::numbers::pi)) return {};
  if (std::isinf(alpha)) return {0.5 * theta_d, 0.5 * theta_d};
  StandardForm form(alpha, theta_d);
  const double m_max = maxShape(alpha, options);
  return {form.eval(-m_max).chordAngle(), form.eval(m_max).chordAngle()};
}

SegmentSolve solveThreePointSegment(double alpha, const Vec2& q0, const Vec2& q1, const Vec2& q2,
                                    const ThreePointOptions& options) {
  if (std::isnan(alpha)) {
    SolveReport r;
    r.message = "alpha is NaN";
    return badInput(r);
  }
  ControlTriangle tri;
  SolveReport check = analyzeTriangle(q0, q1, q2, tri);
  if (!check.usable()) return badInput(check);

  SegmentSolve out;
  out.theta_d = tri.theta_d;
  out.chord_angle = tri.chord_angle;
  if (tri.theta_d == 0.0) {  // collinear, in order: the straight line is every LA curve's limit
    out.segment = LaSegment::arc(tri.chord, q0, tri.heading, 0.0);
    out.shape = 0.0;
    out.report = {SolveStatus::kConverged, 0, 0.0, "collinear control points: straight line"};
    return out;
  }
  const double target = tri.chord_angle;
  const double theta_d = tri.theta_d;

  // Finished curve from the standard form: scale, rotate, mirror, translate.
  auto place = [&](double m, const StandardEval& e) {
    const double scale = tri.chord / e.end.norm();
    return LaSegment(alpha, scale * e.length, q0, tri.heading, tri.turn_sign / scale,
                     tri.turn_sign * std::exp(-m) / scale);
  };

  if (std::isinf(alpha)) {  // circle only: the isosceles triangle
    const double gap = std::abs(target - 0.5 * theta_d);
    constexpr double kIsoscelesTolerance = 1e-12;  // relative to theta_d
    if (gap > kIsoscelesTolerance * theta_d) {
      out.reachable = {0.5 * theta_d, 0.5 * theta_d};
      out.report = {SolveStatus::kInfeasible, 0, gap,
                    "alpha = inf is a circular arc: only isosceles triangles (chord angle " +
                        std::to_string(0.5 * theta_d) + " rad) are reachable"};
      return out;
    }
    const double kappa = 2.0 * std::sin(0.5 * theta_d) / tri.chord;
    out.segment = LaSegment::arc(theta_d / kappa, q0, tri.heading, tri.turn_sign * kappa);
    out.shape = 0.0;
    out.report = {SolveStatus::kConverged, 0, gap, "circular arc"};
    return out;
  }

  StandardForm form(alpha, theta_d);
  StandardEval last;
  // Newton on a logit of the chord angle, g = log((phi - lo) / (hi - phi)), with lo, hi
  // the limits of phi(m) for m -> -+inf: phi approaches them exponentially in m, so g
  // is nearly linear in m (slope ~|alpha| or |alpha - 1| at both ends) and Newton
  // converges quadratically from the start below; with (0, theta_d) instead it crawls
  // along the saturated ends (alpha = -3: 11 evaluations instead of 3). A target
  // outside (lo, hi) is unreachable; the plain logit then leads to that report.
  ChordAngleRange limits = chordAngleLimits(alpha, theta_d);
  if (!limits.contains(target)) limits = {0.0, theta_d};
  auto logit = [&](double phi) { return std::log((phi - limits.lo) / (limits.hi - phi)); };
  auto dlogit = [&](double phi) { return 1.0 / (phi - limits.lo) + 1.0 / (limits.hi - phi); };
  const double target_logit = logit(target);
  auto residual = [&](double m) {
    last = form.eval(m);
    const double phi = last.chordAngle();
    // rounding can put phi on a limit at the far end of the bracket: same sign there,
    // in the logit's units at the target
    if (!limits.contains(phi)) return std::pair{(phi - target) * dlogit(target), last.dChordAngle() * dlogit(target)};
    return std::pair{logit(phi) - target_logit, last.dChordAngle() * dlogit(phi)};
  };
  const double m_max = maxShape(alpha, options);
  const bool up = target > 0.5 * theta_d;  // chord angle grows with m; circle at m = 0
  const double lo = up ? 0.0 : -m_max, hi = up ? m_max : 0.0;
  RootOptions root_options;
  // |phi - target| <= chord_tolerance * theta_d to first order (dg/dphi >= 4 / theta_d)
  root_options.f_tol = options.chord_tolerance * theta_d * dlogit(target);
  root_options.x_tol = 1e-15;
  root_options.max_iterations = options.max_iterations;
  // Start: the quadratic Taylor model of g at the circle m = 0, in closed form:
  // log rho = m tau + (alpha-1) m^2 (tau - tau^2)/2 + O(m^3), so with M_k = powerMoment(k)
  // E ~ M_0, dE/dm ~ M_1, d2E/dm2 ~ (2-alpha) M_2 + (alpha-1) M_1 (times theta_d), and
  // phi' = Im(E'/E), phi'' = Im(E''/E - (E'/E)^2); dg/dphi is stationary at phi = theta_d/2.
  const std::complex<double> e0 = toComplex(powerMoment(0.0, theta_d)), e1 = toComplex(powerMoment(1.0, theta_d)),
                             e2 = (2.0 - alpha) * toComplex(powerMoment(2.0, theta_d)) + (alpha - 1.0) * e1;
  const std::complex<double> r1 = e1 / e0, r2 = e2 / e0;
  const double g1 = dlogit(0.5 * theta_d) * r1.imag(), g2 = dlogit(0.5 * theta_d) * (r2 - r1 * r1).imag();
  const double disc = g1 * g1 + 2.0 * g2 * target_logit;  // root of g1 m + g2 m^2 / 2 = target near 0
  const double guess = disc > 0.0 ? 2.0 * target_logit / (g1 + std::sqrt(disc)) : target_logit / g1;
  const double start = std::isfinite(guess) ? std::clamp(guess, lo, hi) : 0.0;
  // The last Newton step is predicted instead of confirmed by one more evaluation.
  constexpr double kFinishSafety = 0.25;  // the secant f'' may be off by a few
  root_options.newton_finish_tol = kFinishSafety * root_options.f_tol;
  // E and S are moved along the predicted step by first order: |E''| / |E| is O(1) in
  // m (rho ~ e^{m tau}), so a step of 1e-8 leaves ~1e-16 relative.
  root_options.newton_finish_max_step = 1e-8;
  RootResult root = solveMonotone(residual, lo, hi, start, true, root_options);
  out.report = root.report;
  out.shape = root.x + root.newton_step;
  if (root.report.status == SolveStatus::kInfeasible) {
    out.report.message = "triangle not reachable with alpha = " + std::to_string(alpha) + ": chord angle " +
                         std::to_string(target) + " rad for turning angle " + std::to_string(theta_d) + " rad";
    if (options.report_reachable) {
      out.reachable = reachableChordAngles(alpha, theta_d, options);
      out.report.message += ", reachable " + rangeText(out.reachable);
    }
    return out;
  }
  if (!root.report.usable()) return out;
  // solveMonotone's last evaluation was at root.x, so `last` holds that curve; a
  // predicted last Newton step moves it along by first order (the step is tiny: its
  // square is below the chord tolerance).
  const double step = root.newton_step;
  last.end += step * last.d_end;
  last.length += step * last.d_length;
  out.segment = place(out.shape, last);
  return out;
}

}  // namespace la
