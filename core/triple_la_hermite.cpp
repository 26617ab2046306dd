#include "core/triple_la_hermite.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/least_squares.h"
#include "core/quadrature.h"

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;

// Piece lengths as fractions of L: joints at 0.25 L and 0.75 L (seed 002 sec. 2.1).
constexpr std::array<double, 3> kPieceFraction = {0.25, 0.5, 0.25};

// Gauss-Legendre nodes per panel of the fast model. A panel whose width is at most
// kSingularWidthRatio times its distance to the branch point of the LA law (where
// |kappa|^(-alpha) = 0) has a Bernstein ellipse parameter >= 3, so 16 nodes give
// ~3^-32 ~ 5e-16 relative error (the same bound as core/three_point_segment.cpp).
constexpr int kNodes = 16;
constexpr double kSingularWidthRatio = 3.0;
// Easy panels get 8 nodes: width at most kEasyWidthRatio times the distance to the
// branch point (ellipse parameter >= 9.9, error ~ 9.9^-16 ~ 1e-16), turning at most
// kEasyTurning (GL8 error ~ 0.75^16 / 16! ~ 5e-16) and, alpha = 0, a change of
// log|kappa| at most kEasyLogChange.
constexpr int kEasyNodes = 8;
constexpr double kEasyWidthRatio = 0.5;
constexpr double kEasyTurning = 1.5;
constexpr double kEasyLogChange = 1.5;
// Turning per panel: GL16 on exp(i theta) with theta varying by 6 rad errs by
// ~ 3^32 / 32! ~ 1e-20.
constexpr double kMaxPanelTurning = 6.0;
// alpha = 0: change of log|kappa| per panel (as kMaxLogRhoChange in three_point_segment.cpp).
constexpr double kMaxLogChange = 8.0;
// A part that reaches kappa = 0 at an end (alpha < 0) gets a first panel of this
// fraction of the part with the substitution s = t^m that smooths the |s|^beta law.
constexpr double kZeroEndPanel = 0.25;
constexpr int kMaxPanelsPerPart = 80;  // grading by factor 4: 1e-48 of the part, never reached in practice

// Verification: LaSegment::end to this accuracy relative to each segment's length.
constexpr double kVerifyTolerance = 1e-14;
// Steps with the verified residual and the fast Jacobian after the fast Newton.
constexpr int kPolishSteps = 4;
// Largest Newton step in log L, and in log|kappa| (alpha >= 0); alpha < 0 limits
// |dq| to kMaxRelativeQStep times the larger of |q| and the problem's q scale.
constexpr double kMaxLogLengthStep = 1.0;
constexpr double kMaxLogKappaStep = 2.0;
constexpr double kMaxRelativeQStep = 2.0;
constexpr int kMaxHalvings = 8;
// Newton gives up after this many damped steps (t < 1/8) in a row: it is crawling
// towards a boundary of the domain, not converging.
constexpr int kMaxDampedSteps = 6;
// Iterates beyond these (normalized by the chord) are taken as diverging: the family of
// solutions has left the domain (a joint curvature blowing up, typically for alpha > 1).
constexpr double kMaxNormalizedKappa = 1e6;
constexpr double kMaxNormalizedLength = 1e4;
// The fast model's residual is ~1e-15; below this the line search may stall on rounding,
// and the verified residual decides.
constexpr double kFastNoiseFloor = 1e-10;
// Newton takes its last full step unevaluated when the contraction of the previous full
// step (norm_new / norm_old^2) predicts a residual below this fraction of the target;
// the verification checks the result anyway. Measured on the benchmark's end
// conditions for alpha = -3 to 3 in steps of 0.25 (174 such steps), the skipped
// evaluation would have shown at most 2.5e-14 against the target 1e-13.
constexpr double kSkipConfirmFactor = 0.1;
// The law-aware start (lawStart): Gauss-Legendre nodes per piece, Newton iterations,
// and the residual (radians) it must reach to be used. Its conditions are a model of
// the end point's, good to the small-deflection error (~1e-2), so neither the
// quadrature (a kink where kappa crosses 0 costs ~1e-4 with 8 nodes) nor the
// tolerance needs to be tight.
constexpr int kLawStartNodes = 8;
constexpr int kLawStartIterations = 12;
constexpr double kLawStartTolerance = 1e-8;
// Lengths tried (times the Bezier estimate) when Newton fails from the first start.
constexpr std::array<double, 4> kLengthFactors = {0.7, 1.5, 2.5, 0.5};
// Continuation from the triple clothoid: steps in alpha.
constexpr int kContinuationSteps = 6;

using Vars = Eigen::Vector3d;  // (log L, y1, y2)

/// Gauss-Legendre rule on [0, 1] with its collocation integration matrix:
/// integral[k][j] = integral_0^{t_k} l_j(t) dt for the Lagrange basis l_j on the nodes,
/// so sum_j integral[k][j] f(t_j) integrates f from 0 to t_k (exact for degree < N).
/// Built from the Legendre expansion l_j = sum_n (2n+1)/2 w_j P_n(x_j) P_n(x) and
/// integral_{-1}^x P_n = (P_{n+1} - P_{n-1})/(2n+1).
template <int N>
struct CollocationRule {
  std::array<double, N> node{}, weight{};
  std::array<std::array<double, N>, N> integral{};
};

template <int N>
const CollocationRule<N>& collocationRule() {
  static const CollocationRule<N> rule = [] {
    CollocationRule<N> r;
    const auto& gl = gaussLegendre<N>();
    r.node = gl.node;
    r.weight = gl.weight;
    auto legendre = [](double x, std::array<double, N + 1>& p) {
      p[0] = 1.0;
      p[1] = x;
      for (int n = 1; n < N; ++n) p[n + 1] = ((2.0 * n + 1.0) * x * p[n] - n * p[n - 1]) / (n + 1.0);
    };
    std::array<double, N + 1> pj, pk;
    for (int k = 0; k < N; ++k) {
      const double xk = 2.0 * r.node[k] - 1.0;
      legendre(xk, pk);
      std::array<double, N> in{};
      in[0] = xk + 1.0;
      for (int n = 1; n < N; ++n) in[n] = (pk[n + 1] - pk[n - 1]) / (2.0 * n + 1.0);
      for (int j = 0; j < N; ++j) {
        legendre(2.0 * r.node[j] - 1.0, pj);
        double sum = 0.0;
        for (int n = 0; n < N; ++n) sum += 0.5 * (2.0 * n + 1.0) * pj[n] * in[n];
        r.integral[k][j] = r.weight[j] * sum;
      }
    }
    return r;
  }();
  return rule;
}

