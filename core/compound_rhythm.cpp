#include "core/compound_rhythm.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/la_segment.h"
#include "core/quadrature.h"
#include "core/root_finding.h"

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;

// Composite Gauss-Legendre in tau = t / phi (t the turning within a piece), as in
// core/three_point_segment.cpp: rho = (1 + A tau)^p has a branch point at tau* = -1/A
// outside [0, 1]; a panel no wider than kSingularWidthRatio times its distance to it
// has Bernstein ellipse parameter >= 3, so 16 nodes give ~3^-32 ~ 1e-15 relative
// error; panels also keep the change of log rho below kMaxLogRhoChange (alpha ~ 1).
constexpr int kPanelNodes = 16;
constexpr double kSingularWidthRatio = 3.0;
constexpr double kMaxLogRhoChange = 8.0;
// Each piece's |log(rho_end / rho_start)| is kept below this (a radius ratio e^30 ~
// 1e13); beyond it a polygon is reported infeasible (same bound as the 3-point solve).
constexpr double kMaxLogRadiusRatio = 30.0;
// Piece 1's law (rho/rho_c)^(alpha1-1) = 1 + y, y = (alpha1-1) r t, is computed from the
// joint rate r; near the end of its domain (rho_end -> 0 or infinity) 1 + y cancels.
// Keeping 1 + y >= kMinBase at the piece's end leaves 4 digits after the cancellation,
// and y's own rounding (1e-16) cannot push it to 0. The shapes left out differ from the
// limit (an inflection end for alpha1 < 0) by ~kMinBase^(alpha1/(alpha1-1)) in position.
constexpr double kMinBase = 1e-12;
// Below this base the rounding of m moves m1 by more than 1e-16 / kSwitchBase = 1e-12, so
// the solve switches its unknown to m1 (see StandardCompound::Variable).
constexpr double kSwitchBase = 1e-4;
// exp() overflows past ~709; the laws use exp(alpha m) and exp((alpha-1) m).
constexpr double kMaxExponent = 600.0;
// Points closer than this, relative to the polygon's size, coincide (scale-free).
constexpr double kCoincident = 1e-14;
// Corner angles smaller than this (radians) count as straight: rounding noise on a
// collinear triple must not make a polygon S-shaped.
constexpr double kStraightAngle = 1e-12;
// Newton stops at |chord angle error| <= this share of the tolerance (the end-point
// miss relative to the chord is the chord angle error in radians, to first order), so
// the check on the built segments has room for their own quadrature error.
constexpr double kNewtonShareOfTolerance = 0.25;

/// expm1(x m) / x, m at x = 0 (the integral of e^(x u) over u in [0, m]).
double expm1Over(double x, double m) { return x == 0.0 ? m : std::expm1(x * m) / x; }
/// log1p(x y) / x, y at x = 0 (the inverse of expm1Over in m).
double log1pOver(double x, double y) { return x == 0.0 ? y : std::log1p(x * y) / x; }

/// One LA piece in its turning-angle form: rho(tau)/rho_start for tau in [0, 1] over a
/// turning phi is (1 + A tau)^p, p = 1/(alpha-1), A = e^((alpha-1) m) - 1, or
/// e^(m tau) for alpha = 1; m = log(rho_end / rho_start).
struct PieceLaw {
  double alpha = 0.0, phi = 0.0, m = 0.0;
  bool unit_alpha = false;
  double a = 0.0, p = 0.0, b_end = 1.0;
  bool branch_at_end = false;     // the branch point lies past tau = 1 (else before 0)
  double distance = INFINITY;     // from the nearer end of [0, 1] to the branch point
};

PieceLaw makeLaw(double alpha, double phi, double m) {
  PieceLaw law;
  law.alpha = alpha;
  law.phi = phi;
  law.m = m;
  law.unit_alpha = (alpha == 1.0);
  if (law.unit_alpha) return law;
  law.a = std::expm1((alpha - 1.0) * m);
  law.b_end = std::exp((alpha - 1.0) * m);
  law.p = 1.0 / (alpha - 1.0);
  if (law.a > 0.0) {
    law.distance = 1.0 / law.a;
  } else if (law.a < 0.0) {
    law.branch_at_end = true;
    law.distance = law.b_end / -law.a;  // (1 + A)/|A| without cancellation
  }
  return law;
}