/// The problem in the normalized frame: start at the origin, end at (1, 0).
struct Problem {
  double alpha = -1.0;
  bool signed_power = true;  // alpha < 0: y = sign(k)|k|^(-alpha); else y = log|k|
  double beta = 1.0;         // -1/alpha: |kappa| = |y-linear|^beta (alpha < 0)
  bool beta_integer = true;  // the law is a polynomial: no branch point to resolve
  double sigma = 1.0;        // alpha >= 0: the sign of every curvature
  double phi0 = 0.0;         // start tangent angle relative to the chord
  double turning = 0.0;      // end.theta - start.theta
  double k0 = 0.0, k3 = 0.0;
  double y0 = 0.0, y3 = 0.0;

  double kappaOf(double y) const {
    if (signed_power) return y == 0.0 ? 0.0 : std::copysign(std::pow(std::abs(y), beta), y);
    return sigma * std::exp(y);
  }
  double yOf(double k) const {
    if (signed_power) return k == 0.0 ? 0.0 : std::copysign(std::pow(std::abs(k), -alpha), k);
    return std::log(std::abs(k));
  }
};

Problem makeProblem(double alpha, double phi0, double turning, double k0, double k3) {
  Problem pb;
  pb.alpha = alpha;
  pb.signed_power = alpha < 0.0;
  pb.beta = pb.signed_power ? -1.0 / alpha : 0.0;
  pb.beta_integer = pb.signed_power && pb.beta >= 1.0 && std::abs(pb.beta - std::round(pb.beta)) < 1e-12;
  pb.sigma = (k0 + k3 >= 0.0) ? 1.0 : -1.0;
  pb.phi0 = phi0;
  pb.turning = turning;
  pb.k0 = k0;
  pb.k3 = k3;
  pb.y0 = pb.yOf(k0);
  pb.y3 = pb.yOf(k3);
  return pb;
}

/// One LaSegment of the chain: a piece, or half of a piece split at its inflection.
struct Part {
  LaSegment seg;
  int piece;          // 0, 1, 2
  double s_in_piece;  // where the part starts within its piece
};

/// The chain for the variables x, in the normalized frame, each part starting at the
/// origin (positions are the caller's business). False if a piece is not a valid LA
/// segment (overflowing curvature ratio for a large alpha).
bool buildParts(const Problem& pb, const Vars& x, std::vector<Part>& parts) {
  parts.clear();
  const double length = std::exp(x[0]);
  const std::array<double, 4> k = {pb.k0, pb.kappaOf(x[1]), pb.kappaOf(x[2]), pb.k3};
  const std::array<double, 4> y = {pb.y0, x[1], x[2], pb.y3};
  if (!(std::isfinite(length) && length > 0.0) || !std::isfinite(k[1]) || !std::isfinite(k[2])) return false;
  double theta = pb.phi0;
  try {
    for (int j = 0; j < 3; ++j) {
      const double ell = kPieceFraction[j] * length;
      double ka = k[j], kb = k[j + 1];
      if (ka * kb < 0.0) {  // alpha < 0: q = y is linear along the piece and crosses 0
        const double s_zero = ell * (y[j] / (y[j] - y[j + 1]));
        if (s_zero > 0.0 && s_zero < ell) {
          parts.push_back({LaSegment(pb.alpha, s_zero, Vec2::Zero(), theta, ka, 0.0), j, 0.0});
          theta = parts.back().seg.theta(s_zero);
          parts.push_back({LaSegment(pb.alpha, ell - s_zero, Vec2::Zero(), theta, 0.0, kb), j, s_zero});
          theta = parts.back().seg.theta(ell - s_zero);
          continue;
        }
        (s_zero <= 0.0 ? ka : kb) = 0.0;  // rounding put the inflection on the end
      }
      parts.push_back({LaSegment(pb.alpha, ell, Vec2::Zero(), theta, ka, kb), j, 0.0});
      theta = parts.back().seg.theta(ell);
    }
  } catch (const std::invalid_argument&) {
    return false;
  }
  return true;
}

struct Panel {
  double lo = 0.0, hi = 0.0;  // arc length within the part
  int power = 1;              // substitution s = lo + (hi-lo) t^power (or from hi)
  bool from_hi = false;
  int nodes = kNodes;
};

/// Panels of a part such that the fixed Gauss-Legendre rule is accurate on each (see
/// the constants): graded towards the branch point of the LA law, a substituted first
/// panel at a zero-curvature end, no panel turning more than kMaxPanelTurning; 8 nodes
/// where that is enough, 16 elsewhere. Panels come in increasing s.
void layoutPanels(const Problem& pb, const LaSegment& seg, std::vector<Panel>& panels) {
  panels.clear();
  const double len = seg.length();
  const double ka = seg.kappaStart(), kb = seg.kappaEnd();
  struct Graded {
    Panel panel;
    double width_ratio;  // width / distance to the branch point (0: none)
  };
  std::array<Graded, kMaxPanelsPerPart> graded;
  int count = 0;
  if (ka == kb || pb.beta_integer || pb.alpha == 0.0) {
    const double log_change = (pb.alpha == 0.0 && ka != kb) ? std::abs(std::log(kb / ka)) : 0.0;
    const int n = ceilWithin(log_change / kMaxLogChange, 1, kMaxPanelsPerPart);
    for (int i = 0; i < n; ++i) {
      Panel p;
      p.lo = len * i / n;
      p.hi = (i + 1 == n) ? len : len * (i + 1) / n;
      p.nodes = (log_change / n <= kEasyLogChange) ? kEasyNodes : kNodes;
      graded[count++] = {p, 0.0};
    }
  } else {
    // |kappa|^(-alpha) is linear and vanishes at the branch point, at distance d (in
    // units of len) beyond the near end.
    bool near_hi = false;
    double d = 0.0;
    if (ka == 0.0) {
      near_hi = false;
    } else if (kb == 0.0) {
      near_hi = true;
    } else {
      const double r = std::exp(-pb.alpha * (std::log(std::abs(kb)) - std::log(std::abs(ka))));  // v(end)/v(start)
      if (r > 1.0) {
        d = std::isinf(r) ? 0.0 : 1.0 / (r - 1.0);
      } else {
        near_hi = true;
        d = r / (1.0 - r);
      }
    }
    const int power = (d == 0.0) ? ceilWithin(4.0 / std::max(pb.beta, 0.25), 2, 16) : 1;
    double x = 0.0;  // distance from the near end, in units of len
    while (x < 1.0) {
      double w = (x == 0.0 && d == 0.0) ? kZeroEndPanel : kSingularWidthRatio * (d + x);
      if (x + w >= 1.0 || count + 1 >= kMaxPanelsPerPart) w = 1.0 - x;
      const double lo = x, hi = (x + w >= 1.0) ? 1.0 : x + w;
      Panel p;
      p.power = (x == 0.0) ? power : 1;
      p.nodes = (p.power == 1 && hi - lo <= kEasyWidthRatio * (d + x)) ? kEasyNodes : kNodes;
      if (near_hi) {
        p.lo = len * (1.0 - hi);
        p.hi = (lo == 0.0) ? len : len * (1.0 - lo);
        p.from_hi = true;
      } else {
        p.lo = len * lo;
        p.hi = (hi == 1.0) ? len : len * hi;
      }
      graded[count++] = {p, (d + x > 0.0) ? (hi - lo) / (d + x) : INFINITY};
      x = hi;
    }
    if (near_hi) std::reverse(graded.begin(), graded.begin() + count);  // panels in increasing s
  }
  // Split panels that turn too much (uniformly; a substituted panel keeps its
  // substitution on the sub-panel at the zero end).
  for (int g = 0; g < count; ++g) {
    const Panel& p = graded[g].panel;
    const double turn = std::abs(seg.theta(p.hi) - seg.theta(p.lo));
    const int n = ceilWithin(turn / kMaxPanelTurning, 1, kMaxPanelsPerPart);
    for (int i = 0; i < n; ++i) {
      Panel q = p;
      q.lo = p.lo + (p.hi - p.lo) * i / n;
      q.hi = (i + 1 == n) ? p.hi : p.lo + (p.hi - p.lo) * (i + 1) / n;
      const bool at_zero_end = p.from_hi ? (i + 1 == n) : (i == 0);
      q.power = at_zero_end ? p.power : 1;
      // sub-panels are no closer to the branch point than the panel
      const bool easy = q.power == 1 && turn / n <= kEasyTurning &&
                        (p.nodes == kEasyNodes || graded[g].width_ratio / n <= kEasyWidthRatio);
      q.nodes = easy ? kEasyNodes : kNodes;
      panels.push_back(q);
    }
  }
}

struct Evaluation {
  bool ok = false;
  Eigen::Vector3d residual = Eigen::Vector3d::Constant(INFINITY);  // (E - (1,0), T - turning)
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();              // d residual / d (log L, y1, y2)
};

/// Reused buffers of one solve.
struct Workspace {
  std::vector<Part> parts;
  std::vector<Panel> panels;
};

/// Sums of the fast model over the panels, in order of s.
struct Sums {
  Vec2 pos = Vec2::Zero();           // P at the current panel's start
  Vec2 d_log_length = Vec2::Zero();  // integral of (theta - phi0) i exp(i theta)
  double g[2] = {0.0, 0.0};          // integral of d kappa / d y_j so far: d theta / d y_j at the panel start
  Vec2 d_y[2] = {Vec2::Zero(), Vec2::Zero()};  // integral of (d theta / d y_j) i exp(i theta)
};

/// The LA law along one piece in the Newton variables: y goes from qa at the piece's
/// start to qb at its end, and at u in [0, 1] along the piece
///   alpha < 0:  kappa = F(v), v = qa (1-u) + qb u, F(v) = sign(v) |v|^beta;
///   alpha = 0:  kappa = sigma exp(qa (1-u) + qb u);
///   alpha > 0:  kappa = sigma q^(-1/alpha), q = |k|^(-alpha) = exp(-alpha y) linear in u.
struct PieceLaw {
  double qa = 0.0, qb = 0.0; // y at the piece's ends
  double ratio = 1.0;        // alpha > 0: q_b / q_a or q_a / q_b, whichever is <= 1
};

PieceLaw pieceLaw(const Problem& pb, double qa, double qb) {
  PieceLaw law;
  law.qa = qa;
  law.qb = qb;
  if (!pb.signed_power && pb.alpha != 0.0) law.ratio = std::exp(-std::abs(pb.alpha * (qb - qa)));
  return law;
}

/// d kappa / d qa and d kappa / d qb at u along the piece, where the curvature is kappa;
/// for alpha < 0 the caller gives F'(v) = beta kappa / v, computed where it keeps its precision.
inline void kappaDerivatives(const Problem& pb, const PieceLaw& law, double kappa, double dkappa_dv, double u,
                             double& da, double& db) {
  const double u1 = 1.0 - u;
  if (pb.signed_power) {
    da = dkappa_dv * u1;
    db = dkappa_dv * u;
  } else if (pb.alpha == 0.0) {
    da = kappa * u1;
    db = kappa * u;
  } else if (law.qb >= law.qa) {  // dk/dya = kappa (1-u) q_a / q, dk/dyb = kappa u q_b / q
    const double r = law.ratio, den = u1 + r * u;  // r = q_b / q_a <= 1, q = q_a den
    da = kappa * u1 / den;
    db = kappa * u * r / den;
  } else {
    const double ir = law.ratio, den = u1 * ir + u;  // ir = q_a / q_b < 1, q = q_b den
    da = kappa * u1 * ir / den;
    db = kappa * u / den;
  }
}