/// Length / (rho_start phi) of a piece in closed form: integral_0^1 rho/rho_start dtau
/// = (expm1(alpha m)/alpha) / (expm1((alpha-1) m)/(alpha-1)); 1 for the circle m = 0.
double lengthFactor(double alpha, double m) {
  return m == 0.0 ? 1.0 : expm1Over(alpha, m) / expm1Over(alpha - 1.0, m);
}

// Widest panel at distance delta from the branch point.
double maxPanelWidth(const PieceLaw& law, double delta) {
  if (law.unit_alpha) return law.m == 0.0 ? INFINITY : kMaxLogRhoChange / std::abs(law.m);
  return delta * std::min(kSingularWidthRatio, kMaxLogRhoChange / std::abs(law.p));
}

/// integral_0^phi (rho/rho_start) e^{i t} dt and its derivative in m.
struct PieceIntegral {
  Vec2 end = Vec2::Zero();
  Vec2 d_end = Vec2::Zero();
};

PieceIntegral integratePiece(const PieceLaw& law) {
  const auto& rule = gaussLegendre<kPanelNodes>();
  double ex = 0, ey = 0, dx = 0, dy = 0;
  // March from the end nearest the branch point, each panel as wide as allowed.
  // Widths grow geometrically (by 1 + kSingularWidthRatio), so a branch point even
  // e^-600 away needs ~1000 panels; the cap only guards against a NaN law.
  constexpr int kMaxPanels = 2000;
  double x = 0.0;  // distance from the near end covered so far
  for (int panel = 0; x < 1.0; ++panel) {
    const double allowed = maxPanelWidth(law, law.distance + x);
    const double width = (panel + 1 >= kMaxPanels || !(allowed > 0.0)) ? 1.0 - x : std::min(1.0 - x, allowed);
    const double near = x;
    x = (width >= 1.0 - x) ? 1.0 : x + width;
    for (int k = 0; k < kPanelNodes; ++k) {
      // Distance from the near end, exact to rounding relative to itself: near a branch
      // point past tau = 1 the base is formed from 1 - tau, never from 1 - (1 - (1 - tau)).
      const double d = near + width * rule.node[k];
      const double tau = law.branch_at_end ? 1.0 - d : d;
      const double tau_c = law.branch_at_end ? d : 1.0 - d;  // 1 - tau
      double rho, drho;
      if (law.unit_alpha) {
        rho = std::exp(law.m * tau);
        drho = tau * rho;
      } else {
        // b = 1 + A tau; near b -> 0 (A -> -1) written from the end so no digits cancel
        const bool far = law.a >= -0.5;
        const double b = far ? 1.0 + law.a * tau : law.b_end - law.a * tau_c;
        rho = std::exp(law.p * (far ? std::log1p(law.a * tau) : std::log(b)));
        drho = rho * tau * law.b_end / b;  // d rho/dm = rho tau (1 + A) / b
      }
      const double t = law.phi * tau;
      const double c = std::cos(t), s = std::sin(t);
      const double wk = width * rule.weight[k];
      ex += wk * rho * c;
      ey += wk * rho * s;
      dx += wk * drho * c;
      dy += wk * drho * s;
    }
  }
  PieceIntegral out;
  out.end = law.phi * Vec2(ex, ey);
  out.d_end = law.phi * Vec2(dx, dy);
  return out;
}