/// kappa at u along the piece (and, alpha < 0, F'(v) = beta kappa / v).
inline double pieceKappa(const Problem& pb, const PieceLaw& law, double u, double& dkappa_dv) {
  const double u1 = 1.0 - u;
  dkappa_dv = 0.0;
  if (pb.signed_power) {
    const double v = law.qa * u1 + law.qb * u;
    const double kappa = pb.kappaOf(v);
    if (v != 0.0) dkappa_dv = pb.beta * kappa / v;
    return kappa;
  }
  if (pb.alpha == 0.0) return pb.sigma * std::exp(law.qa * u1 + law.qb * u);
  const double den = (law.qb >= law.qa) ? u1 + law.ratio * u : u1 * law.ratio + u;
  return pb.sigma * std::exp((law.qb >= law.qa) ? law.qa : law.qb) * std::exp(-std::log(den) / pb.alpha);
}

/// What the panels of one part need to know about it.
struct PartLaw : PieceLaw {
  int piece = 0;
  double ell = 0.0;          // length of the piece
  double s_in_piece = 0.0;   // the part's start in the piece
  // A part that reaches kappa = 0 at an end (alpha < 0): with r the distance from that
  // end and lambda the part's length, y = y_far r / lambda (y is linear and 0 there),
  // kappa = kappa_far (r / lambda)^beta and theta = theta_zero +- kappa r / (1 + beta),
  // all without cancellation next to the zero end.
  bool zero_end = false;
  bool zero_at_start = false;
  double part_length = 0.0;
  double y_far = 0.0, kappa_far = 0.0, theta_zero = 0.0;
};

PartLaw partLaw(const Problem& pb, const Part& part, const std::array<double, 4>& y, double length) {
  const LaSegment& seg = part.seg;
  PartLaw law;
  static_cast<PieceLaw&>(law) = pieceLaw(pb, y[part.piece], y[part.piece + 1]);
  law.piece = part.piece;
  law.ell = kPieceFraction[part.piece] * length;
  law.s_in_piece = part.s_in_piece;
  law.zero_end = seg.kappaStart() == 0.0 || seg.kappaEnd() == 0.0;
  if (law.zero_end) {
    law.zero_at_start = seg.kappaStart() == 0.0;
    law.part_length = seg.length();
    // the far end of a part with its zero at the start is the piece's end, and vice versa
    law.y_far = law.zero_at_start ? law.qb : law.qa;
    law.kappa_far = law.zero_at_start ? seg.kappaEnd() : seg.kappaStart();
    law.theta_zero = law.zero_at_start ? seg.theta0() : seg.theta(seg.length());
  }
  return law;
}

/// x^n for a small n >= 0 (the panel substitution's power).
inline double integerPower(double x, int n) {
  double r = 1.0;
  for (; n > 0; n >>= 1, x *= x)
    if (n & 1) r *= x;
  return r;
}

template <int N>
void accumulatePanel(const Problem& pb, const LaSegment& seg, const PartLaw& law, const Panel& p, Sums& sums) {
  const CollocationRule<N>& rule = collocationRule<N>();
  std::array<double, N> c, sn, w, th, f1, f2;
  const double h = p.hi - p.lo;
  const int j = law.piece;
  for (int k = 0; k < N; ++k) {
    const double t = rule.node[k];
    double d, dsdt;  // distance from the panel's starting end (lo, or hi if from_hi); ds/dt
    if (p.power == 1) {
      d = h * t;
      dsdt = h;
    } else {
      const double tp = integerPower(t, p.power - 1);
      d = h * tp * t;
      dsdt = h * p.power * tp;
    }
    const double s = p.from_hi ? p.hi - d : p.lo + d;
    double kappa, f = 0.0;  // f: d kappa / d v for the signed power law (see below)
    if (law.zero_end) {
      // r from the zero end, exact on the substituted panel there (lo = 0, or hi = the part's length)
      double r;
      if (law.zero_at_start) r = p.from_hi ? s : p.lo + d;
      else r = p.from_hi ? (law.part_length - p.hi) + d : law.part_length - s;
      const double rel = r / law.part_length;
      kappa = (rel > 0.0) ? law.kappa_far * std::exp(pb.beta * std::log(rel)) : 0.0;
      const double turned = kappa * r / (1.0 + pb.beta);
      th[k] = law.zero_at_start ? law.theta_zero + turned : law.theta_zero - turned;
      // kappa = F(v) = sign(v) |v|^beta, F' = beta kappa / v with v = y_far r / lambda
      // (F' is taken as 0 where kappa = 0: a straight part, or a node rounded onto the zero end)
      if (kappa != 0.0) f = pb.beta * kappa / (law.y_far * rel);
    } else {
      seg.thetaKappa(s, th[k], kappa);
    }
    c[k] = std::cos(th[k]);
    sn[k] = std::sin(th[k]);
    w[k] = rule.weight[k] * dsdt;
    // d kappa / d y at the piece's start (da) and end (db); u = s / ell in the piece.
    const double u = (law.s_in_piece + s) / law.ell;
    if (pb.signed_power && !law.zero_end) {
      const double v = law.qa * (1.0 - u) + law.qb * u;
      f = (v == 0.0) ? 0.0 : pb.beta * kappa / v;
    }
    double da, db;
    kappaDerivatives(pb, law, kappa, f, u, da, db);
    // y1 is the end of piece 0 and the start of piece 1; y2 likewise for pieces 1, 2.
    f1[k] = dsdt * ((j == 0) ? db : (j == 1 ? da : 0.0));
    f2[k] = dsdt * ((j == 1) ? db : (j == 2 ? da : 0.0));
  }
  // d theta / d y_j at the nodes by the collocation matrix (the integrand in t is
  // smooth even on a substituted panel, where d kappa / d y is singular in s).
  double tx = 0.0, ty = 0.0, t1 = 0.0, t2 = 0.0;
  for (int k = 0; k < N; ++k) {
    tx += w[k] * c[k];
    ty += w[k] * sn[k];
    t1 += rule.weight[k] * f1[k];
    t2 += rule.weight[k] * f2[k];
  }
  const double reversed = p.from_hi ? -1.0 : 1.0;
  const double base1 = sums.g[0] + (p.from_hi ? t1 : 0.0), base2 = sums.g[1] + (p.from_hi ? t2 : 0.0);
  // y1 does not move piece 2's curvature nor y2 piece 0's: skip their zero integrals.
  const bool moves1 = j != 2, moves2 = j != 0;
  for (int k = 0; k < N; ++k) {
    double i1 = 0.0, i2 = 0.0;
    if (moves1)
      for (int m = 0; m < N; ++m) i1 += rule.integral[k][m] * f1[m];
    if (moves2)
      for (int m = 0; m < N; ++m) i2 += rule.integral[k][m] * f2[m];
    const Vec2 wt = w[k] * Vec2(-sn[k], c[k]);  // w i exp(i theta)
    sums.d_log_length += (th[k] - pb.phi0) * wt;
    sums.d_y[0] += (base1 + reversed * i1) * wt;
    sums.d_y[1] += (base2 + reversed * i2) * wt;
  }
  sums.g[0] += t1;
  sums.g[1] += t2;
  sums.pos += Vec2(tx, ty);
}

/// The fast model: residual and Jacobian on fixed Gauss-Legendre panels.
Evaluation evaluate(const Problem& pb, const Vars& x, Workspace& ws) {
  Evaluation ev;
  if (!buildParts(pb, x, ws.parts)) return ev;
  const double length = std::exp(x[0]);
  const std::array<double, 4> y = {pb.y0, x[1], x[2], pb.y3};
  Sums sums;
  for (const Part& part : ws.parts) {
    const LaSegment& seg = part.seg;
    const PartLaw law = partLaw(pb, part, y, length);
    layoutPanels(pb, seg, ws.panels);
    for (const Panel& p : ws.panels) {
      if (p.nodes == kEasyNodes) accumulatePanel<kEasyNodes>(pb, seg, law, p, sums);
      else accumulatePanel<kNodes>(pb, seg, law, p, sums);
    }
  }
  const Part& last = ws.parts.back();
  const double total_turning = last.seg.theta(last.seg.length()) - pb.phi0;
  const Vec2 end = sums.pos;
  const Vec2 dE_dlog = end + sums.d_log_length;
  ev.residual = {end.x() - 1.0, end.y(), total_turning - pb.turning};
  ev.jacobian << dE_dlog.x(), sums.d_y[0].x(), sums.d_y[1].x(),  //
      dE_dlog.y(), sums.d_y[0].y(), sums.d_y[1].y(),             //
      total_turning, sums.g[0], sums.g[1];
  ev.ok = ev.residual.allFinite() && ev.jacobian.allFinite();
  return ev;
}

/// The chain with positions by LaSegment::end (the trusted evaluation), and its miss:
/// (end point - (1, 0), end angle - wanted) in the normalized frame.
bool verifiedChain(const Problem& pb, const Vars& x, Workspace& ws, std::vector<LaSegment>& chain,
                   Eigen::Vector3d& miss) {
  if (!buildParts(pb, x, ws.parts)) return false;
  chain.clear();
  Vec2 pos = Vec2::Zero();
  for (const Part& part : ws.parts) {
    const LaSegment& s = part.seg;
    chain.emplace_back(s.alpha(), s.length(), pos, s.theta0(), s.kappaStart(), s.kappaEnd());
    pos = chain.back().end(kVerifyTolerance);
  }
  const LaSegment& last = chain.back();
  miss = {pos.x() - 1.0, pos.y(), last.theta(last.length()) - (pb.phi0 + pb.turning)};
  return miss.allFinite();
}

struct Attempt {
  bool converged = false;
  Vars x = Vars::Zero();
  std::vector<LaSegment> chain;
  int iterations = 0;
  double residual = INFINITY;
  std::string why;
};

double yScale(const Problem& pb, double length) {
  // A typical |y| for alpha < 0: that of the larger of the end curvatures and the mean curvature.
  const double k = std::max({std::abs(pb.k0), std::abs(pb.k3), std::abs(pb.turning) / length, 1e-3});
  return std::abs(pb.yOf(k));
}