Vec2 rotate(const Vec2& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

/// The standard compound curve: starts at the origin heading +x with rho_0 = 1, turns
/// phi0 on piece 0 (alpha0) and phi1 on piece 1 (alpha1), left.
class StandardCompound {
 public:
  StandardCompound(double alpha0, double alpha1, double phi0, double phi1)
      : alpha0_(alpha0), alpha1_(alpha1), phi0_(phi0), phi1_(phi1) {}

  /// d rho/ds at the joint (dimensionless) as a function of m = log(rho_c / rho_0):
  /// r = (e^((1-alpha0) m) - 1) / ((1-alpha0) phi0), increasing in m.
  double jointRate(double m) const { return expm1Over(1.0 - alpha0_, m) / phi0_; }
  /// Piece 1's m1 = log(rho_end / rho_c) from the joint rate r; NaN outside its domain
  /// (1 + (alpha1-1) r phi1 <= 0: the radius would reach 0 or infinity inside the piece).
  double secondLogRatio(double r) const {
    const double y = (alpha1_ - 1.0) * r * phi1_;
    return 1.0 + y > 0.0 ? log1pOver(alpha1_ - 1.0, r * phi1_) : std::nan("");
  }
  /// The m whose joint rate gives piece 1 the log ratio m1 (+-inf when no m does).
  double firstLogRatioFor(double m1) const {
    const double r = expm1Over(alpha1_ - 1.0, m1) / phi1_;
    const double y = (1.0 - alpha0_) * r * phi0_;
    if (1.0 + y > 0.0) return log1pOver(1.0 - alpha0_, r * phi0_);
    return alpha0_ < 1.0 ? -INFINITY : INFINITY;
  }

  /// The unknown of the shape solve: m (well conditioned everywhere except where piece
  /// 1 nears the end of its domain, 1 + y -> 0, and m1 reacts to the last bits of m),
  /// or m1 (the same, the other way round).
  enum class Variable { kFirst, kSecond };
  struct Eval {
    Vec2 end = Vec2::Zero();    // E
    Vec2 d_end = Vec2::Zero();  // dE/d(variable)
    double m = 0.0, m1 = 0.0;
    double base1 = 1.0;  // (rho_end/rho_c)^(alpha1-1) = 1 + (alpha1-1) r phi1; small near piece 1's limit
  };
  Eval eval(double w, Variable variable) const {
    Eval out;
    double chain;  // dm1/dm (kFirst) or dm/dm1 (kSecond)
    if (variable == Variable::kFirst) {
      out.m = w;
      const double r = jointRate(w);
      out.m1 = secondLogRatio(r);
      out.base1 = 1.0 + (alpha1_ - 1.0) * r * phi1_;
      chain = phi1_ / out.base1 * std::exp((1.0 - alpha0_) * w) / phi0_;
    } else {
      out.m1 = w;
      const double r = expm1Over(alpha1_ - 1.0, w) / phi1_;
      out.m = firstLogRatioFor(w);
      out.base1 = std::exp((alpha1_ - 1.0) * w);
      chain = phi0_ / (1.0 + (1.0 - alpha0_) * r * phi0_) * out.base1 / phi1_;
    }
    const PieceIntegral i0 = integratePiece(makeLaw(alpha0_, phi0_, out.m));
    const PieceIntegral i1 = integratePiece(makeLaw(alpha1_, phi1_, out.m1));
    const double rho_c = std::exp(out.m);
    const Vec2 e1 = rotate(i1.end, phi0_), de1 = rotate(i1.d_end, phi0_);
    out.end = i0.end + rho_c * e1;
    const Vec2 d_m = i0.d_end + rho_c * e1, d_m1 = rho_c * de1;  // partial derivatives
    out.d_end = variable == Variable::kFirst ? Vec2(d_m + chain * d_m1) : Vec2(chain * d_m + d_m1);
    return out;
  }

 private:
  double alpha0_, alpha1_, phi0_, phi1_;
};

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}
double degrees(double radians) { return radians * 180.0 / kPi; }

}  // namespace