/// Damped Newton on the fast model from x, then verification and polishing. Its own
/// iteration, not core/least_squares.h's: the last full step is taken unevaluated where
/// quadratic convergence predicts it lands (kSkipConfirmFactor), a step must lower the
/// largest residual by a margin that shrinks with the step, and steps that stay damped
/// end the solve (it is crawling to the domain's edge).
Attempt newtonSolve(const Problem& pb, Vars x, const TripleLaHermiteOptions& opt, Workspace& ws) {
  Attempt at;
  Evaluation ev = evaluate(pb, x, ws);
  if (!ev.ok) {
    at.why = "the start is not a valid chain";
    return at;
  }
  double norm = ev.residual.lpNorm<Eigen::Infinity>();
  const double target = 0.1 * opt.tolerance;
  int damped_steps = 0;
  // Quadratic convergence: after a full step norm_new ~ contraction * norm_old^2.
  double contraction = INFINITY;
  while (norm > target) {
    if (at.iterations >= opt.max_iterations) {
      at.why = "iteration limit of the Newton iteration";
      at.residual = norm;
      return at;
    }
    ++at.iterations;
    Eigen::FullPivLU<Eigen::Matrix3d> lu(ev.jacobian);
    Vars dx = -lu.solve(ev.residual);
    if (!lu.isInvertible() || !dx.allFinite()) {
      if (norm <= kFastNoiseFloor) break;
      at.why = "singular Jacobian";
      at.residual = norm;
      return at;
    }
    double scale = 1.0;
    if (std::abs(dx[0]) > kMaxLogLengthStep) scale = kMaxLogLengthStep / std::abs(dx[0]);
    for (int i = 1; i < 3; ++i) {
      const double limit = pb.signed_power ? kMaxRelativeQStep * std::max(std::abs(x[i]), yScale(pb, std::exp(x[0])))
                                           : kMaxLogKappaStep;
      if (std::abs(dx[i]) > limit) scale = std::min(scale, limit / std::abs(dx[i]));
    }
    if (scale == 1.0 && contraction * norm * norm <= kSkipConfirmFactor * target) {
      // The full step is predicted to land well below the target: take it without
      // evaluating the fast model there; the verification below checks it.
      x += dx;
      break;
    }
    bool accepted = false;
    double t = scale;
    if (t < 0.125) ++damped_steps;
    for (int halving = 0; halving < kMaxHalvings; ++halving, t *= 0.5) {
      const Vars x_try = x + t * dx;
      Evaluation ev_try = evaluate(pb, x_try, ws);
      if (!ev_try.ok) continue;
      const double norm_try = ev_try.residual.lpNorm<Eigen::Infinity>();
      if (norm_try < (1.0 - 1e-4 * t) * norm) {
        if (std::abs(pb.kappaOf(x_try[1])) > kMaxNormalizedKappa || std::abs(pb.kappaOf(x_try[2])) > kMaxNormalizedKappa ||
            x_try[0] > std::log(kMaxNormalizedLength)) {
          at.why = "a joint curvature or the length diverges";
          at.residual = norm_try;
          return at;
        }
        contraction = (t == 1.0) ? norm_try / (norm * norm) : INFINITY;
        x = x_try;
        ev = ev_try;
        norm = norm_try;
        accepted = true;
        if (t >= 0.125) damped_steps = 0;
        else if (t < scale) ++damped_steps;
        break;
      }
    }
    if (accepted && damped_steps >= kMaxDampedSteps) {
      at.why = "Newton stalls (damped steps only)";
      at.residual = norm;
      return at;
    }
    if (!accepted) {
      if (norm <= kFastNoiseFloor) break;  // rounding floor of the fast model: let verification decide
      at.why = "line search found no decrease";
      at.residual = norm;
      return at;
    }
  }
  // Verify, and correct the small remaining miss of the fast model.
  Eigen::Vector3d miss;
  for (int polish = 0;; ++polish) {
    if (!verifiedChain(pb, x, ws, at.chain, miss)) {
      at.why = "verification failed to build the chain";
      return at;
    }
    at.residual = miss.lpNorm<Eigen::Infinity>();
    if (at.residual <= opt.tolerance) {
      at.converged = true;
      at.x = x;
      return at;
    }
    if (polish == kPolishSteps) break;
    ++at.iterations;
    x -= Eigen::FullPivLU<Eigen::Matrix3d>(ev.jacobian).solve(miss);
  }
  at.why = "the verified curve misses the end by " + std::to_string(at.residual);
  return at;
}

/// Length of the cubic Bezier from the origin to (1, 0) with handles of a third of the
/// chord along the end tangents: the start's length estimate.
double bezierLength(double phi0, double phi1) {
  const Vec2 b0(0, 0), b1 = unitVector(phi0) / 3.0, b2 = Vec2(1, 0) - unitVector(phi1) / 3.0, b3(1, 0);
  auto speed = [&](double t) {
    const double u = 1.0 - t;
    return (3.0 * (u * u * (b1 - b0) + 2.0 * u * t * (b2 - b1) + t * t * (b3 - b2))).norm();
  };
  return integrateFixed<16>(speed, 0.0, 1.0);
}

/// The small-deflection triple clothoid of the given length: kappa piecewise linear in
/// s through (0, k0), (L/4, k1), (3L/4, k2), (L, k3); L integral kappa = T and
/// phi0 + L integral_0^1 (1 - sigma) kappa d sigma = 0 (i.e. integral of theta = 0,
/// the linearized y(L) = 0). With the hat-function integrals
///   integral h_i = (1/8, 3/8, 3/8, 1/8), integral (1-sigma) h_i = (11/96, 1/4, 1/8, 1/96).
Vars linearStart(const Problem& pb, double length) {
  const double sum12 = (8.0 * pb.turning / length - pb.k0 - pb.k3) / 3.0;          // k1 + k2
  const double r = 8.0 * (-pb.phi0 / length - 11.0 * pb.k0 / 96.0 - pb.k3 / 96.0);  // 2 k1 + k2
  double k1 = r - sum12, k2 = 2.0 * sum12 - r;
  if (!pb.signed_power) {  // curvature keeps the sign sigma: fall back to geometric interpolation
    if (!(pb.sigma * k1 > 0.0)) k1 = pb.sigma * std::pow(std::abs(pb.k0), 0.75) * std::pow(std::abs(pb.k3), 0.25);
    if (!(pb.sigma * k2 > 0.0)) k2 = pb.sigma * std::pow(std::abs(pb.k0), 0.25) * std::pow(std::abs(pb.k3), 0.75);
  }
  return {std::log(length), pb.yOf(k1), pb.yOf(k2)};
}

/// Variables of problem `to` for the same (L, k1, k2) as x in problem `from`.
Vars convert(const Problem& from, const Problem& to, const Vars& x) {
  return {x[0], to.yOf(from.kappaOf(x[1])), to.yOf(from.kappaOf(x[2]))};
}

bool usableStart(const Problem& pb, const Vars& x) {
  return x.allFinite() && (pb.signed_power || (pb.sigma * pb.kappaOf(x[1]) > 0.0 && pb.sigma * pb.kappaOf(x[2]) > 0.0));
}