CompoundRhythmSolve solveCompoundRhythm(double alpha0, double alpha1, const std::array<Vec2, 4>& q,
                                        double joint_theta, const CompoundRhythmOptions& options) {
  CompoundRhythmSolve result;
  SolveReport& report = result.report;
  auto fail = [&](SolveStatus status, const std::string& message) {
    report.status = status;
    report.message = message;
    return result;
  };

  // ---- Input checks and the normalized frame.
  if (!std::isfinite(alpha0) || !std::isfinite(alpha1))
    return fail(SolveStatus::kBadInput, "alpha0 and alpha1 must be finite (a circle has no compound rhythm)");
  for (const Vec2& p : q)
    if (!allFinite(p)) return fail(SolveStatus::kBadInput, "control point is NaN or infinite");
  if (!(options.tolerance > 0.0) || options.max_iterations < 1)
    return fail(SolveStatus::kBadInput, "tolerance must be > 0 and max_iterations >= 1");
  const bool default_joint = std::isnan(joint_theta);
  if (!default_joint && !std::isfinite(joint_theta))
    return fail(SolveStatus::kBadInput, "joint angle is infinite");
  const Vec2 leg0 = q[1] - q[0], leg1 = q[2] - q[1], leg2 = q[3] - q[2], chord_vec = q[3] - q[0];
  const double size = std::max({leg0.norm(), leg1.norm(), leg2.norm(), chord_vec.norm()});
  if (!(size > 0.0) || leg0.norm() <= kCoincident * size || leg2.norm() <= kCoincident * size)
    return fail(SolveStatus::kBadInput, "coincident control points: Q0 = Q1 or Q2 = Q3 leaves an end tangent undefined");
  if (chord_vec.norm() <= kCoincident * size)
    return fail(SolveStatus::kBadInput, "coincident control points: Q0 = Q3 (a closed curve)");
  if (default_joint) {
    const Vec2 dir = 0.5 * (q[2] + q[3]) - 0.5 * (q[0] + q[1]);
    if (dir.norm() <= kCoincident * size)
      return fail(SolveStatus::kBadInput, "default joint direction undefined: the midpoints of Q0Q1 and Q2Q3 coincide");
    joint_theta = angleOf(dir);
  }
  result.joint_theta = joint_theta;

  // Turning of the polygon: the sum of its corner angles (one corner if Q1 = Q2).
  double turning;
  if (leg1.norm() <= kCoincident * size) {
    turning = signedAngle(leg0, leg2);
    if (std::abs(turning) >= kPi) return fail(SolveStatus::kBadInput, "the polygon doubles back (corner of pi)");
  } else {
    const double a1 = signedAngle(leg0, leg1), a2 = signedAngle(leg1, leg2);
    if (std::abs(a1) >= kPi || std::abs(a2) >= kPi)
      return fail(SolveStatus::kBadInput, "the polygon doubles back (corner of pi)");
    if ((a1 > kStraightAngle && a2 < -kStraightAngle) || (a1 < -kStraightAngle && a2 > kStraightAngle))
      return fail(SolveStatus::kInfeasible,
                  "S-shaped control polygon (corners of " + fmt(degrees(a1)) + " and " + fmt(degrees(a2)) +
                      " degrees): a compound-rhythm curve has monotone curvature and no inflection, so the polygon "
                      "must turn one way");
    turning = a1 + a2;
  }
  if (std::abs(turning) <= kStraightAngle)
    return fail(SolveStatus::kBadInput, "straight control polygon: the end tangents are parallel and no turning");
  const double turn_sign = turning > 0.0 ? 1.0 : -1.0;
  const double theta_d = std::abs(turning);
  const double heading = angleOf(leg0);
  // Joint angle from the start tangent in the standard (left-turning) frame, unwrapped
  // around the middle of the turning.
  const double phi0 = 0.5 * theta_d + wrapAngle(turn_sign * (joint_theta - heading) - 0.5 * theta_d);
  const double phi1 = theta_d - phi0;
  if (!(phi0 > kStraightAngle && phi1 > kStraightAngle))
    return fail(SolveStatus::kInfeasible,
                "joint direction " + fmt(degrees(joint_theta)) +
                    " degrees is not strictly between the start and end tangents (" + fmt(degrees(heading)) + " and " +
                    fmt(degrees(heading + turning)) + " degrees)");

  // Target chord in the standard frame, as an angle from the middle direction theta_d/2:
  // the curve has monotone curvature (G3 keeps the sign of d rho/ds), so by the nested
  // osculating circles (Tait-Kneser) its chord lies within pi of that direction and this
  // angle never wraps for theta_d < 2 pi.
  const Vec2 target = rotate(chord_vec, -heading);
  const Vec2 target_std(target.x(), turn_sign * target.y());
  const Vec2 middle = unitVector(0.5 * theta_d);
  auto chordAngle = [&](const Vec2& e) { return std::atan2(cross(middle, e), middle.dot(e)); };
  const double target_angle = chordAngle(target_std);

  // ---- The shape solve: chord angle of E(m) = target, m in the admissible range.
  const StandardCompound standard(alpha0, alpha1, phi0, phi1);
  const double m0_max = std::min(kMaxLogRadiusRatio, kMaxExponent / std::max(std::abs(alpha0), std::abs(alpha0 - 1.0)));
  const double m1_max = std::min(kMaxLogRadiusRatio, kMaxExponent / std::max(std::abs(alpha1), std::abs(alpha1 - 1.0)));
  double m1_lo = -m1_max, m1_hi = m1_max;
  if (alpha1 > 1.0) m1_lo = std::max(m1_lo, std::log(kMinBase) / (alpha1 - 1.0));
  if (alpha1 < 1.0) m1_hi = std::min(m1_hi, std::log(kMinBase) / (alpha1 - 1.0));
  const double m_lo = std::max(-m0_max, standard.firstLogRatioFor(m1_lo));
  const double m_hi = std::min(m0_max, standard.firstLogRatioFor(m1_hi));
  if (!(m_lo < m_hi))
    return fail(SolveStatus::kInfeasible, "no admissible shape: the radius ratio of a piece would exceed e^30");
  RootOptions root_options;
  root_options.f_tol = kNewtonShareOfTolerance * options.tolerance;
  root_options.max_iterations = options.max_iterations;
  using Variable = StandardCompound::Variable;
  auto solveIn = [&](Variable variable, double lo, double hi, double start) {
    auto f = [&](double w) {
      const StandardCompound::Eval e = standard.eval(w, variable);
      return std::pair<double, double>(chordAngle(e.end) - target_angle, cross(e.end, e.d_end) / e.end.squaredNorm());
    };
    return solveMonotone(f, lo, hi, start, /*increasing=*/true, root_options);
  };
  RootResult root = solveIn(Variable::kFirst, m_lo, m_hi, 0.0);
  Variable variable = Variable::kFirst;
  report.iterations = root.report.iterations;
  if (root.report.status == SolveStatus::kInfeasible) {
    const double lo = chordAngle(standard.eval(m_lo, Variable::kFirst).end);
    const double hi = chordAngle(standard.eval(m_hi, Variable::kFirst).end);
    auto chord = [&](double a) { return fmt(degrees(a + 0.5 * theta_d)); };
    return fail(SolveStatus::kInfeasible,
                "Q3 is out of reach for alpha0 = " + fmt(alpha0) + ", alpha1 = " + fmt(alpha1) + " and joint " +
                    fmt(degrees(phi0)) + " degrees into a turning of " + fmt(degrees(theta_d)) +
                    ": the chord Q0Q3 must make an angle between " + chord(lo) + " and " + chord(hi) +
                    " degrees with Q1-Q0 (it makes " + chord(target_angle) + ")");
  }
  if (std::isfinite(root.x)) {
    // Near piece 1's limit (an inflection or cusp end) m1 reacts to the rounding of m:
    // polish in m1 instead, from where the first solve ended.
    const StandardCompound::Eval at = standard.eval(root.x, Variable::kFirst);
    if (at.base1 < kSwitchBase) {
      const double w_lo = standard.eval(m_lo, Variable::kFirst).m1, w_hi = standard.eval(m_hi, Variable::kFirst).m1;
      const RootResult polished = solveIn(Variable::kSecond, w_lo, w_hi, std::clamp(at.m1, w_lo, w_hi));
      report.iterations += polished.report.iterations;
      if (polished.report.status == SolveStatus::kConverged || root.report.status != SolveStatus::kConverged) {
        root = polished;
        variable = Variable::kSecond;
      }
    }
  }
  if (root.report.status != SolveStatus::kConverged) {
    report.residual = std::abs(root.value);
    return fail(root.report.status, "shape solve: " + root.report.message);
  }

  // ---- The curve in the world frame, and the check of its end on the real segments.
  const StandardCompound::Eval e = standard.eval(root.x, variable);
  const double m = e.m;
  const double chord = chord_vec.norm();
  const double rho0 = chord / e.end.norm();
  const double rho_c = rho0 * std::exp(m), rho1 = rho_c * std::exp(e.m1);
  const double length0 = rho0 * phi0 * lengthFactor(alpha0, m);
  const double length1 = rho_c * phi1 * lengthFactor(alpha1, e.m1);
  const double segment_tolerance = std::max(1e-15, 0.05 * options.tolerance);
  Curve curve;
  try {
    const LaSegment piece0(alpha0, length0, q[0], heading, turn_sign / rho0, turn_sign / rho_c);
    const LaSegment piece1(alpha1, length1, piece0.end(segment_tolerance), heading + turn_sign * phi0,
                           turn_sign / rho_c, turn_sign / rho1);
    curve.pieces.push_back({piece0, false});
    curve.pieces.push_back({piece1, false});
  } catch (const std::invalid_argument& error) {
    // LaSegment's own range is narrower than the solve's for extreme alphas (e.g. |alpha|
    // ~ 1e-300, where 1/alpha overflows); the input, not the polygon, is at fault.
    return fail(SolveStatus::kBadInput,
                std::string("the solved pieces cannot be represented as LA segments (alpha out of range?): ") +
                    error.what());
  }
  const Vec2 end = curve.pieces[1].segment.end(segment_tolerance);
  report.residual = (end - q[3]).norm() / chord;
  if (!(report.residual <= options.tolerance))
    return fail(SolveStatus::kIterationLimit,
                "the shape solve converged but the built curve misses Q3 by " + fmt(report.residual) +
                    " of the chord (tolerance " + fmt(options.tolerance) + ")");
  report.status = SolveStatus::kConverged;
  report.message = "converged";
  result.curve = std::move(curve);
  return result;
}

}  // namespace la