/// linearStart's two small-deflection conditions with the LA law itself in place of
/// the piecewise linear curvature (for alpha = -1 the law is that profile, and the linear
/// start is returned as it is); with L fixed,
///   F1 = L integral_0^1 kappa d sigma - T = 0,  F2 = phi0 + L integral_0^1 (1 - sigma) kappa d sigma = 0,
/// solved for (y1, y2) by damped Newton from the linear start `linear`, kappa and its
/// derivatives by the piece law on kLawStartNodes Gauss-Legendre nodes per piece. For
/// alpha far from -1 the linear start's curvatures are off by ~20% (S-shaped, alpha = -3)
/// and the first Newton steps on the fast model are spent there; this costs a few
/// microseconds. Falls back to the linear start when it does not converge.
Vars lawStart(const Problem& pb, double length, const Vars& linear) {
  if (pb.alpha == -1.0 || !usableStart(pb, linear)) return linear;
  const auto& rule = gaussLegendre<kLawStartNodes>();
  auto conditions = [&](const Eigen::Vector2d& y12, Eigen::Vector2d& f, Eigen::Matrix2d& jac) {
    const std::array<double, 4> y = {pb.y0, y12[0], y12[1], pb.y3};
    f = {-pb.turning, pb.phi0};
    jac.setZero();
    double sigma0 = 0.0;  // the piece's start as a fraction of L
    for (int j = 0; j < 3; ++j) {
      const PieceLaw law = pieceLaw(pb, y[j], y[j + 1]);
      const double frac = kPieceFraction[j];
      for (int k = 0; k < kLawStartNodes; ++k) {
        const double u = rule.node[k], w = length * frac * rule.weight[k], moment = 1.0 - (sigma0 + frac * u);
        double dkappa_dv, da, db;
        const double kappa = pieceKappa(pb, law, u, dkappa_dv);
        kappaDerivatives(pb, law, kappa, dkappa_dv, u, da, db);
        f[0] += w * kappa;
        f[1] += w * moment * kappa;
        // y1 ends piece 0 and starts piece 1; y2 ends piece 1 and starts piece 2
        const double d1 = (j == 0) ? db : (j == 1 ? da : 0.0), d2 = (j == 1) ? db : (j == 2 ? da : 0.0);
        jac(0, 0) += w * d1;
        jac(0, 1) += w * d2;
        jac(1, 0) += w * moment * d1;
        jac(1, 1) += w * moment * d2;
      }
      sigma0 += frac;
    }
    return f.allFinite() && jac.allFinite();
  };
  // Newton steps (core/least_squares.h) on the largest condition, with the fast
  // Newton's step limits; a trial's Jacobian comes with its conditions, kept for the
  // step after it.
  Eigen::Vector2d at(NAN, NAN);
  Eigen::Matrix2d jac_at;
  LeastSquaresProblem problem;
  problem.residual = [&](const Eigen::VectorXd& y12, Eigen::VectorXd& r) {
    Eigen::Vector2d f;
    if (!conditions(y12, f, jac_at)) return false;
    at = y12;
    r = f;
    return true;
  };
  problem.jacobian = [&](const Eigen::VectorXd& y12, Eigen::VectorXd& r, Eigen::MatrixXd& jac) {
    if (y12 != at) {
      Eigen::Vector2d f;
      if (!conditions(y12, f, jac_at)) return false;
      at = y12;
      r = f;
    }
    jac = jac_at;
    return true;
  };
  problem.max_step = [&](const Eigen::VectorXd& y12) -> Eigen::VectorXd {
    if (!pb.signed_power) return Eigen::Vector2d::Constant(kMaxLogKappaStep);
    const double floor = yScale(pb, length);
    return kMaxRelativeQStep * y12.cwiseAbs().cwiseMax(floor);
  };
  LeastSquaresOptions options;
  options.max_iterations = kLawStartIterations;
  options.tolerance = kLawStartTolerance;
  options.cost = LeastSquaresCost::kLargest;
  options.max_halvings = kMaxHalvings - 1;
  Eigen::VectorXd y12 = Eigen::Vector2d(linear[1], linear[2]), r;
  if (solveLeastSquares(problem, y12, r, options).end != LeastSquaresEnd::kConverged) return linear;
  return {linear[0], y12[0], y12[1]};
}

TripleLaHermiteSolve fail(SolveStatus status, const std::string& message, int iterations = 0,
                          double residual = INFINITY) {
  TripleLaHermiteSolve out;
  out.report.status = status;
  out.report.message = message;
  out.report.iterations = iterations;
  out.report.residual = residual;
  return out;
}

}  // namespace

TripleLaHermiteSolve solveTripleLaHermite(double alpha, const HermiteEnd& start, const HermiteEnd& end,
                                          const TripleLaHermiteOptions& options) {
  // --- input checks ---
  if (std::isnan(alpha) || !allFinite(start.point) || !allFinite(end.point) || !std::isfinite(start.theta) ||
      !std::isfinite(end.theta) || !std::isfinite(start.kappa) || !std::isfinite(end.kappa))
    return fail(SolveStatus::kBadInput, "alpha is NaN or an end condition is not finite");
  if (!(options.tolerance > 0.0) || options.max_iterations < 1)
    return fail(SolveStatus::kBadInput, "tolerance must be positive and max_iterations at least 1");
  const Vec2 chord_vec = end.point - start.point;
  const double chord = chord_vec.norm();
  const double extent = std::max({start.point.norm(), end.point.norm(), 1e-300});
  if (!(chord > 1e-14 * extent)) return fail(SolveStatus::kBadInput, "start and end points coincide");
  const double chord_angle = angleOf(chord_vec);
  const double phi0 = wrapAngle(start.theta - chord_angle);
  const double turning = end.theta - start.theta;
  const double k0 = start.kappa * chord, k3 = end.kappa * chord;

  TripleLaHermiteSolve out;
  std::vector<LaSegment> chain;  // normalized frame
  Vars solution = Vars::Zero();
  int iterations = 0;
  double residual = INFINITY;
  std::string how;

  if (std::isinf(alpha)) {
    // Circular arcs joined G2 are one circle.
    if (k0 != k3)
      return fail(SolveStatus::kInfeasible,
                  "alpha = inf gives circular arcs, which join G2 only into one circle: start.kappa must equal end.kappa");
    const double length = (k0 == 0.0) ? 1.0 : turning / k0;
    if (!(length > 0.0) || (k0 == 0.0 && turning != 0.0))
      return fail(SolveStatus::kInfeasible, "alpha = inf: the turning has the wrong sign for the circle's curvature");
    Vec2 pos = Vec2::Zero();
    double theta = phi0;
    for (double f : kPieceFraction) {
      chain.push_back(LaSegment::arc(f * length, pos, theta, k0));
      pos = chain.back().end();
      theta = chain.back().theta(f * length);
    }
    residual = std::max((pos - Vec2(1, 0)).norm(), std::abs(theta - phi0 - turning));
    if (!(residual <= options.tolerance))
      return fail(SolveStatus::kInfeasible,
                  "alpha = inf: the ends do not lie on one circle of the given curvature and turning (miss " +
                      std::to_string(residual) + " of the chord)",
                  0, residual);
    solution = {std::log(length), k0, k0};
    how = "one circle";
  } else {
    if (alpha >= 0.0) {
      if (k0 == 0.0 || k3 == 0.0)
        return fail(SolveStatus::kInfeasible, "a zero end curvature (inflection end) needs alpha < 0");
      if (k0 * k3 < 0.0)
        return fail(SolveStatus::kInfeasible,
                    "opposite-sign end curvatures need an inflection, which LA pieces with alpha >= 0 cannot have");
      const double sigma = k0 > 0.0 ? 1.0 : -1.0;
      if (!(sigma * turning > 0.0))
        return fail(SolveStatus::kInfeasible,
                    "with alpha >= 0 the curvature keeps the sign of the end curvatures, so the turning "
                    "end.theta - start.theta must have that sign");
      // A convex curve turning by less than pi has its chord between its end tangents.
      if (sigma * turning < kPi && !(sigma * phi0 < 0.0 && sigma * (phi0 + turning) > 0.0))
        return fail(SolveStatus::kInfeasible,
                    "with alpha >= 0 the curve is convex; turning less than pi, its chord must lie between the "
                    "end tangents");
    }
    const Problem pb = makeProblem(alpha, phi0, turning, k0, k3);
    Workspace ws;
    const double bez = bezierLength(phi0, phi0 + turning);
    auto tryFrom = [&](const Problem& problem, const Vars& x0, const char* label) -> bool {
      if (!usableStart(problem, x0)) return false;
      Attempt at = newtonSolve(problem, x0, options, ws);
      iterations += at.iterations;
      if (at.converged) {
        chain = std::move(at.chain);
        solution = at.x;
        residual = at.residual;
        how = label;
        return true;
      }
      residual = std::min(residual, at.residual);
      how = at.why;
      return false;
    };
    const Vars linear_start = linearStart(pb, bez), law_start = lawStart(pb, bez, linear_start);
    bool done = tryFrom(pb, law_start, "small-deflection start");
    if (!done && law_start != linear_start) done = tryFrom(pb, linear_start, "small-deflection start, clothoid profile");
    if (!done && alpha != -1.0) {
      // Continuation in alpha from the triple clothoid.
      const Problem clothoid = makeProblem(-1.0, phi0, turning, k0, k3);
      Attempt at = newtonSolve(clothoid, linearStart(clothoid, bez), options, ws);
      iterations += at.iterations;
      if (at.converged) {
        Problem prev = clothoid;
        Vars x = at.x;
        bool ok = true;
        for (int step = 1; step <= kContinuationSteps && ok; ++step) {
          const double a = -1.0 + (alpha + 1.0) * step / kContinuationSteps;
          // Skip alpha values where the parametrization switches inside the path (a in [0, ...)).
          const Problem next = (step == kContinuationSteps) ? pb : makeProblem(a, phi0, turning, k0, k3);
          if (step < kContinuationSteps && (a >= 0.0) != (alpha >= 0.0)) continue;
          const Vars x0 = convert(prev, next, x);
          if (!usableStart(next, x0)) {
            ok = false;
            break;
          }
          if (step == kContinuationSteps) {
            done = tryFrom(pb, x0, "continuation from alpha = -1");
            break;
          }
          Attempt mid = newtonSolve(next, x0, options, ws);
          iterations += mid.iterations;
          if (!mid.converged) {
            ok = false;
            break;
          }
          prev = next;
          x = mid.x;
        }
      }
    }
    for (double factor : kLengthFactors) {
      if (done) break;
      done = tryFrom(pb, linearStart(pb, factor * bez), "small-deflection start, other length");
    }
    if (!done)
      return fail(SolveStatus::kIterationLimit,
                  "no triple-LA curve found for alpha = " + std::to_string(alpha) +
                      ": Newton did not converge from any start (last: " + how + ")",
                  iterations, residual);
  }

  // --- back to the caller's frame ---
  Curve curve;
  const Eigen::Rotation2Dd rot(chord_angle);
  for (const LaSegment& s : chain) {
    const Vec2 p = start.point + chord * (rot * s.start());
    const double theta0 = start.theta + (s.theta0() - phi0);
    curve.pieces.push_back({LaSegment(s.alpha(), s.length() * chord, p, theta0, s.kappaStart() / chord,
                                      s.kappaEnd() / chord),
                            false});
  }
  const Problem pb = makeProblem(std::isinf(alpha) ? -1.0 : alpha, phi0, turning, k0, k3);
  out.curve = std::move(curve);
  out.length = std::exp(solution[0]) * chord;
  out.kappa1 = (std::isinf(alpha) ? solution[1] : pb.kappaOf(solution[1])) / chord;
  out.kappa2 = (std::isinf(alpha) ? solution[2] : pb.kappaOf(solution[2])) / chord;
  out.report.status = SolveStatus::kConverged;
  out.report.iterations = iterations;
  out.report.residual = residual;
  out.report.message = "converged (" + how + ")";
  return out;
}

}  // namespace la
