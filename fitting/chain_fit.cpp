#include "fitting/chain_fit.h"

#include <ceres/jet.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/quadrature.h"

namespace la {
namespace {

// Forward-mode derivatives of a segment's local curve by its own four unknowns.
using Jet = ceres::Jet<double, 4>;
enum LocalUnknown { kAlpha = 0, kLogKappaStart = 1, kLogKappaEnd = 2, kLogTurning = 3 };

// A joint's |kappa| stays above this fraction of the chain's largest: towards 0 a law
// with alpha > 0 turns abruptly (rho^alpha runs to infinity), a trap for the solver. A
// stroke that really wants zero curvature there has an inflection the segmentation
// missed; the pipeline splits it.
constexpr double kKappaFloor = 1e-3;
// A segment turns at most this much (radians, eight whole turns; more if it starts so):
// an LA spiral may wind a few times, but a trial step that winds it thousands of times
// is a solver astray, and one such segment costs its quadrature tens of milliseconds.
constexpr double kMaxSegmentTurning = 16.0 * std::numbers::pi;
// Largest change of an unknown in one step (normalized frame: unit diagonal): the
// linear model of a chain is trusted only this far. A longer step is scaled down whole.
constexpr double kMaxAlphaStep = 1.0, kMaxRelativeKappaStep = 0.5, kMaxLogTurningStep = 0.5, kMaxAngleStep = 0.5,
                 kMaxPointStep = 0.2;
// Panels (see panelGrid): largest turning (radians), largest width (fraction of the
// length), and the grading of v ~ rho^alpha towards its small end (largest ratio of v
// across a panel, down to a smallest v). Positions between panel ends are quintic
// Hermite interpolants (position, tangent and curvature at both ends). On the fitting
// grid they stay within ~2e-6 of the segment length of LaSegment's adaptive quadrature
// (measured on the tests' laws: far below any noise, and a model build is cheap); the
// Jacobian's grid is coarser still (derivatives need a few digits, not ten); distances
// reported to the user come from the measuring grid, within ~1e-9.
struct GridRule {
  double turning, width, grading, smallest;
};
constexpr GridRule kFittingGrid{0.25, 0.5, 0.5, 1e-4};
constexpr GridRule kJacobianGrid{0.5, 0.5, 0.25, 1e-3};
constexpr GridRule kMeasuringGrid{0.1, 0.0625, 0.7071067811865476, 1e-6};
constexpr int kMaxPanels = 512;
constexpr int kPanelNodes = 3;  // Gauss-Legendre nodes per panel where buildPanels does not take its Hermite rule
// Below this |x| the series of expm1(x)/x and log1p(x)/x are exact to rounding.
constexpr double kSeriesLimit = 1e-4;
// Newton steps per foot and per evaluation (the feet move little between steps), and
// nodes per segment of the polyline that gives the first feet when none are passed.
constexpr int kFootSteps = 1, kFirstFootSteps = 3, kFinalFootSteps = 1;
constexpr double kFootMoved = 1e-6;  // of a segment's parameter: a foot that moves less has arrived
constexpr int kCoarseFeetSamples = 64;
// A point further than this many times the root mean square distance has its foot
// looked for again over the whole chain (refineOutlyingFeet).
constexpr double kOutlyingFoot = 3.0;
// A bin of points stands in by its centroid where the chain's sagitta across it is at
// most this fraction of the noise (the bias then adds at most 1% to a point's variance).
constexpr double kBinBias = 0.1;
// A segment shorter than ChainFitOptions::min_length costs as much as a point this many
// noise sigmas off per e-fold it is shorter: least squares would shrink a segment to
// nothing to follow a sharp vertex of the points with a bend no point can place.
constexpr double kShortSegmentWeight = 10.0;
// Levenberg-Marquardt damping: start, growth on a rejected step, shrink on an accepted one.
constexpr double kInitialLambda = 1e-4, kLambdaGrowth = 8.0, kLambdaShrink = 4.0, kMaxLambda = 1e10;
// A step that the caps (kMaxAlphaStep...) would shorten to less than this fraction is
// damped once more (by kLambdaGrowth) before it is shortened, where no constraint holds
// the chain (there the move onto the constraints, which damping does not shorten, is
// most of a long step). Scaled down whole, a Gauss-Newton step far beyond the caps keeps
// a direction the linear model does not vouch for; damped, it turns towards the
// gradient, as a trust region's step would. On the shared data (data_benchmark
// --variants=8) 64 segments and 50 extrema fewer of 9,238 and 4,953, walked strokes 55
// and 51 fewer, for 0.4% more instructions; damped up to three times by 4: 53 and 46
// fewer for 2.5% more; at a cap under a quarter: 24 and 38 more; also under constraints:
// 6% more instructions.
constexpr double kCappedStep = 0.5;
// Weight of a constraint violation (squared) in the merit function that accepts steps:
// the steps satisfy the linearized constraints, so this only keeps the iterates from
// trading closure for fit.
constexpr double kConstraintMerit = 1e8;
constexpr double kNegligibleDecrease = 0.1;
// Closing the constraints after the iterations (which keep them only as far as their
// merit asks): at most this many Newton steps on the exact chain, until its violation
// (normalized units) is below kExactlyClosed. LaSegment's positions are good to ~1e-10
// of a length, and a tighter target only repeats its quadrature.
constexpr int kRestoreSteps = 5;
constexpr double kExactlyClosed = 1e-11;
// A chain meets its constraints (joints, closure, a fixed end) below this violation
// (normalized units); snapToJoints closes what is left exactly.
constexpr double kAdmissible = 1e-7;
// snapToJoints takes a chain as ending where it should, or a closed one as closed, when
// the gaps (position, fraction of its length; tangent, radians) are below this.
constexpr double kClosed = 1e-10;
// A held start's curvature this close to the bound on curvature (relative) is on it: the
// rounding of the units between two fits.
constexpr double kBoundRounding = 1e-12;

inline double valueOf(double x) { return x; }
inline double valueOf(const Jet& x) { return x.a; }

// expm1(x) / x and log1p(x) / x, smooth through x = 0.
template <typename T>
T expm1OverX(const T& x) {
  using std::expm1;
  if (std::abs(valueOf(x)) < kSeriesLimit) return 1.0 + x * (0.5 + x * (1.0 / 6.0 + x * (1.0 / 24.0)));
  return expm1(x) / x;
}
// e^x and (e^x - 1) / x by one transcendental call: expm1 where |x| is small (e^x - 1
// would cancel there), exp elsewhere (1 + expm1(x) would cancel where e^x is tiny).
constexpr double kExpm1Limit = 0.5;
template <typename T>
void expAndExpm1OverX(const T& x, T& exp_x, T& expm1_over_x) {
  using std::exp;
  if (std::abs(valueOf(x)) < kExpm1Limit) {
    expm1_over_x = expm1OverX(x);
    exp_x = 1.0 + x * expm1_over_x;
  } else {
    exp_x = exp(x);
    expm1_over_x = (exp_x - 1.0) / x;
  }
}
template <typename T>
T log1pOverX(const T& x) {
  using std::log1p;
  if (std::abs(valueOf(x)) < kSeriesLimit) return 1.0 + x * (-0.5 + x * (1.0 / 3.0 - x * 0.25));
  return log1p(x) / x;
}

// Which ends of a segment have zero curvature (both: a straight line).
enum class ZeroEnd { kNone, kStart, kEnd, kBoth };

// The law of one segment: alpha, log|kappa| at both ends (unused at a zero end), length
// and turning direction. A line has only its length.
struct Law {
  double alpha = -1.0, y0 = 0.0, y1 = 0.0, length = 1.0, sign = 1.0;
  double log_turning = 0.0;  // log of |total turning| (the unknown that sets the length; a line's: log length)
  double turning = 0.0;      // |total turning| (radians; the panels follow it)
  ZeroEnd zero = ZeroEnd::kNone;
};

// theta(u) - theta(0) and kappa(u) of an LA segment at fraction u of its length, from
// alpha, y0 = log|kappa_start|, y1 = log|kappa_end|, its length and turning sign; for
// doubles or for Jets carrying derivatives. With rho(u)^alpha = rho0^alpha (1 + r u),
// r = (rho1/rho0)^alpha - 1 = expm1(alpha l), l = y0 - y1:
//   integral_0^u kappa/kappa0 = ((1 + r u)^(1 - 1/alpha) - 1) / (r (1 - 1/alpha))
//                             = E(z) u G(r u),  z = (alpha - 1) R u G(r u),  R = r / alpha = l E(alpha l),
// with E(x) = expm1(x)/x and G(x) = log1p(x)/x: no division by alpha, alpha - 1 or l,
// so alpha = 0 (Nielsen's spiral), alpha = 1 (log spiral) and the circle (l = 0) need no
// case of their own. A zero end (alpha < 0, e = 1 - 1/alpha > 1): kappa ~ (1 - u)^(e - 1)
// towards a zero end, u^(e - 1) from a zero start. The segment's constants are computed
// once: two transcendental calls a node, the hot loop of every model build.
template <typename T>
class LawEvaluator {
 public:
  LawEvaluator(const T& alpha, const T& y0, const T& y1, const T& length, double sign, ZeroEnd zero)
      : alpha_(alpha), zero_(zero) {
    using std::exp;
    if (zero == ZeroEnd::kNone) {
      const T l = y0 - y1;
      big_r_ = l * expm1OverX(alpha * l);
      kappa_ref_ = sign * exp(y0);
    } else if (zero != ZeroEnd::kBoth) {
      e_ = 1.0 - 1.0 / alpha;
      kappa_ref_ = sign * exp(zero == ZeroEnd::kEnd ? y0 : y1);
    }
    turning_ref_ = length * kappa_ref_;
  }

  T theta(double u) const {
    T theta_u{}, kappa_u{};
    thetaAndKappa(u, theta_u, kappa_u);
    return theta_u;
  }
  // theta(u) and kappa(u) from one logarithm and one exponential: with v = 1 + alpha R u
  // (v ~ rho^alpha), kappa / kappa0 = v^(-1/alpha) = e^z / v for the z = (alpha - 1) / alpha
  // log v that theta needs anyway (zero ends alike, v = 1 - u or u).
  void thetaAndKappa(double u, T& theta_u, T& kappa_u) const {
    T exp_z, expm1_over_z;
    switch (zero_) {
      case ZeroEnd::kNone: {
        const T x = alpha_ * big_r_ * u, g = log1pOverX(x);
        expAndExpm1OverX(T((alpha_ - 1.0) * big_r_ * u * g), exp_z, expm1_over_z);
        theta_u = turning_ref_ * u * g * expm1_over_z;
        kappa_u = kappa_ref_ * exp_z / (1.0 + x);
        return;
      }
      case ZeroEnd::kEnd: {
        if (u >= 1.0) {
          theta_u = turning_ref_ / e_, kappa_u = T(0.0);
          return;
        }
        const double l = std::log1p(-u);
        const T z = e_ * l;
        expAndExpm1OverX(z, exp_z, expm1_over_z);
        theta_u = -turning_ref_ * l * expm1_over_z;  // (-turning_ref (e^z - 1) / e)
        kappa_u = kappa_ref_ * exp_z / (1.0 - u);
        return;
      }
      case ZeroEnd::kStart: {
        if (u <= 0.0) {
          theta_u = kappa_u = T(0.0);
          return;
        }
        using std::exp;
        exp_z = exp(e_ * std::log(u));
        theta_u = turning_ref_ * exp_z / e_;
        kappa_u = kappa_ref_ * exp_z / u;
        return;
      }
      case ZeroEnd::kBoth: theta_u = kappa_u = T(0.0); return;
    }
  }
  // d2kappa/du2, given kappa and its slope at u (not at a zero end): kappa is a power
  // -1/alpha of a variable linear in u at every law, so kappa'' = (1 + alpha) kappa'^2 / kappa
  // (0 where kappa is: a line, or a law whose kappa underflows, a line to doubles).
  T kappaBow(const T& kappa, const T& slope) const {
    return valueOf(kappa) == 0.0 ? T(0.0) : T((1.0 + alpha_) * slope * slope / kappa);
  }
  // dkappa/du at u, given kappa there (not at a zero end: its slope may be infinite).
  T kappaSlope(double u, const T& kappa) const {
    switch (zero_) {
      case ZeroEnd::kNone: return -big_r_ * kappa / (1.0 + alpha_ * big_r_ * u);  // kappa ~ (1 + alpha R u)^(-1/alpha)
      case ZeroEnd::kEnd: return kappa / (alpha_ * (1.0 - u));                    // kappa ~ (1 - u)^(-1/alpha)
      case ZeroEnd::kStart: return -kappa / (alpha_ * u);                         // kappa ~ u^(-1/alpha)
      case ZeroEnd::kBoth: return T(0.0);
    }
    return T(0.0);
  }

 private:
  T alpha_;
  ZeroEnd zero_;
  T big_r_{0.0}, e_{1.0}, kappa_ref_{0.0}, turning_ref_{0.0};
};

// |total turning| of a law per unit length: its length is |turning| over this.
template <typename T>
T unitTurning(const T& alpha, const T& y0, const T& y1, ZeroEnd zero) {
  return LawEvaluator<T>(alpha, y0, y1, T(1.0), 1.0, zero).theta(1.0);
}

// Panel ends (fractions of the length) on which a segment is integrated and
// interpolated: each panel turns at most rule.turning, is at most rule.width of the
// length, and the law's variable v ~ rho^alpha (linear in u) changes by at most a factor
// 1/rule.grading across it. The last rule grades the panels geometrically towards an end
// where v is small against the other end: there kappa behaves like a power of the
// distance to a (virtual) zero of v, whose derivatives blow up.
// (into `out`, whose storage a model build reuses: a grid per segment and build was two
// allocations, a few percent of the fit)
void panelGrid(const Law& law, const GridRule& rule, std::vector<double>& out) {
  const int widths = static_cast<int>(std::ceil(1.0 / rule.width));
  out.clear();
  const auto uniform = [&] {
    for (int k = 0; k <= widths; ++k) out.push_back(static_cast<double>(k) / widths);
  };
  if (law.zero == ZeroEnd::kBoth) return uniform();  // a line: positions are exact on any panels
  double v0 = 1.0, v1 = 1.0;
  const double turning = law.turning;
  // (e only where an end is zero: for alpha = 0, Nielsen's spiral, it is infinite, and the
  // check below took the law for a broken one and gave it uniform panels, turning by
  // radians each: a 2.5-turn spiral's fit from its own segment drifted 41 units off)
  const double e = law.zero == ZeroEnd::kNone ? 1.0 : 1.0 - 1.0 / law.alpha;
  if (law.zero == ZeroEnd::kNone) v1 = std::exp(law.alpha * (law.y0 - law.y1));
  else (law.zero == ZeroEnd::kStart ? v0 : v1) = 0.0;
  // A law doubles cannot evaluate: a wild step's NaN unknown, or 1 + r rounding to 0
  // where alpha (y0 - y1) < -37 (the law's length comes out NaN though the segment
  // exists), or v1 overflowing. Its positions come out NaN on any panels and buildModel
  // refuses it like an overflow; the uniform panels only keep the count an int (a NaN
  // cast to int here was undefined behaviour: the fit fuzzer's first finding).
  if (!std::isfinite(turning) || !std::isfinite(law.length) || !std::isfinite(e) || !std::isfinite(v1)) return uniform();
  thread_local std::vector<double> grid;
  grid.clear();
  // Equal turning: uniform for the bound, graded as turning ~ u^e from a zero start
  // (clamped as a double: beyond int range the cast would be undefined too).
  const int panels = static_cast<int>(std::clamp(std::ceil(turning / rule.turning), 1.0, static_cast<double>(kMaxPanels)));
  for (int k = 0; k <= panels; ++k) {
    const double f = static_cast<double>(k) / panels;
    grid.push_back(law.zero == ZeroEnd::kNone    ? f
                   : law.zero == ZeroEnd::kStart ? std::pow(f, 1.0 / e)
                                                 : 1.0 - std::pow(1.0 - f, 1.0 / e));
  }
  for (int k = 1; k < widths; ++k) grid.push_back(static_cast<double>(k) / widths);
  // kappa ~ v^(-1/alpha) changes faster than v for |alpha| < 1: below |alpha| = 1/2, v
  // is graded finer, so that kappa changes by at most the grading squared per panel
  // (steep laws running into an inflection: alpha -0.05 puts kappa ~ (1 - u)^20).
  const double power = std::min(1.0, 2.0 * std::abs(law.alpha));
  // (x^1 is x: no call for the laws with |alpha| >= 1/2, a percent of the fits' instructions)
  const double grading = power == 1.0 ? rule.grading : std::pow(rule.grading, power);
  const double smallest = power == 1.0 ? rule.smallest : std::pow(rule.smallest, power);
  const double v_max = std::max(v0, v1), v_min = std::max(std::min(v0, v1), smallest * v_max);
  for (double v = grading * v_max; v > v_min; v *= grading) grid.push_back((v - v0) / (v1 - v0));
  if (std::min(v0, v1) == 0.0) grid.push_back((v_min - v0) / (v1 - v0));
  std::sort(grid.begin(), grid.end());
  for (double u : grid) {
    u = std::clamp(u, 0.0, 1.0);
    if (out.empty() || u > out.back() + 1e-12) out.push_back(u);
  }
  out.back() = 1.0;
}

// A segment's local curve (start at the origin heading along +x) at its panel ends:
// position, tangent angle (with its cosine and sine) and signed curvature, as doubles
// or as Jets carrying their derivatives by the segment's four local unknowns.
template <typename T>
struct Panels {
  T length{};  // the segment's length (with its derivatives, for Jets)
  std::vector<double> grid;
  std::vector<T> x, y, theta, c, s, kappa;

  std::size_t panelOf(double u) const {
    const auto it = std::upper_bound(grid.begin(), grid.end(), u);
    const std::size_t k = it == grid.begin() ? 0 : static_cast<std::size_t>(it - grid.begin()) - 1;
    return std::min(k, grid.size() - 2);
  }
  // Per panel, the quintic Hermite interpolant of the position (below) as a polynomial
  // in t = (u - u_i) / h_i: filled by prepare() for the double panels.
  std::vector<std::array<double, 6>> poly_x, poly_y;
  std::vector<double> inverse_width;

  void prepare(double length) {
    const std::size_t panels = grid.size() - 1;
    poly_x.resize(panels);
    poly_y.resize(panels);
    inverse_width.resize(panels);
    auto coefficients = [](double p0, double v0, double w0, double p1, double v1, double w1) {
      return std::array<double, 6>{p0, v0, 0.5 * w0, -10 * p0 - 6 * v0 - 1.5 * w0 + 10 * p1 - 4 * v1 + 0.5 * w1,
                                   15 * p0 + 8 * v0 + 1.5 * w0 - 15 * p1 + 7 * v1 - w1,
                                   -6 * p0 - 3 * v0 - 0.5 * w0 + 6 * p1 - 3 * v1 + 0.5 * w1};
    };
    for (std::size_t i = 0; i < panels; ++i) {
      const double h = grid[i + 1] - grid[i], hl = h * length, hl2 = hl * hl;
      inverse_width[i] = 1.0 / h;
      poly_x[i] = coefficients(x[i], hl * c[i], -hl2 * kappa[i] * s[i], x[i + 1], hl * c[i + 1], -hl2 * kappa[i + 1] * s[i + 1]);
      poly_y[i] = coefficients(y[i], hl * s[i], hl2 * kappa[i] * c[i], y[i + 1], hl * s[i + 1], hl2 * kappa[i + 1] * c[i + 1]);
    }
  }
  // Position, unit tangent and (linearly interpolated) curvature at u, from the
  // prepared polynomials: no transcendental function, the hot loop of the foot projection.
  void frame(double u, Vec2& point, Vec2& tangent, double& curvature) const {
    const std::size_t i = panelOf(u);
    const double t = (u - grid[i]) * inverse_width[i];
    const auto& a = poly_x[i];
    const auto& b = poly_y[i];
    point = {a[0] + t * (a[1] + t * (a[2] + t * (a[3] + t * (a[4] + t * a[5])))),
             b[0] + t * (b[1] + t * (b[2] + t * (b[3] + t * (b[4] + t * b[5]))))};
    tangent = Vec2(a[1] + t * (2 * a[2] + t * (3 * a[3] + t * (4 * a[4] + t * 5 * a[5]))),
                   b[1] + t * (2 * b[2] + t * (3 * b[3] + t * (4 * b[4] + t * 5 * b[5]))))
                  .normalized();
    curvature = kappa[i] + t * (kappa[i + 1] - kappa[i]);
  }
  // Quintic Hermite position at u: positions, first derivatives L (cos, sin) and second
  // derivatives L^2 kappa (-sin, cos) in u at the panel's ends.
  void position(double u, const T& length, T& out_x, T& out_y) const {
    const std::size_t i = panelOf(u);
    const double h = grid[i + 1] - grid[i], t = (u - grid[i]) / h;
    const double t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
    const double h0 = 1 - 10 * t3 + 15 * t4 - 6 * t5, h3 = 1 - h0;
    const double h1 = (t - 6 * t3 + 8 * t4 - 3 * t5) * h, h4 = (-4 * t3 + 7 * t4 - 3 * t5) * h;
    const double h2 = 0.5 * (t2 - 3 * t3 + 3 * t4 - t5) * h * h, h5 = 0.5 * (t3 - 2 * t4 + t5) * h * h;
    const T l2 = length * length;
    out_x = h0 * x[i] + h3 * x[i + 1] + length * (h1 * c[i] + h4 * c[i + 1]) -
            l2 * (h2 * kappa[i] * s[i] + h5 * kappa[i + 1] * s[i + 1]);
    out_y = h0 * y[i] + h3 * y[i + 1] + length * (h1 * s[i] + h4 * s[i + 1]) +
            l2 * (h2 * kappa[i] * c[i] + h5 * kappa[i + 1] * c[i + 1]);
  }
};

// sin and cos of an angle, for a Jet from one sine and one cosine of its value (Ceres'
// sin and cos of a Jet each take both: four calls where two do, in the hot loop of every
// Jacobian; the same arithmetic, so the same bits).
inline void sinCos(double t, double& s, double& c) {
  s = std::sin(t);
  c = std::cos(t);
}
inline void sinCos(const Jet& t, Jet& s, Jet& c) {
  const double sa = std::sin(t.a), ca = std::cos(t.a);
  s = Jet(sa, ca * t.v);
  c = Jet(ca, -sa * t.v);
}

// The panels of a law, for the fit's model (doubles, on the fitting grid) or its Jacobian
// (Jets, on the coarser Jacobian grid). Positions on each panel by a Hermite rule from the
// tangent (cos, sin) of theta and its derivatives at the panel ends, which come from the
// ends' theta, kappa and kappa's slopes (closed forms). The model's rule,
//   integral over [0, 1] of f = 1/2 (f0 + f1) + 3/28 (f0' - f1') + 1/84 (f0'' + f1'')
//                               + 1/1680 (f0''' - f1'''),
// exact to degree 7, evaluates the law once a panel, at its end (the law's evaluations
// are most of a fit's time). The Jacobian's rule takes the middle's value instead of the
// third derivatives,
//   integral over [0, 1] of f = 19/70 (f0 + f1) + 1/35 (f0' - f1') + 1/840 (f0'' + f1'')
//                               + 16/35 f(1/2),
// also exact to degree 7 and eight times closer: its panels turn by up to half a radian
// and the first rule's Jacobian was too coarse for a steep law's fit to converge (alpha
// 2.9, fitted back from off its truth, crawled to the iteration limit). Gauss-Legendre
// with 3 nodes where a panel ends at a zero end (kappa's slope may be infinite there) or
// bends by more than a radian at an end (the derivatives then outgrow the rules).
template <typename T>
void buildPanels(const Law& law, Panels<T>& p) {
  constexpr bool kJacobian = std::is_same_v<T, Jet>;
  panelGrid(law, kJacobian ? kJacobianGrid : kFittingGrid, p.grid);
  T alpha(law.alpha), y0(law.y0), y1(law.y1), length(law.length);
  if constexpr (kJacobian) {
    alpha.v[kAlpha] = 1.0;
    y0.v[kLogKappaStart] = 1.0;
    y1.v[kLogKappaEnd] = 1.0;
    // L = |turning| / (turning of the unit-length segment): the length follows alpha and
    // the end curvatures at a fixed turning.
    Jet log_turning(law.log_turning);
    log_turning.v[kLogTurning] = 1.0;
    length = law.zero == ZeroEnd::kBoth ? exp(log_turning) : exp(log_turning) / unitTurning(alpha, y0, y1, law.zero);
  }
  p.length = length;
  const LawEvaluator<T> evaluator(alpha, y0, y1, length, law.sign, law.zero);
  auto theta = [&](double u) { return evaluator.theta(u); };
  using std::abs;
  const auto& rule = gaussLegendre<kPanelNodes>();
  const std::size_t n = p.grid.size();
  for (auto* v : {&p.x, &p.y, &p.theta, &p.c, &p.s, &p.kappa}) v->resize(n);
  // dkappa/du at the panel ends, and for doubles d2kappa/du2 (unset at a zero end)
  thread_local std::vector<T> slope, bow;
  slope.resize(n);
  if constexpr (!kJacobian) bow.resize(n);
  p.x[0] = p.y[0] = T(0.0);
  auto atZeroEnd = [&](std::size_t k) {
    return (law.zero == ZeroEnd::kStart && k == 0) || (law.zero == ZeroEnd::kEnd && k + 1 == n);
  };
  for (std::size_t k = 0; k < n; ++k) {
    evaluator.thetaAndKappa(p.grid[k], p.theta[k], p.kappa[k]);
    sinCos(p.theta[k], p.s[k], p.c[k]);
    if (!atZeroEnd(k)) {
      slope[k] = evaluator.kappaSlope(p.grid[k], p.kappa[k]);
      if constexpr (!kJacobian) bow[k] = evaluator.kappaBow(p.kappa[k], slope[k]);
    }
    if (k == 0) continue;
    const double a = p.grid[k - 1], h = p.grid[k] - a;
    T cx(0.0), cy(0.0);
    const T bend0 = (h * length) * p.kappa[k - 1], bend1 = (h * length) * p.kappa[k];  // dtheta/dt at the ends
    // (in t = (u - a) / h, with theta' = h L kappa, theta'' = h^2 L kappa_u and theta''' =
    // h^3 L kappa_uu: (cos, sin)' = theta' (-sin, cos), (cos, sin)'' = -theta'^2 (cos, sin)
    // + theta'' (-sin, cos), (cos, sin)''' = (theta'^3 - theta''') (sin, -cos)
    // - 3 theta' theta'' (cos, sin))
    const T& c0 = p.c[k - 1];
    const T& s0 = p.s[k - 1];
    const T& c1 = p.c[k];
    const T& s1 = p.s[k];
    if (atZeroEnd(k - 1) || atZeroEnd(k) || abs(bend0) > T(1.0) || abs(bend1) > T(1.0)) {
      for (int g = 0; g < kPanelNodes; ++g) {
        T st, ct;
        sinCos(theta(a + h * rule.node[g]), st, ct);
        cx += rule.weight[g] * ct;
        cy += rule.weight[g] * st;
      }
    } else if constexpr (kJacobian) {
      const T curl0 = (h * h) * length * slope[k - 1], curl1 = (h * h) * length * slope[k];
      T sm, cm;
      sinCos(theta(a + 0.5 * h), sm, cm);
      cx = (19.0 / 70.0) * (c0 + c1) + (1.0 / 35.0) * (bend1 * s1 - bend0 * s0) +
           (1.0 / 840.0) * (-bend0 * bend0 * c0 - curl0 * s0 - bend1 * bend1 * c1 - curl1 * s1) + (16.0 / 35.0) * cm;
      cy = (19.0 / 70.0) * (s0 + s1) + (1.0 / 35.0) * (bend0 * c0 - bend1 * c1) +
           (1.0 / 840.0) * (-bend0 * bend0 * s0 + curl0 * c0 - bend1 * bend1 * s1 + curl1 * c1) + (16.0 / 35.0) * sm;
    } else {
      const T curl0 = (h * h) * length * slope[k - 1], curl1 = (h * h) * length * slope[k];
      const T twist0 = (h * h * h) * length * bow[k - 1], twist1 = (h * h * h) * length * bow[k];
      const T cubed0 = bend0 * bend0 * bend0 - twist0, cubed1 = bend1 * bend1 * bend1 - twist1;
      const T cross0 = 3.0 * bend0 * curl0, cross1 = 3.0 * bend1 * curl1;
      cx = 0.5 * (c0 + c1) + (3.0 / 28.0) * (bend1 * s1 - bend0 * s0) +
           (1.0 / 84.0) * (-bend0 * bend0 * c0 - curl0 * s0 - bend1 * bend1 * c1 - curl1 * s1) +
           (1.0 / 1680.0) * (cubed0 * s0 - cross0 * c0 - cubed1 * s1 + cross1 * c1);
      cy = 0.5 * (s0 + s1) + (3.0 / 28.0) * (bend0 * c0 - bend1 * c1) +
           (1.0 / 84.0) * (-bend0 * bend0 * s0 + curl0 * c0 - bend1 * bend1 * s1 + curl1 * c1) +
           (1.0 / 1680.0) * (-cubed0 * c0 - cross0 * s0 + cubed1 * c1 + cross1 * s1);
    }
    p.x[k] = p.x[k - 1] + (h * length) * cx;
    p.y[k] = p.y[k - 1] + (h * length) * cy;
  }
}

Eigen::Matrix2d rotation(double a) { return Eigen::Rotation2Dd(a).toRotationMatrix(); }

// Where a point's foot is on a chain: position, unit tangent, curvature.
struct FootFrame {
  Vec2 point = Vec2::Zero();
  Vec2 tangent = Vec2::UnitX();
  double kappa = 0.0;
  Vec2 normal() const { return {-tangent.y(), tangent.x()}; }
};

// A chain as the foot projection sees it: per segment its law, its local panels and its
// start pose (with the rotation of its local frame).
struct ChainGeometry {
  std::vector<Law> laws;
  std::vector<Panels<double>> panels;
  std::vector<Vec2> start;     // pose of each segment's start, and of the chain's end
  std::vector<double> angle;
  std::vector<Eigen::Matrix2d> rotations;  // of each segment's start angle
  double total_length = 0.0;
  bool closed = false;
  std::vector<bool> corner;  // per segment: it starts at a corner (empty: none)

  std::size_t size() const { return laws.size(); }
  bool cornerAtStart(std::size_t i) const { return !corner.empty() && corner[i]; }
  bool cornerAtEnd(std::size_t i) const { return i + 1 < size() ? cornerAtStart(i + 1) : closed && cornerAtStart(0); }
  // A foot on a corner: the point's nearest point there has no normal through the point.
  bool atCorner(const ChainFoot& f) const {
    return (f.u == 0.0 && cornerAtStart(f.segment)) || (f.u == 1.0 && cornerAtEnd(f.segment));
  }
  double length(std::size_t i) const { return laws[i].length; }
  FootFrame frame(const ChainFoot& f) const {
    Vec2 p, t;
    double k;
    panels[f.segment].frame(f.u, p, t, k);
    const Eigen::Matrix2d& r = rotations[f.segment];
    return {start[f.segment] + r * p, r * t, k};
  }
};

// The segments a point's foot may be on, from `first` to `last` along the chain
// (through a closed chain's seam where first > last). With corners, those of the
// point's own part (between the corners around it); a corner's own point may be on
// either side of it, or is held at the corner (at the start of segment `held`).
struct FootRange {
  std::size_t first = 0, last = SIZE_MAX;
  bool corner = false;  // a corner's own point
  std::size_t held = SIZE_MAX;
  bool holds(std::size_t i) const { return first <= last ? i >= first && i <= last : i >= first || i <= last; }
};

// Newton steps on the closest-point condition t . (X - P(s)) = 0, s the arc length
// along the chain, crossing joints (and a closed chain's seam) as needed, within
// `range` if given (its ends stop the foot as the chain's do); returns the frame at the
// final foot. A step reaching a corner stops there.
FootFrame projectFoot(const ChainGeometry& g, const Vec2& point, ChainFoot& foot, int steps,
                      const FootRange* range = nullptr) {
  const std::size_t n = g.size();
  const std::size_t first = range ? range->first : 0, last = range ? std::min(range->last, n - 1) : n - 1;
  const bool wraps = g.closed && (!range || first > last);
  if (range && !range->holds(foot.segment)) foot = {first, 0.0};
  FootFrame f = g.frame(foot);
  for (int step = 0; step < steps; ++step) {
    const Vec2 d = point - f.point;
    const double ds = f.tangent.dot(d) / std::max(0.25, 1.0 - f.kappa * f.normal().dot(d));
    double s = foot.u * g.length(foot.segment) + ds;
    std::size_t i = foot.segment;
    for (std::size_t guard = 0; guard <= n && s > g.length(i); ++guard) {
      const std::size_t next = (i + 1) % n;
      if (i == last || (next == 0 && !wraps)) {
        s = g.length(i);
      } else if (g.cornerAtStart(next)) {
        // (on along the other side only if the point is ahead along it: else the corner
        // is the nearest point)
        const FootFrame other = g.frame({next, 0.0});
        if (other.tangent.dot(point - other.point) > 0.0) i = next, s = 0.0;
        else s = g.length(i);
        break;
      } else {
        s -= g.length(i);
        i = next;
      }
    }
    for (std::size_t guard = 0; guard <= n && s < 0.0; ++guard) {
      const std::size_t before = (i + n - 1) % n;
      if (i == first || (i == 0 && !wraps)) {
        s = 0.0;
      } else if (g.cornerAtStart(i)) {
        const FootFrame other = g.frame({before, 1.0});
        if (other.tangent.dot(point - other.point) < 0.0) i = before, s = g.length(before);
        else s = 0.0;
        break;
      } else {
        i = before;
        s += g.length(i);
      }
    }
    const ChainFoot moved{i, std::clamp(s / g.length(i), 0.0, 1.0)};
    const bool stuck = moved.segment == foot.segment && moved.u == foot.u;  // (at a corner)
    foot = moved;
    f = g.frame(foot);
    if (stuck || std::abs(ds) < 1e-13 * g.total_length) break;
  }
  return f;
}

// Nearest node of a polyline of the chain for every point: the first feet. (The nodes'
// coordinates apart and each point's search by whole segments: the search over every
// node for every point was 1.5% of the fits' instructions.)
std::vector<ChainFoot> coarseFeet(const ChainGeometry& g, const std::vector<Vec2>& points,
                                  const std::vector<FootRange>& ranges = {}) {
  constexpr int kNodes = kCoarseFeetSamples + 1;  // per segment
  thread_local std::vector<double> xs, ys;
  xs.clear(), ys.clear();
  for (std::size_t i = 0; i < g.size(); ++i)
    for (int k = 0; k < kNodes; ++k) {
      const Vec2 p = g.frame({i, static_cast<double>(k) / kCoarseFeetSamples}).point;
      xs.push_back(p.x()), ys.push_back(p.y());
    }
  std::vector<ChainFoot> feet(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const FootRange range = ranges.empty() ? FootRange{} : ranges[k];
    const double px = points[k].x(), py = points[k].y();
    double best = INFINITY;
    std::size_t nearest = SIZE_MAX;
    for (std::size_t i = 0; i < g.size(); ++i) {
      if (!range.holds(i)) continue;
      for (std::size_t j = i * kNodes; j < (i + 1) * kNodes; ++j) {
        const double dx = xs[j] - px, dy = ys[j] - py, d = dx * dx + dy * dy;
        if (d < best) best = d, nearest = j;
      }
    }
    if (nearest != SIZE_MAX)
      feet[k] = {nearest / kNodes, static_cast<double>(nearest % kNodes) / kCoarseFeetSamples};
  }
  return feet;
}

// Feet of the points whose distance is an outlier (more than kOutlyingFoot times the
// root mean square), found again from the nearest coarse node: a foot carried over from
// an edited chain or a rough start can sit on a far part of the chain, where Newton
// settles on a local closest point. `distance` (of the points at their feet) is updated.
// With `pinned_ends`, the first and last points keep theirs (an open chain's ends); with
// `ranges`, each foot stays within its point's range.
void refineOutlyingFeet(const ChainGeometry& g, const std::vector<Vec2>& points, std::vector<ChainFoot>& feet,
                        std::vector<double>& distance, bool pinned_ends = false,
                        const std::vector<FootRange>& ranges = {}) {
  double ssq = 0.0;
  for (double d : distance) ssq += d * d;
  const double limit = kOutlyingFoot * std::sqrt(ssq / static_cast<double>(distance.size()));
  std::vector<Vec2> far;
  std::vector<std::size_t> which;
  std::vector<FootRange> far_ranges;
  for (std::size_t k = pinned_ends ? 1 : 0; k + (pinned_ends ? 1 : 0) < points.size(); ++k)
    if (distance[k] > limit) {
      far.push_back(points[k]);
      which.push_back(k);
      if (!ranges.empty()) far_ranges.push_back(ranges[k]);
    }
  if (far.empty()) return;
  const std::vector<ChainFoot> fresh = coarseFeet(g, far, far_ranges);
  for (std::size_t j = 0; j < far.size(); ++j) {
    ChainFoot foot = fresh[j];
    const FootRange* range = far_ranges.empty() ? nullptr : &far_ranges[j];
    const double d = (projectFoot(g, far[j], foot, kFirstFootSteps, range).point - far[j]).norm();
    if (d < distance[which[j]]) {
      distance[which[j]] = d;
      feet[which[j]] = foot;
    }
  }
}

// Where the unknowns sit in the parameter vector, and their bounds.
struct Layout {
  std::size_t segments = 0;
  bool closed = false, fix_start = false, fix_end = false;
  int start = -1;                 // x of the start point (y follows), -1 if fixed
  int theta = 0;
  // per segment: its start and end curvatures (signed; -1 for zero), one unknown shared
  // by the two sides of a smooth joint, one per side at a corner
  std::vector<int> kappa_start, kappa_end;
  std::vector<int> corner_turn;   // per joint 0..n: the tangent's turn at a corner, else -1
  std::vector<bool> corner;       // per segment: it starts at a corner
  std::vector<int> turning, alpha;  // per segment: log |total turning| (sets the length; a line's: log length), alpha (a line's: -1)
  std::vector<ZeroEnd> zero;      // per segment
  std::vector<double> turn_sign;  // per segment
  Eigen::VectorXd lower, upper;   // bounds of every unknown
  Vec2 start_point = Vec2::Zero();
  Vec2 end_point = Vec2::Zero();  // where a fixed end stays
  double total_turning = 0.0;     // closed: the end tangent is the start's plus this
  // A window (ChainFitOptions::window): fix_start and fix_end, its end tangent at
  // end_angle (unwrapped from the start's) and these unknowns held at their values (the
  // start tangent, the end curvatures) by equality constraints.
  bool window = false;
  double end_angle = 0.0;
  std::vector<std::pair<int, double>> held;
  double prior_alpha = 0.0, prior_weight = 0.0;  // residual prior_weight (alpha - prior_alpha) per segment
  double min_length = 0.0, length_weight = 0.0;  // residual length_weight log(min_length / length), if positive
  int size = 0;

  // closed with a corner at its seam: the chain returns to its start in position only
  bool seamCorner() const { return closed && corner[0]; }
  int constraints() const {
    return closed ? (seamCorner() ? 2 : 3) : window ? 3 + static_cast<int>(held.size()) : fix_end ? 2 : 0;
  }
  // The first and last points sit at the chain's ends (an open chain that is no window).
  bool pointsAtEnds() const { return !closed && !window; }
  Law law(const Eigen::VectorXd& x, std::size_t i) const {
    Law l;
    l.zero = zero[i];
    l.log_turning = x[turning[i]];
    if (l.zero == ZeroEnd::kBoth) {
      l.length = std::exp(l.log_turning);
      return l;
    }
    l.alpha = x[alpha[i]];
    l.y0 = l.zero == ZeroEnd::kStart ? 0.0 : std::log(std::abs(x[kappa_start[i]]));
    l.y1 = l.zero == ZeroEnd::kEnd ? 0.0 : std::log(std::abs(x[kappa_end[i]]));
    l.turning = std::exp(l.log_turning);
    l.length = l.turning / unitTurning(l.alpha, l.y0, l.y1, l.zero);
    l.sign = turn_sign[i];
    return l;
  }
};

using PoseJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic>;  // rows: x, y, angle
using Jacobian = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// J^T J, one triangle computed (the product dominates a step's linear algebra).
Eigen::MatrixXd normalMatrix(const Jacobian& j) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(j.cols(), j.cols());
  a.selfadjointView<Eigen::Lower>().rankUpdate(j.transpose());
  return a.selfadjointView<Eigen::Lower>();
}

// The chain at given unknowns; with derivatives, also the Jet panels and the Jacobian
// of every segment's start pose by all unknowns.
struct ChainModel : ChainGeometry {
  std::vector<Panels<Jet>> jets;
  std::vector<PoseJacobian> pose_jacobian;
  std::vector<std::array<int, 4>> columns;     // global unknown of each local one (-1: none)
  std::vector<std::array<double, 4>> factors;  // d local / d global
  std::vector<double> held;  // a window's held unknowns (Layout::held), as x has them
  bool differentiated = false;  // the derivatives (addDerivatives) are those of this model
};

// The derivatives of a model built at x (buildModel without them): the Jet panels and
// the start poses' Jacobian. (An accepted trial gets them without building its double
// panels again.)
void addDerivatives(const Layout& layout, const Eigen::VectorXd& x, ChainModel& m) {
  const std::size_t n = layout.segments;
  if (m.jets.size() < n) m.jets.resize(n);  // (never shrunk: see buildModel)
  m.columns.resize(n);
  m.factors.resize(n);
  m.pose_jacobian.assign(n + 1, PoseJacobian::Zero(3, layout.size));
  if (!layout.fix_start) m.pose_jacobian[0](0, layout.start) = m.pose_jacobian[0](1, layout.start + 1) = 1.0;
  m.pose_jacobian[0](2, layout.theta) = 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Law& law = m.laws[i];
    buildPanels(law, m.jets[i]);
    const int k0 = law.zero == ZeroEnd::kStart || law.zero == ZeroEnd::kBoth ? -1 : layout.kappa_start[i];
    const int k1 = law.zero == ZeroEnd::kEnd || law.zero == ZeroEnd::kBoth ? -1 : layout.kappa_end[i];
    m.columns[i] = {layout.alpha[i], k0, k1, layout.turning[i]};
    // d log|kappa| / d kappa = 1 / kappa
    m.factors[i] = {1.0, k0 < 0 ? 0.0 : 1.0 / x[k0], k1 < 0 ? 0.0 : 1.0 / x[k1], 1.0};
    const Eigen::Matrix2d& r = m.rotations[i];
    const Vec2 world = r * Vec2(m.panels[i].x.back(), m.panels[i].y.back());
    const PoseJacobian& here = m.pose_jacobian[i];
    PoseJacobian& next = m.pose_jacobian[i + 1];
    next = here;
    next.row(0) -= world.y() * here.row(2);
    next.row(1) += world.x() * here.row(2);
    const Jet& jx = m.jets[i].x.back();
    const Jet& jy = m.jets[i].y.back();
    const Jet& jt = m.jets[i].theta.back();
    for (int c = 0; c < 4; ++c) {
      const int col = m.columns[i][c];
      if (col < 0) continue;
      const double f = m.factors[i][c];
      const Vec2 d = r * Vec2(jx.v[c], jy.v[c]);
      next(0, col) += f * d.x();
      next(1, col) += f * d.y();
      next(2, col) += f * jt.v[c];
    }
    if (const int corner = layout.corner_turn[i + 1]; corner >= 0) next(2, corner) += 1.0;
  }
  m.differentiated = true;
}

// (a model's derivatives where they are needed: a fit's last accepted step needs none,
// unless its constraints are closed exactly or its standard errors measured after it)
void differentiate(const Layout& layout, const Eigen::VectorXd& x, ChainModel& m) {
  if (!m.differentiated) addDerivatives(layout, x, m);
}

// The interpolants of a model's panels, which points are projected on (Panels::frame).
void prepareFrames(ChainModel& m) {
  for (std::size_t i = 0; i < m.size(); ++i) m.panels[i].prepare(m.laws[i].length);
}

// Builds the model at x. False if a segment's unknowns leave the LA family or overflow.
// Without `frames`, the interpolants are left for prepareFrames: a tried step whose
// constraints' violation rejects it is never projected on.
bool buildModel(const Layout& layout, const Eigen::VectorXd& x, bool derivatives, ChainModel& m, bool frames = true) {
  const std::size_t n = layout.segments;
  m.differentiated = false;
  m.closed = layout.closed;
  m.corner = layout.corner;
  m.laws.resize(n);
  // (never shrunk: a model is reused from fit to fit, and a shrink freed the storage of
  // the panels a longer chain would fill again; those beyond the laws are unused)
  if (m.panels.size() < n) m.panels.resize(n);
  m.rotations.resize(n);
  m.start.resize(n + 1);
  m.angle.resize(n + 1);
  m.start[0] = layout.fix_start ? layout.start_point : Vec2(x[layout.start], x[layout.start + 1]);
  m.angle[0] = x[layout.theta];
  m.held.clear();
  for (const auto& [unknown, value] : layout.held) m.held.push_back(x[unknown]);
  m.total_length = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Law law = layout.law(x, i);
    m.laws[i] = law;
    Panels<double>& p = m.panels[i];
    buildPanels(law, p);
    const double ex = p.x.back(), ey = p.y.back(), turn = p.theta.back();
    if (!std::isfinite(ex) || !std::isfinite(ey) || !std::isfinite(turn) || !(law.length > 0.0)) return false;
    m.total_length += law.length;
    const Eigen::Matrix2d& r = m.rotations[i] = rotation(m.angle[i]);
    m.start[i + 1] = m.start[i] + r * Vec2(ex, ey);
    const int corner = layout.corner_turn[i + 1];
    m.angle[i + 1] = m.angle[i] + turn + (corner >= 0 ? x[corner] : 0.0);
  }
  if (frames) prepareFrames(m);
  if (derivatives) addDerivatives(layout, x, m);
  return true;
}

// Jacobian of the constraints (closure of a closed chain, a fixed end) by the unknowns;
// no rows when there are none.
Eigen::MatrixXd constraintJacobian(const Layout& layout, const ChainModel& m) {
  const std::size_t n = layout.segments;
  if (layout.closed) return (m.pose_jacobian[n] - m.pose_jacobian[0]).topRows(layout.constraints());
  if (layout.window) {
    Eigen::MatrixXd cj = Eigen::MatrixXd::Zero(layout.constraints(), layout.size);
    cj.topRows(3) = m.pose_jacobian[n];
    for (std::size_t k = 0; k < layout.held.size(); ++k) cj(3 + static_cast<Eigen::Index>(k), layout.held[k].first) = 1.0;
    return cj;
  }
  if (layout.fix_end) return m.pose_jacobian[n].topRows(2);
  return Eigen::MatrixXd::Zero(0, layout.size);
}

// The least-norm move of x that meets the linearized constraints (Jacobian cjac, values
// `violation`), clipped to the bounds; with hold_at_bounds, an unknown the move would
// take past its bound stays where it is instead, and the others move again without it.
// (The final closing of the exact chain holds: clipped, its move broke the closure it was
// for, a glyph's chain stayed open, and its unfitted start came back with a stage-4
// alpha of -5. The second-order correction of the steps clips, and is kept only where it
// helps: holding there sent 1 of 1,840 strokes of the shared data, variants included,
// below the tolerance's radius.)
Eigen::VectorXd movedOntoConstraints(const Layout& layout, const Eigen::VectorXd& x, const Eigen::MatrixXd& cjac,
                                     const Eigen::VectorXd& violation, bool hold_at_bounds = false) {
  Eigen::MatrixXd c = cjac;
  Eigen::VectorXd moved;
  for (int round = 0; round <= layout.size; ++round) {
    moved = x + c.transpose() * (c * c.transpose()).ldlt().solve(-violation);
    if (!hold_at_bounds) break;
    bool held = false;
    for (int i = 0; i < layout.size; ++i)
      if (c.col(i).any() && (moved[i] < layout.lower[i] || moved[i] > layout.upper[i])) c.col(i).setZero(), held = true;
    if (!held) break;
  }
  return moved.cwiseMax(layout.lower).cwiseMin(layout.upper);
}

// The points of the problem with their feet and residuals.
class ChainProblem {
 public:
  ChainProblem(const Layout& layout, const std::vector<Vec2>& points, const std::vector<double>& weights,
               const std::vector<FootRange>& ranges)
      : layout_(layout), points_(points), weights_(weights), ranges_(ranges) {}

  // One row per point (its tangent distance), for an open chain (not a window) the
  // tangential components of its two end points (pinned to the chain's ends), and two per segment:
  // the prior on its alpha, and the penalty on a length below min_length (0 above it).
  std::size_t ends() const { return layout_.pointsAtEnds() ? 2 : 0; }
  // The largest distance of a point from the chain, by the residuals r (weights divided out).
  double farthest(const Eigen::VectorXd& r) const {
    double most = 0.0;
    for (std::size_t k = 0; k < points_.size(); ++k)
      if (weights_[k] > 0.0) most = std::max(most, std::abs(r[static_cast<Eigen::Index>(k)]) / weights_[k]);
    return most;
  }
  std::size_t rows() const { return points_.size() + ends() + 2 * layout_.segments; }

  // Projects the feet on the model (an open chain's end points stay at its ends) and
  // fills the residuals; the constraint values too.
  void evaluate(const ChainModel& m, std::vector<ChainFoot>& feet, std::vector<FootFrame>& frames, Eigen::VectorXd& r,
                Eigen::VectorXd& c, bool project = true) const {
    const std::size_t n_points = points_.size();
    frames.resize(n_points);
    if (layout_.pointsAtEnds()) {
      feet.front() = {0, 0.0};
      feet.back() = {layout_.segments - 1, 1.0};
    }
    for (std::size_t k = 0; k < n_points; ++k) {
      const FootRange* range = ranges_.empty() ? nullptr : &ranges_[k];
      const bool held = range && range->held != SIZE_MAX;
      if (held) feet[k] = {range->held, 0.0};
      const bool pinned = (layout_.pointsAtEnds() && (k == 0 || k + 1 == n_points)) || held;
      frames[k] = pinned || !project ? m.frame(feet[k]) : projectFoot(m, points_[k], feet[k], kFootSteps, range);
    }
    r.resize(static_cast<Eigen::Index>(rows()));
    for (std::size_t k = 0; k < n_points; ++k)
      r[static_cast<Eigen::Index>(k)] = weights_[k] * direction(m, feet[k], frames[k], k).dot(frames[k].point - points_[k]);
    if (layout_.pointsAtEnds()) {
      const std::size_t last = n_points - 1;
      r[static_cast<Eigen::Index>(n_points)] =
          layout_.fix_start ? 0.0 : weights_[0] * frames[0].tangent.dot(frames[0].point - points_[0]);
      r[static_cast<Eigen::Index>(n_points + 1)] =
          layout_.fix_end ? 0.0 : weights_[last] * frames[last].tangent.dot(frames[last].point - points_[last]);
    }
    for (std::size_t i = 0; i < layout_.segments; ++i)
      r[static_cast<Eigen::Index>(n_points + ends() + i)] =
          layout_.alpha[i] < 0 ? 0.0 : layout_.prior_weight * (m.laws[i].alpha - layout_.prior_alpha);
    for (std::size_t i = 0; i < layout_.segments; ++i)
      r[static_cast<Eigen::Index>(n_points + ends() + layout_.segments + i)] =
          layout_.length_weight * std::max(0.0, std::log(layout_.min_length / m.laws[i].length));
    constraints(m, c);
  }

  // The constraint values of the model alone (no point is needed).
  void constraints(const ChainModel& m, Eigen::VectorXd& c) const {
    c.resize(layout_.constraints());
    const std::size_t n = layout_.segments;
    if (layout_.seamCorner()) {
      c << m.start[n] - m.start[0];
    } else if (layout_.closed) {
      c << m.start[n] - m.start[0], m.angle[n] - m.angle[0] - layout_.total_turning;
    } else if (layout_.window) {
      c.head(2) = m.start[n] - layout_.end_point;
      c[2] = m.angle[n] - layout_.end_angle;
      for (std::size_t k = 0; k < layout_.held.size(); ++k)
        c[3 + static_cast<Eigen::Index>(k)] = m.held[k] - layout_.held[k].second;
    } else if (layout_.fix_end) {
      c << m.start[n] - layout_.end_point;
    }
  }

  // The Jacobians of the residuals (feet held) and of the constraints.
  void jacobian(const ChainModel& m, const std::vector<ChainFoot>& feet, const std::vector<FootFrame>& frames,
                Jacobian& j, Eigen::MatrixXd& cj) const {
    const std::size_t n_points = points_.size();
    // (a point's row is written whole by `add`; the other rows are zeroed here: zeroing
    // the whole matrix first was a percent of the fits' instructions)
    j.resize(static_cast<Eigen::Index>(rows()), layout_.size);
    j.bottomRows(static_cast<Eigen::Index>(rows() - n_points)).setZero();
    auto add = [&](Eigen::Index row, std::size_t k, const Vec2& unweighted) {
      const Vec2 direction = weights_[k] * unweighted;
      const ChainFoot& f = feet[k];
      const Panels<Jet>& p = m.jets[f.segment];
      Jet px, py;
      p.position(f.u, p.length, px, py);
      const Eigen::Matrix2d& r = m.rotations[f.segment];
      const Vec2 world = r * Vec2(px.a, py.a);
      const PoseJacobian& jp = m.pose_jacobian[f.segment];
      auto out = j.row(row);
      out = direction.x() * jp.row(0) + direction.y() * jp.row(1) + direction.dot(Vec2(-world.y(), world.x())) * jp.row(2);
      const Vec2 local = r.transpose() * direction;  // direction . (R dP) = (R^T direction) . dP
      for (int c = 0; c < 4; ++c) {
        const int col = m.columns[f.segment][c];
        if (col >= 0) out[col] += m.factors[f.segment][c] * (local.x() * px.v[c] + local.y() * py.v[c]);
      }
    };
    for (std::size_t k = 0; k < n_points; ++k) add(static_cast<Eigen::Index>(k), k, direction(m, feet[k], frames[k], k));
    if (layout_.pointsAtEnds()) {
      const std::size_t last = n_points - 1;
      if (!layout_.fix_start) add(static_cast<Eigen::Index>(n_points), 0, frames[0].tangent);
      if (!layout_.fix_end) add(static_cast<Eigen::Index>(n_points + 1), last, frames[last].tangent);
    }
    for (std::size_t i = 0; i < layout_.segments; ++i)
      if (layout_.alpha[i] >= 0) j(static_cast<Eigen::Index>(n_points + ends() + i), layout_.alpha[i]) = layout_.prior_weight;
    for (std::size_t i = 0; i < layout_.segments; ++i) {
      const Jet& length = m.jets[i].length;
      if (!(length.a < layout_.min_length)) continue;
      for (int c = 0; c < 4; ++c) {
        const int col = m.columns[i][c];
        if (col >= 0)
          j(static_cast<Eigen::Index>(n_points + ends() + layout_.segments + i), col) -=
              layout_.length_weight * m.factors[i][c] * length.v[c] / length.a;
      }
    }
    cj = constraintJacobian(layout_, m);
  }

 private:
  // Of a point's residual: the normal at its foot (the tangent distance), or at a corner
  // towards the point (the distance itself).
  Vec2 direction(const ChainModel& m, const ChainFoot& foot, const FootFrame& frame, std::size_t k) const {
    const Vec2 away = frame.point - points_[k];
    if (!m.atCorner(foot) || !(away.norm() > 0.0)) return frame.normal();
    return away.normalized();
  }

  const Layout& layout_;
  const std::vector<Vec2>& points_;
  const std::vector<double>& weights_;
  const std::vector<FootRange>& ranges_;  // per point (empty: the whole chain)
};

// The damped, bound- and equality-constrained Gauss-Newton model
//   min  g.d + d.(A + lambda D).d / 2   subject to  C d = -c,  lower <= x + d <= upper
// (A = J^T J, D its diagonal, g = J^T r), solved by active sets: the unknowns held at a
// bound are left out of
//   [A + lambda D   C^T] [d]    [-g - (A + lambda D) d_held]
//   [C              0  ] [nu] = [-c - C d_held             ]
// and a held one whose multiplier ((A + lambda D) d + g + C^T nu, its own row) says the
// model falls inwards is let go. Why not solve with every unknown free and clip the move
// to the bounds: the clipped move breaks the linearized constraints the others were
// solved for, and a fit started outside its constraints (a part between corners, a
// closed chain) then refused every step and stopped where it started. One system serves
// all the tries of a fit: its matrices keep their storage from one to the next (a system
// per try allocated a dozen small matrices and vectors).
class StepSystem {
 public:
  // `active`: the bounds to hold first (empty: those x is at with the gradient outwards),
  // on return those held at the step; the previous step's set saves most rounds (below).
  void compute(const Eigen::MatrixXd& a, const Eigen::VectorXd& g, const Eigen::MatrixXd& cj, const Eigen::VectorXd& x,
               const Eigen::VectorXd& c, const Layout& layout, double lambda, std::vector<int>& active) {
    p_ = layout.size;
    m_ = static_cast<int>(cj.rows());
    cj_ = &cj;
    h_ = a;
    const double floor = 1e-12 * std::max(1.0, a.diagonal().maxCoeff());
    for (int i = 0; i < p_; ++i) h_(i, i) += lambda * std::max(a(i, i), floor);
    // Primal active sets (Nocedal & Wright 16.5): each round solves with the held unknowns
    // at their bounds; where that move leaves a bound, d goes only as far as the first
    // bound on the way, whose unknown is held from then on; else d is that move, and the
    // held unknown whose multiplier says the model falls inwards most is let go (none: d
    // is the step, the unique minimum of the damped model within the bounds, whatever the
    // start). From d = 0, each bound the step meets costs a round and a factorization: a
    // chain of 25 segments with many curvatures on the radius bound took 30 a step. From
    // the previous step's held set (d moving those unknowns onto their bounds), the
    // steps are the same and a few rounds find them.
    std::vector<int>& held = at_bound_;  // per unknown: -1 held at its lower bound, 1 at its upper, 0 free
    Eigen::VectorXd& d = move_;
    d.setZero(p_);
    if (static_cast<int>(active.size()) == p_) {
      held = active;
      for (int i = 0; i < p_; ++i)
        if (held[i] != 0) d[i] = (held[i] < 0 ? layout.lower[i] : layout.upper[i]) - x[i];
    } else {
      held.resize(p_);
      for (int i = 0; i < p_; ++i)
        held[i] = x[i] <= layout.lower[i] && g[i] > 0.0 ? -1 : x[i] >= layout.upper[i] && g[i] < 0.0 ? 1 : 0;
    }
    // (a round holds or lets go one unknown; more than a few are rare, and the limit only
    // stops a cycle that rounding could make)
    for (int round = 0; round < 2 * p_ + 2; ++round) {
      factor(held, d);
      step_ = solve(g, c);
      double reach = 1.0;  // of the way from d to step_
      int blocking = -1;
      for (int i = 0; i < p_; ++i) {
        if (held[i] != 0 || !std::isfinite(step_[i])) continue;
        const double to = x[i] + step_[i];
        const double bound = to < layout.lower[i] ? layout.lower[i] : to > layout.upper[i] ? layout.upper[i] : to;
        if (bound == to) continue;
        const double fraction = (bound - x[i] - d[i]) / (step_[i] - d[i]);
        if (fraction < reach) reach = std::max(fraction, 0.0), blocking = i;
      }
      if (blocking >= 0) {
        d += reach * (step_ - d);
        held[blocking] = x[blocking] + step_[blocking] < layout.lower[blocking] ? -1 : 1;
        d[blocking] = (held[blocking] < 0 ? layout.lower[blocking] : layout.upper[blocking]) - x[blocking];
        continue;
      }
      d = step_;
      if (std::all_of(held.begin(), held.end(), [](int h) { return h == 0; })) break;
      multiplier_ = h_ * step_ + g + cj.transpose() * nu_;
      int release = -1;
      double worst = 0.0;
      for (int i = 0; i < p_; ++i) {
        const double inward = held[i] * multiplier_[i];  // > 0: the model falls inwards
        if (inward > worst) worst = inward, release = i;
      }
      if (release < 0) break;
      held[release] = 0;
    }
    active = held;
  }
  // The move compute() found (gradient g, constraint values c).
  const Eigen::VectorXd& step() const { return step_; }
  // The move for another gradient g and constraint values c on the same active set, the
  // held unknowns still (the geodesic acceleration's).
  Eigen::VectorXd correction(const Eigen::VectorXd& g, const Eigen::VectorXd& c) const {
    return solveWith(g, c, Eigen::VectorXd::Zero(p_));
  }

 private:
  // The KKT system of the unknowns not held; the held ones keep their moves in d. By its
  // Schur complement: H (A + lambda D on the free unknowns) is positive definite, so one
  // Cholesky factor of it and a small system for the multipliers,
  //   nu = (C H^-1 C^T)^-1 (C H^-1 b - e),  d = H^-1 (b - C^T nu),
  // where a pivoted LU of the whole KKT matrix cost twice the Cholesky's arithmetic. A
  // factor that fails (rounding, lambda tiny) gives a non-finite step: the caller damps
  // more.
  void factor(const std::vector<int>& held, const Eigen::VectorXd& d) {
    free_.clear();
    held_ = d;
    for (int i = 0; i < p_; ++i)
      if (held[i] == 0) free_.push_back(i), held_[i] = 0.0;
    const int f = static_cast<int>(free_.size());
    Eigen::MatrixXd& h = h_free_;
    h.resize(f, f);
    for (int k = 0; k < f; ++k)
      for (int i = k; i < f; ++i) h(i, k) = h_(free_[i], free_[k]);  // (the lower triangle)
    llt_.compute(h);
    c_free_.resize(m_, f);
    for (int i = 0; i < f; ++i) c_free_.col(i) = cj_->col(free_[i]);
    if (m_ > 0 && llt_.info() == Eigen::Success) {
      h_inverse_ct_ = llt_.solve(c_free_.transpose());
      schur_.compute(c_free_ * h_inverse_ct_);
    }
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& g, const Eigen::VectorXd& c) { return solveWith(g, c, held_, &nu_); }
  Eigen::VectorXd solveWith(const Eigen::VectorXd& g, const Eigen::VectorXd& c, const Eigen::VectorXd& held,
                            Eigen::VectorXd* nu = nullptr) const {
    const int f = static_cast<int>(free_.size());
    Eigen::VectorXd step = held;
    if (llt_.info() != Eigen::Success) {
      for (int i : free_) step[i] = NAN;
      if (nu) nu->setConstant(m_, NAN);
      return step;
    }
    // (the held moves enter the right-hand side; free entries of `held` are zero)
    const bool moves = held.any();  // (.any(): nonzero entries)
    const Eigen::VectorXd g_held = moves ? Eigen::VectorXd(g + h_ * held) : g;
    const Eigen::VectorXd c_held = moves ? Eigen::VectorXd(c + *cj_ * held) : c;
    Eigen::VectorXd b(f);
    for (int i = 0; i < f; ++i) b[i] = -g_held[free_[i]];
    Eigen::VectorXd move = llt_.solve(b);
    Eigen::VectorXd multipliers = Eigen::VectorXd::Zero(m_);
    if (m_ > 0) {
      multipliers = schur_.solve(c_free_ * move + c_held);
      move -= h_inverse_ct_ * multipliers;
    }
    for (int i = 0; i < f; ++i) step[free_[i]] = move[i];
    if (nu) *nu = multipliers;
    return step;
  }

  int p_ = 0, m_ = 0;
  Eigen::MatrixXd h_, h_free_;  // A + lambda D; its rows and columns of the free unknowns
  const Eigen::MatrixXd* cj_ = nullptr;
  std::vector<int> at_bound_;          // compute()'s held set
  Eigen::VectorXd move_, multiplier_;  // compute()'s d, and its multipliers of the bounds
  Eigen::VectorXd held_;  // the move of each held unknown (zero for a free one)
  Eigen::VectorXd step_, nu_;
  std::vector<int> free_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd c_free_, h_inverse_ct_;  // C on the free unknowns, H^-1 C^T
  Eigen::LDLT<Eigen::MatrixXd> schur_;     // of C H^-1 C^T
};

// The factor (<= 1) that shortens a step to the trust caps.
double capFactor(const Eigen::VectorXd& step, const Eigen::VectorXd& caps) {
  double shrink = 1.0;
  for (Eigen::Index i = 0; i < step.size(); ++i)
    if (std::abs(step[i]) > caps[i]) shrink = std::min(shrink, caps[i] / std::abs(step[i]));
  return shrink;
}

// Projects the feet once more on the model at x; true where one moved. Feet handed in
// far off (an edit's) move a few projection steps per evaluation, and the tangent
// distance from a foot far off can be smaller than from the true foot: a merit that
// rises as the feet arrive is no reason to stop.
bool feetMoved(const ChainProblem& problem, const ChainModel& model, std::vector<ChainFoot>& feet,
               std::vector<FootFrame>& frames, Eigen::VectorXd& r, Eigen::VectorXd& c) {
  const std::vector<ChainFoot> before = feet;
  problem.evaluate(model, feet, frames, r, c);
  for (std::size_t k = 0; k < feet.size(); ++k)
    if (feet[k].segment != before[k].segment || std::abs(feet[k].u - before[k].u) > kFootMoved) return true;
  return false;
}

// Levenberg-Marquardt on the merit |r|^2 + kConstraintMerit |c|^2 from x (and the
// feet), each step from StepSystem, bent by geodesic acceleration, corrected back onto
// the constraints. Leaves x, the feet and the model (its derivatives: differentiate) at
// the best point; counts iterations on; `abandoned` where it gave up
// (ChainFitOptions::abandon, its distance in normalized units).
SolveStatus minimize(const Layout& layout, const ChainProblem& problem, const Eigen::VectorXd& step_caps,
                     int max_iterations, double relative_decrease, double least_decrease,
                     const Budget& budget, const ChainFitOptions::Abandon& abandon, Eigen::VectorXd& x, std::vector<ChainFoot>& feet,
                     ChainModel& model, int& iterations, bool& abandoned) {
  auto merit = [](const Eigen::VectorXd& res, const Eigen::VectorXd& con) {
    return res.squaredNorm() + kConstraintMerit * con.squaredNorm();
  };
  std::vector<FootFrame> frames;
  Eigen::VectorXd r, c;
  problem.evaluate(model, feet, frames, r, c);
  double phi = merit(r, c);
  Jacobian jac;
  Eigen::MatrixXd cjac;
  double lambda = kInitialLambda;
  std::vector<int> active;  // the bounds the last step system held: the next one's start
  StepSystem system;
  thread_local ChainModel trial_model, corrected_model;  // (their panels' storage kept from fit to fit)
  std::vector<ChainFoot> trial_feet, corrected_feet, held;
  std::vector<FootFrame> trial_frames, corrected_frames;
  Eigen::VectorXd trial_r, trial_c, corrected_r, corrected_c;
  const bool unconstrained = layout.constraints() == 0;
  for (int local = 0; local < max_iterations; ++local) {
    if (budget.spent()) break;
    ++iterations;
    differentiate(layout, x, model);
    problem.jacobian(model, feet, frames, jac, cjac);
    budget.charge(static_cast<std::int64_t>(jac.rows()) * jac.cols());
    const Eigen::MatrixXd a = normalMatrix(jac);
    const Eigen::VectorXd g = jac.transpose() * r;
    bool accepted = false, converged = false;
    bool damped_for_caps = false;  // (the trial's step damped once more already: kCappedStep)
    for (; lambda < kMaxLambda; lambda *= kLambdaGrowth) {
      system.compute(a, g, cjac, x, c, layout, lambda, active);
      Eigen::VectorXd step = system.step();
      const double cap = capFactor(step, step_caps);
      if (cap < kCappedStep && unconstrained && !damped_for_caps) {
        damped_for_caps = true;
        continue;
      }
      damped_for_caps = false;
      step *= cap;
      {
        // Geodesic acceleration (Transtrum & Sethna 2012): the second directional
        // derivative of the residuals along the step (feet held), by a finite difference,
        // bends the step along the curved valleys a chain's rotations make. Used only
        // where it is small against the step (their criterion).
        constexpr double kProbe = 0.1, kMaxAcceleration = 0.75;
        if (!buildModel(layout, x + kProbe * step, false, trial_model)) continue;
        held = feet;
        problem.evaluate(trial_model, held, trial_frames, trial_r, trial_c, false);
        const Eigen::VectorXd r2 = (2.0 / kProbe) * ((trial_r - r) / kProbe - jac * step);
        const Eigen::VectorXd c2 = (2.0 / kProbe) * ((trial_c - c) / kProbe - cjac * step);
        const Eigen::VectorXd accel = system.correction(jac.transpose() * r2, c2);
        if (2.0 * accel.norm() <= kMaxAcceleration * step.norm()) step += 0.5 * accel;
      }
      Eigen::VectorXd trial = (x + step).cwiseMax(layout.lower).cwiseMin(layout.upper);
      if (!trial.allFinite() || !buildModel(layout, trial, false, trial_model, /*frames=*/false)) continue;
      // The second-order correction (below) of a step on a constrained chain, and a step
      // rejected before its points are projected where its violation alone outweighs the
      // merit at x, and its correction's too (the same verdicts: a quarter of the steps
      // tried on the shared data, 7,132 of 28,609).
      Eigen::VectorXd corrected;
      bool corrected_built = false;
      if (layout.constraints() > 0) {
        problem.constraints(trial_model, trial_c);
        corrected = movedOntoConstraints(layout, trial, cjac, trial_c);
        corrected_built = corrected.allFinite() && buildModel(layout, corrected, false, corrected_model, /*frames=*/false);
        if (kConstraintMerit * trial_c.squaredNorm() >= phi) {
          if (!corrected_built) continue;
          problem.constraints(corrected_model, corrected_c);
          if (kConstraintMerit * corrected_c.squaredNorm() >= phi) continue;
        }
      }
      prepareFrames(trial_model);
      trial_feet = feet;
      problem.evaluate(trial_model, trial_feet, trial_frames, trial_r, trial_c);
      if (trial_c.size() > 0) {
        // Second-order correction (Nocedal & Wright 18.3): the step met the linearized
        // constraints; the least-norm move back onto the constraints themselves avoids
        // rejecting good steps for their second-order violation (the Maratos effect).
        // Kept only where it lowers the merit: clipped at a bound, it can break the
        // constraints more than the step did.
        corrected_feet = trial_feet;
        if (corrected_built) {
          prepareFrames(corrected_model);
          problem.evaluate(corrected_model, corrected_feet, corrected_frames, corrected_r, corrected_c);
          if (merit(corrected_r, corrected_c) < merit(trial_r, trial_c)) {
            trial = corrected;
            std::swap(trial_model, corrected_model);
            std::swap(trial_feet, corrected_feet);
            std::swap(trial_frames, corrected_frames);
            std::swap(trial_r, corrected_r);
            std::swap(trial_c, corrected_c);
          }
        }
      }
      const double trial_phi = merit(trial_r, trial_c);
      if (!(trial_phi < phi)) continue;
      converged = phi - trial_phi < std::max(relative_decrease * phi, least_decrease);
      x = trial;
      std::swap(feet, trial_feet);
      std::swap(frames, trial_frames);
      std::swap(r, trial_r);
      std::swap(c, trial_c);
      phi = trial_phi;
      lambda = std::max(lambda / kLambdaShrink, 1e-12);
      accepted = true;
      break;
    }
    if (accepted) std::swap(model, trial_model);  // (trial_model is at x, without derivatives)
    if (!accepted && feetMoved(problem, model, feet, frames, r, c)) {
      // (the feet were still on their way: the merit at x is measured anew)
      phi = merit(r, c);
      lambda = kInitialLambda;
      continue;
    }
    // No step lowers the merit: a minimum to the steps' resolution.
    if (!accepted || converged) return SolveStatus::kConverged;
    if (local + 1 == abandon.after && problem.farthest(r) > abandon.beyond) {
      abandoned = true;
      return SolveStatus::kIterationLimit;
    }
  }
  return SolveStatus::kIterationLimit;
}

// Standard error of each segment's alpha: the residuals' variance (SSR over the degrees
// of freedom) times the alpha entries of the inverse of J^T J restricted to the
// constraints' null space (Z (Z^T J^T J Z)^-1 Z^T), the usual least-squares covariance.
// Infinite where the data do not determine alpha at all (a circular segment).
Eigen::VectorXd alphaStandardErrors(const Layout& layout, const ChainProblem& problem, const ChainModel& model,
                                    const std::vector<ChainFoot>& feet, const std::vector<FootFrame>& frames,
                                    const Eigen::VectorXd& r) {
  Jacobian jac;
  Eigen::MatrixXd cjac;
  problem.jacobian(model, feet, frames, jac, cjac);
  const Eigen::MatrixXd a = normalMatrix(jac);
  const bool constrained = cjac.rows() > 0;
  const Eigen::MatrixXd z = constrained ? Eigen::MatrixXd(Eigen::FullPivLU<Eigen::MatrixXd>(cjac).kernel()) : Eigen::MatrixXd();
  const Eigen::Index free_unknowns = constrained ? z.cols() : layout.size;
  const double dof = std::max<double>(1.0, static_cast<double>(r.size()) - static_cast<double>(free_unknowns));
  const double variance = r.squaredNorm() / dof;
  const Eigen::MatrixXd inverse = (constrained ? Eigen::MatrixXd(z.transpose() * a * z) : a).completeOrthogonalDecomposition().pseudoInverse();
  // (only the alphas' variances: the diagonal entries z_a inverse z_a^T, not the whole
  // covariance, whose two products were most of this function's time)
  Eigen::VectorXd se(static_cast<Eigen::Index>(layout.segments));
  for (std::size_t i = 0; i < layout.segments; ++i) {
    const int k = layout.alpha[i];
    double v = 0.0;  // (a line has no alpha)
    if (k >= 0) v = variance * (constrained ? z.row(k).dot(inverse * z.row(k).transpose()) : inverse(k, k));
    se[static_cast<Eigen::Index>(i)] = v > 0.0 ? std::sqrt(v) : INFINITY;
  }
  return se;
}

bool sameSign(double a, double b) { return (a < 0.0) == (b < 0.0); }

}  // namespace

namespace {

// fitChain, or with `errors_only` the alphas' standard errors of `initial` itself (no
// step taken, the chain as it is).
ChainFitResult fitOrMeasureChain(const std::vector<LaSegment>& initial, const std::vector<Vec2>& all_points,
                                 const std::vector<ChainFoot>& initial_feet, const ChainFitOptions& options,
                                 bool errors_only) {
  ChainFitResult result;
  result.segments = initial;
  const std::size_t n = initial.size();
  auto refuse = [&](const std::string& why) {
    result.report = {SolveStatus::kBadInput, 0, INFINITY, "chain fit: " + why};
    return result;
  };
  if (n == 0 || all_points.size() < 3) return refuse("no chain or too few points");
  if (!initial_feet.empty() && initial_feet.size() != all_points.size()) return refuse("feet and points differ in count");
  if (!options.weights.empty() && options.weights.size() != all_points.size()) return refuse("weights and points differ in count");
  if (options.window && (options.closed || options.fix_start || options.fix_end || !options.corners.empty()))
    return refuse("a window is open, without corners, and its ends are its own");
  if (options.held_start && (!options.fix_start || options.closed || options.window))
    return refuse("a held start is a fixed start of an open chain");

  // Normalized frame: the chain's start at the origin, unit bounding-box diagonal.
  const Vec2 origin = initial.front().start();
  const double scale = boundingBoxDiagonal(all_points);
  if (!(scale > 0.0) || !allFinite(origin)) return refuse("the points have no extent");
  std::vector<Vec2> points;
  points.reserve(all_points.size());
  for (const Vec2& p : all_points) points.push_back((p - origin) / scale);

  Layout layout;
  layout.segments = n;
  layout.closed = options.closed;
  layout.fix_start = (options.fix_start || options.window) && !options.closed;
  layout.fix_end = (options.fix_end || options.window) && !options.closed;
  layout.window = options.window;
  // (a fixed end is the first / last point, a corner; a window's ends are its own)
  layout.start_point = options.window ? Vec2::Zero() : points.front();
  layout.end_point = options.window ? Vec2((options.window_end.point - origin) / scale) : points.back();
  std::vector<double> x0, lower, upper, caps;
  auto add = [&](double value, double lo, double hi, double cap) {
    x0.push_back(value), lower.push_back(lo), upper.push_back(hi), caps.push_back(cap);
    return static_cast<int>(x0.size()) - 1;
  };
  if (!layout.fix_start) {
    layout.start = add(0.0, -INFINITY, INFINITY, kMaxPointStep);
    add(0.0, -INFINITY, INFINITY, kMaxPointStep);
  }
  // (a held start's tangent and curvature: unknowns whose bounds meet)
  if (const auto& held = options.held_start) layout.theta = add(held->theta, held->theta, held->theta, kMaxAngleStep);
  else layout.theta = add(initial.front().theta0(), -INFINITY, INFINITY, kMaxAngleStep);
  // Corners: joints where only the position is continuous; each point's foot stays on
  // its part's segments (FootRange).
  const std::size_t m = points.size();
  std::vector<bool>& corner = layout.corner;
  corner.assign(n, false);
  std::vector<FootRange> ranges;
  for (std::size_t a = 0; a < options.corners.size(); ++a) {
    const ChainCorner& c = options.corners[a];
    const bool first = a == 0;
    const ChainCorner before = first ? ChainCorner{0, 0} : options.corners[a - 1];
    const bool ordered = first ? (options.closed ? c.joint == 0 && c.point == 0 : c.joint > 0 && c.point > 0)
                               : c.joint > before.joint && c.point > before.point;
    if (!ordered || c.joint >= n || c.point + 1 >= m)
      return refuse("corner " + std::to_string(a) + " (joint " + std::to_string(c.joint) + ", point " +
                    std::to_string(c.point) + ") is out of order or not inside the chain");
    corner[c.joint] = true;
    if (first) ranges.assign(m, FootRange{0, c.joint - 1});  // (open: the points before it)
    const std::size_t next_joint = a + 1 < options.corners.size() ? options.corners[a + 1].joint : n;
    for (std::size_t k = c.point + 1; k < m; ++k) ranges[k] = {c.joint, next_joint - 1};
  }
  for (const ChainCorner& c : options.corners) {  // (a closed chain's seam: its last part and its first)
    const std::size_t before = c.point > 0 ? c.point - 1 : m - 1, after = c.point + 1;
    ranges[c.point] = {ranges[before].first, ranges[after].last, true, options.hold_corner_points ? ranges[after].first : SIZE_MAX};
  }
  // Curvature values: one per smooth joint (the geometric mean of the two sides where a
  // G2 chain has round-off), one per side of a corner; each segment's ends name theirs.
  const std::size_t joints = options.closed ? n : n + 1;
  std::vector<double> kappa;
  std::vector<std::size_t> at_start(n), at_end(n);
  for (std::size_t j = 0; j < joints; ++j) {
    const double right = j < n ? initial[j].kappaStart() : initial[n - 1].kappaEnd();
    const double left = j > 0 ? initial[j - 1].kappaEnd() : (options.closed ? initial[n - 1].kappaEnd() : right);
    const std::size_t before = (j + n - 1) % n;  // (an open chain's joint 0 has none)
    if (j < n && corner[j]) {
      at_end[before] = kappa.size();
      kappa.push_back(left * scale);
      at_start[j] = kappa.size();
      kappa.push_back(right * scale);
      continue;
    }
    if (!sameSign(left, right) && left != 0.0 && right != 0.0)
      return refuse("curvature changes sign at joint " + std::to_string(j) + " without an inflection");
    if (j < n) at_start[j] = kappa.size();
    if (j > 0 || options.closed) at_end[j > 0 ? j - 1 : before] = kappa.size();
    kappa.push_back((left == 0.0 || right == 0.0) ? 0.0 : std::copysign(std::sqrt(left * right), right) * scale);
  }
  if (const auto& held = options.held_start) {
    kappa[0] = held->kappa * scale;
    const double next = n > 1 ? kappa[at_start[1]] : kappa[at_end[0]];
    if (kappa[0] * next < 0.0) return refuse("the held start's curvature changes sign along the first segment");
    if (kappa[0] != 0.0 && initial.front().isStraight()) return refuse("a held start that bends cannot start a line");
  }
  // Arcs (ChainFitOptions::arcs): the later of a segment's two curvature values becomes
  // an alias of the earlier.
  std::vector<int> alias(kappa.size(), -1);
  std::vector<bool> arc(n, false);
  for (std::size_t i : options.arcs) {
    if (i >= n) return refuse("arc " + std::to_string(i) + " is not a segment of the chain");
    arc[i] = true;
    const std::size_t a = at_start[i], b = at_end[i];
    if (kappa[a] == 0.0 || kappa[b] == 0.0 || (kappa[a] < 0.0) != (kappa[b] < 0.0))
      return refuse("arc " + std::to_string(i) + " does not bend one way from end to end");
    const bool held_end = (options.window || options.held_start) && a == 0;
    if (held_end || (options.window && b + 1 == kappa.size()))
      return refuse("arc " + std::to_string(i) + " ends where the chain holds its curvature");
    if (a == b || alias[a] >= 0 || alias[b] >= 0) continue;  // (a closed chain of one; named twice)
    kappa[a] = kappa[b] = std::copysign(std::sqrt(kappa[a] * kappa[b]), kappa[a]);
    alias[std::max(a, b)] = static_cast<int>(std::min(a, b));
  }
  double kappa_max = 0.0;
  for (double k : kappa) kappa_max = std::max(kappa_max, std::abs(k));
  // (never above a joint of the initial chain: raising one would change the chain before
  // the fit, and an edit's refit would start from a chain that is not the edited one)
  double floor = kKappaFloor * kappa_max;
  for (double k : kappa)
    if (k != 0.0) floor = std::min(floor, std::abs(k));
  // (the largest curvature allowed: a start's tighter joint is eased to it first)
  const double ceiling = options.max_curvature > 0.0 ? std::max(options.max_curvature * scale, floor) : INFINITY;
  std::vector<int> kappa_unknown;
  for (double k : kappa) {
    if (const int same = alias[kappa_unknown.size()]; same >= 0) {
      kappa_unknown.push_back(kappa_unknown[same]);
      continue;
    }
    if (k == 0.0) {
      kappa_unknown.push_back(-1);
      continue;
    }
    const double value = std::copysign(std::clamp(std::abs(k), floor, ceiling), k);
    if (options.held_start && kappa_unknown.empty()) {
      // (a chain fitted before this one under the same bound ends on it to rounding: its
      // curvature, rescaled to this fit's units, can come out an ulp or two above it)
      if (std::abs(k) > ceiling * (1.0 + kBoundRounding)) return refuse("the held start's curvature is beyond the bound on curvature");
      kappa_unknown.push_back(add(value, value, value, kMaxRelativeKappaStep * std::abs(value)));
      continue;
    }
    kappa_unknown.push_back(k > 0.0 ? add(value, floor, ceiling, kMaxRelativeKappaStep * std::abs(value))
                                    : add(value, -ceiling, -floor, kMaxRelativeKappaStep * std::abs(value)));
  }
  double turning = 0.0;  // summed: the segments' own theta0 may be wrapped
  layout.corner_turn.assign(n + 1, -1);
  for (std::size_t i = 0; i < n; ++i) {
    layout.kappa_start.push_back(kappa_unknown[at_start[i]]);
    layout.kappa_end.push_back(kappa_unknown[at_end[i]]);
    const bool zero0 = layout.kappa_start[i] < 0, zero1 = layout.kappa_end[i] < 0;
    if (zero0 && zero1) {
      // A line, its length the only unknown (a segment between two zero joints is one:
      // no LA segment has two zero ends).
      layout.zero.push_back(ZeroEnd::kBoth);
      layout.turn_sign.push_back(1.0);
      layout.turning.push_back(add(std::log(initial[i].length() / scale), -INFINITY, INFINITY, kMaxLogTurningStep));
      layout.alpha.push_back(-1);
    } else {
      layout.zero.push_back(zero0 ? ZeroEnd::kStart : zero1 ? ZeroEnd::kEnd : ZeroEnd::kNone);
      layout.turn_sign.push_back((zero0 ? kappa[at_end[i]] : kappa[at_start[i]]) < 0.0 ? -1.0 : 1.0);
      const double log_turning = std::log(std::abs(initial[i].turning()));
      layout.turning.push_back(add(log_turning, -INFINITY, std::max(log_turning, std::log(kMaxSegmentTurning)), kMaxLogTurningStep));
      const double a = std::isfinite(initial[i].alpha()) ? initial[i].alpha() : -1.0;  // a circle: any alpha
      // (a start's alpha beyond the bounds is moved inside them, which changes the chain
      // before the fit: stage 4 gives inflection pieces alphas below -3, and the range
      // is the user's promise)
      const double lo = options.min_alpha;
      const double hi = (zero0 || zero1) ? std::min(kInflectionAlphaCap, options.max_alpha) : options.max_alpha;
      const double start_alpha = std::clamp(a, lo, hi);
      layout.alpha.push_back(add(start_alpha, arc[i] ? start_alpha : lo, arc[i] ? start_alpha : hi, kMaxAlphaStep));
    }
    turning += initial[i].turning();
    if (i + 1 < n && corner[i + 1]) {
      const double turn = turnBetween(initial[i], initial[i + 1]);
      layout.corner_turn[i + 1] = add(turn, -std::numbers::pi, std::numbers::pi, kMaxAngleStep);
      turning += turn;
    }
  }
  layout.total_turning = 2.0 * std::numbers::pi * std::round(turning / (2.0 * std::numbers::pi));
  if (options.window) {
    // (the end tangent unwrapped: the initial chain's turning, and the turn onto window_end)
    const double initial_end = initial.back().theta(initial.back().length());
    layout.end_angle = x0[layout.theta] + turning + std::remainder(options.window_end.theta - initial_end, 2.0 * std::numbers::pi);
    layout.held.emplace_back(layout.theta, x0[layout.theta]);
    for (const auto& [unknown, value] : {std::pair{layout.kappa_start.front(), kappa[at_start.front()]},
                                         std::pair{layout.kappa_end.back(), kappa[at_end.back()]}}) {
      if (unknown < 0) continue;  // (a zero end stays zero)
      if (x0[unknown] != value) return refuse("a window's end curvature is beyond the bound on curvature");
      layout.held.emplace_back(unknown, value);
    }
  }
  layout.size = static_cast<int>(x0.size());
  layout.prior_alpha = options.alpha_prior;
  layout.prior_weight = options.alpha_spread > 0.0 ? options.noise / scale / options.alpha_spread : 0.0;
  layout.min_length = options.min_length / scale;
  layout.length_weight = kShortSegmentWeight * options.noise / scale;
  layout.lower = Eigen::Map<Eigen::VectorXd>(lower.data(), layout.size);
  layout.upper = Eigen::Map<Eigen::VectorXd>(upper.data(), layout.size);
  const Eigen::VectorXd step_caps = Eigen::Map<Eigen::VectorXd>(caps.data(), layout.size);
  Eigen::VectorXd x = Eigen::Map<Eigen::VectorXd>(x0.data(), layout.size);
  result.unknowns = layout.size;

  // (its panels' storage kept from fit to fit, as minimize's trial models': a fresh
  // model allocated a dozen vectors per segment)
  thread_local ChainModel model;
  if (!buildModel(layout, x, true, model)) return refuse("the initial chain cannot be modelled");
  std::vector<ChainFoot> feet = initial_feet.empty() ? coarseFeet(model, points, ranges) : initial_feet;

  // The iterations use all points or, beyond max_points, an even subsample (the ends
  // kept) in which each picked point stands in for its bin of neighbours by their
  // centroid, weighted by the root of their summed squared weights: where the chain is
  // straight across the bin, the points' sum of squared distances is the centroid's
  // times that weight squared plus a constant, so the fit is the all-points fit at the
  // subsample's cost (with the picked points alone, the pipeline's fits of the
  // ground-truth chains of tests/pipeline_test.cpp came out up to 14% worse in the sum
  // of squares than the truth itself, now 2%, and missed 36 of 78 alphas by more than
  // 0.3, now 32). Where the chain bends across a bin by more than
  // kBinBias of the noise (its centroid would sit inside the bend), or no noise is
  // given, the picked point stands alone.
  // (corner points are picked too, and stand alone: a centroid would cut the corner)
  const std::size_t even_count = options.max_points > 2 ? std::min(m, options.max_points) : m;
  // bin j is [bin[j], bin[j + 1]), around pick[j]
  std::vector<std::size_t> pick, bin;
  for (std::size_t j = 0; j < even_count; ++j) pick.push_back(even_count == m ? j : j * (m - 1) / (even_count - 1));
  for (const ChainCorner& c : options.corners) pick.push_back(c.point);
  std::sort(pick.begin(), pick.end());
  pick.erase(std::unique(pick.begin(), pick.end()), pick.end());
  const std::size_t used_count = pick.size();
  bin.push_back(0);
  for (std::size_t j = 0; j + 1 < used_count; ++j) bin.push_back(j == 0 ? 1 : j + 2 == used_count ? m - 1 : (pick[j] + pick[j + 1]) / 2 + 1);
  bin.push_back(m);
  auto weight2 = [&](std::size_t k) { return options.weights.empty() ? 1.0 : options.weights[k] * options.weights[k]; };
  const double noise = options.noise / scale;
  std::vector<Vec2> used_points;
  std::vector<ChainFoot> used_feet;
  std::vector<double> used_distance, used_weights;
  std::vector<FootRange> used_ranges;
  for (std::size_t j = 0; j < used_count; ++j) {
    const std::size_t k = pick[j], from = bin[j], to = bin[j + 1];
    const FootRange* range = ranges.empty() ? nullptr : &ranges[k];
    ChainFoot foot = feet[k];
    // the given feet may be rough (from the spline's parameters, or an edited chain's)
    const FootFrame f = projectFoot(model, points[k], foot, kFirstFootSteps, range);
    const double sagitta = std::abs(f.kappa) * (points[to - 1] - points[from]).squaredNorm() / 8.0;
    Vec2 point = points[k];
    double w2 = weight2(k), distance = (f.point - point).norm();
    if (to - from > 1 && sagitta <= kBinBias * noise && !(range && range->corner)) {
      point = Vec2::Zero(), w2 = 0.0;
      for (std::size_t i = from; i < to; ++i) point += weight2(i) * points[i], w2 += weight2(i);
      point = w2 > 0.0 ? Vec2(point / w2) : points[k];
      distance = (projectFoot(model, point, foot, kFootSteps, range).point - point).norm();
    }
    used_points.push_back(point);
    used_weights.push_back(std::sqrt(w2));
    used_distance.push_back(distance);
    used_feet.push_back(foot);
    if (range) used_ranges.push_back(*range);
  }
  refineOutlyingFeet(model, used_points, used_feet, used_distance, layout.pointsAtEnds(), used_ranges);
  const ChainProblem used(layout, used_points, used_weights, used_ranges);
  std::vector<FootFrame> frames;
  Eigen::VectorXd r, c;
  used.evaluate(model, used_feet, frames, r, c);
  // (with an open chain's end rows: a pinned end point's distance is along the tangent too)
  const auto data = static_cast<Eigen::Index>(used_points.size() + used.ends());
  const double ssr_before = r.head(data).squaredNorm();
  // (of the model at hand, with its feet, frames and residuals)
  auto measureStandardErrors = [&] {
    differentiate(layout, x, model);
    const Eigen::VectorXd alpha_se = alphaStandardErrors(layout, used, model, used_feet, frames, r);
    result.alpha_standard_error.assign(alpha_se.data(), alpha_se.data() + alpha_se.size());
  };
  if (errors_only) {
    measureStandardErrors();
    return result;
  }
  const bool admissible_before = c.size() == 0 || c.norm() <= kAdmissible;  // the start meets the constraints

  // A step that lowers the sum of squared distances by less than a fraction of one
  // point's noise variance moves the chain by less than the noise can tell (nor, by the
  // caller's least_decrease, by a visible part of the tolerance).
  const double least = std::max(kNegligibleDecrease * noise * noise, options.least_decrease / (scale * scale));
  int iterations = 0;
  bool abandoned = false;
  const SolveStatus status =
      minimize(layout, used, step_caps, options.max_iterations, options.relative_decrease, least, options.budget,
               {options.abandon.after, options.abandon.beyond / scale}, x, used_feet, model, iterations, abandoned);
  used.evaluate(model, used_feet, frames, r, c);
  // The result in world units; each segment starts exactly where the previous ends
  // (LaSegment's adaptive quadrature), so G1 and G2 hold to rounding.
  std::vector<LaSegment> fitted;
  auto build = [&](const ChainModel& mm, const Eigen::VectorXd& xx) {
    std::vector<LaSegment> chain;
    Vec2 start = origin + scale * mm.start[0];
    double theta = mm.angle[0];
    for (std::size_t i = 0; i < n; ++i) {
      const Law& law = mm.laws[i];
      if (law.zero == ZeroEnd::kBoth) {
        chain.push_back(LaSegment::arc(law.length * scale, start, theta, 0.0));
      } else {
        const double k0 = law.zero == ZeroEnd::kStart ? 0.0 : xx[layout.kappa_start[i]] / scale;
        const double k1 = law.zero == ZeroEnd::kEnd ? 0.0 : xx[layout.kappa_end[i]] / scale;
        if (arc[i]) chain.push_back(LaSegment::arc(law.length * scale, start, theta, k0));  // (its alpha: any)
        else chain.emplace_back(law.alpha, law.length * scale, start, theta, k0, k1);
      }
      start = chain.back().end();
      const int turn = layout.corner_turn[i + 1];
      theta = chain.back().theta(chain.back().length()) + (turn >= 0 ? xx[turn] : 0.0);
    }
    return chain;
  };
  // The constraints on that exact chain (normalized units), closed by Newton steps on
  // its exact values with the model's Jacobian: the model is only within ~1e-6 of a
  // segment's length of the exact chain, so closing the model would not close it.
  auto exactConstraints = [&](const std::vector<LaSegment>& chain, const Eigen::VectorXd& xx) {
    const Vec2 end = (chain.back().end() - origin) / scale;
    Eigen::VectorXd value(layout.constraints());
    auto turning = [&] {  // (the segments' and the corners')
      double sum = 0.0;
      for (const LaSegment& seg : chain) sum += seg.turning();
      for (int turn : layout.corner_turn)
        if (turn >= 0) sum += xx[turn];
      return sum;
    };
    if (layout.seamCorner()) {
      value << end - (chain.front().start() - origin) / scale;
    } else if (layout.closed) {
      value << end - (chain.front().start() - origin) / scale, turning() - layout.total_turning;
    } else if (layout.window) {
      value.head(2) = end - layout.end_point;
      value[2] = xx[layout.theta] + turning() - layout.end_angle;
      for (std::size_t k = 0; k < layout.held.size(); ++k)
        value[3 + static_cast<Eigen::Index>(k)] = xx[layout.held[k].first] - layout.held[k].second;
    } else if (layout.fix_end) {
      value << end - layout.end_point;
    }
    return value;
  };
  Eigen::VectorXd exact;
  bool closed_exactly = false;  // the model moved: its residuals are evaluated again
  try {
    fitted = build(model, x);
    exact = exactConstraints(fitted, x);
    for (int k = 0; k < kRestoreSteps && exact.size() > 0 && exact.norm() > kExactlyClosed; ++k) {
      differentiate(layout, x, model);
      const Eigen::VectorXd moved =
          movedOntoConstraints(layout, x, constraintJacobian(layout, model), exact, /*hold_at_bounds=*/true);
      ChainModel trial;
      if (!moved.allFinite() || !buildModel(layout, moved, true, trial)) break;
      std::vector<LaSegment> closer = build(trial, moved);
      const Eigen::VectorXd closer_exact = exactConstraints(closer, moved);
      if (!(closer_exact.norm() < exact.norm())) break;
      x = moved;
      std::swap(model, trial);
      fitted = std::move(closer);
      exact = closer_exact;
      closed_exactly = true;
    }
  } catch (const std::invalid_argument& e) {
    result.report = {SolveStatus::kBadInput, iterations, INFINITY, std::string("chain fit: ") + e.what()};
    return result;
  }
  if (closed_exactly) used.evaluate(model, used_feet, frames, r, c);
  const double ssr_after = r.head(data).squaredNorm();
  // Better: closer to the points, or meeting constraints the start did not meet.
  const bool admissible = exact.size() == 0 || exact.norm() <= kAdmissible;
  result.improved = admissible && (ssr_after < ssr_before || !admissible_before);
  if (!result.improved) {
    result.report = {SolveStatus::kConverged, iterations, std::sqrt(ssr_before / used_points.size()) * scale,
                     "kept: the fit did not bring the chain closer"};
    projectOnChain(initial, options.closed, all_points, result.feet, result.distance);
  } else {
    if (options.standard_errors) measureStandardErrors();
    // Every point's foot: between its picked neighbours' (interpolated where they are on
    // one segment, else the nearer one's), projected afresh.
    for (std::size_t j = 0; j + 1 < pick.size(); ++j) {
      const ChainFoot& a = used_feet[j];
      const ChainFoot& b = used_feet[j + 1];
      for (std::size_t k = pick[j]; k < pick[j + 1]; ++k) {
        const double w = static_cast<double>(k - pick[j]) / static_cast<double>(pick[j + 1] - pick[j]);
        feet[k] = a.segment == b.segment && b.u >= a.u ? ChainFoot{a.segment, a.u + w * (b.u - a.u)} : w <= 0.5 ? a : b;
      }
    }
    feet.back() = used_feet.back();
    result.distance.resize(m);
    for (std::size_t k = 0; k < m; ++k) {
      const FootRange* range = ranges.empty() ? nullptr : &ranges[k];
      const bool pinned = layout.pointsAtEnds() && (k == 0 || k + 1 == m);  // an open chain's ends stay at the points'
      const FootFrame f = pinned ? model.frame(feet[k]) : projectFoot(model, points[k], feet[k], kFinalFootSteps, range);
      result.distance[k] = (f.point - points[k]).norm();
    }
    refineOutlyingFeet(model, points, feet, result.distance, layout.pointsAtEnds(), ranges);
    for (double& d : result.distance) d *= scale;
    result.segments = std::move(fitted);
    result.feet = std::move(feet);
    result.report = {status, iterations, std::sqrt(ssr_after / used_points.size()) * scale,
                     status == SolveStatus::kConverged ? "fitted"
                     : abandoned                       ? "abandoned: still beyond its bound"
                                                       : "fitted (iteration limit)"};
  }
  result.ssr = 0.0;
  result.max_distance = 0.0;
  for (double d : result.distance) {
    result.ssr += d * d;
    result.max_distance = std::max(result.max_distance, d);
  }
  return result;
}

}  // namespace

ChainFitResult fitChain(const std::vector<LaSegment>& initial, const std::vector<Vec2>& points,
                        const std::vector<ChainFoot>& feet, const ChainFitOptions& options) {
  return fitOrMeasureChain(initial, points, feet, options, false);
}

std::vector<double> alphaStandardErrorsOf(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points,
                                          const std::vector<ChainFoot>& feet, const ChainFitOptions& options) {
  return fitOrMeasureChain(chain, points, feet, options, true).alpha_standard_error;
}

void projectOnChain(const std::vector<LaSegment>& segments, bool closed, const std::vector<Vec2>& points,
                    std::vector<ChainFoot>& feet, std::vector<double>& distance) {
  // The segments' own geometry: panel ends by LaSegment's adaptive quadrature, theta and
  // kappa from its law (a straight line: any alpha, zero curvature).
  ChainGeometry g;
  g.closed = closed;
  for (const LaSegment& s : segments) {
    Law law;
    law.length = s.length();
    law.turning = std::abs(s.turning());
    law.alpha = std::isfinite(s.alpha()) ? s.alpha() : -1.0;
    law.sign = s.turnSign() < 0.0 ? -1.0 : 1.0;
    const double k0 = std::abs(s.kappaStart()), k1 = std::abs(s.kappaEnd());
    law.zero = k0 == 0.0 && k1 == 0.0 ? ZeroEnd::kNone : k0 == 0.0 ? ZeroEnd::kStart : k1 == 0.0 ? ZeroEnd::kEnd : ZeroEnd::kNone;
    law.y0 = k0 > 0.0 ? std::log(k0) : (k1 > 0.0 ? 0.0 : -700.0);  // a line: kappa = e^-700 = 0
    law.y1 = k1 > 0.0 ? std::log(k1) : (k0 > 0.0 ? 0.0 : -700.0);
    Panels<double> p;
    panelGrid(law, kMeasuringGrid, p.grid);
    for (double u : p.grid) {
      const double at = u * s.length(), theta = s.theta(at) - s.theta0();
      const Vec2 local = rotation(-s.theta0()) * (s.position(at) - s.start());
      p.x.push_back(local.x());
      p.y.push_back(local.y());
      p.theta.push_back(theta);
      p.c.push_back(std::cos(theta));
      p.s.push_back(std::sin(theta));
      p.kappa.push_back(s.kappa(at));
    }
    p.prepare(s.length());
    g.laws.push_back(law);
    g.panels.push_back(std::move(p));
    g.start.push_back(s.start());
    g.angle.push_back(s.theta0());
    g.rotations.push_back(rotation(s.theta0()));
    g.total_length += s.length();
  }
  const bool given = feet.size() == points.size();
  if (!given) feet = coarseFeet(g, points);
  distance.resize(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    distance[k] = (points[k] - projectFoot(g, points[k], feet[k], kFootSteps + 4).point).norm();
  if (given) refineOutlyingFeet(g, points, feet, distance);  // (coarse feet are the search it would repeat)
}

Chain chainOfSegments(const std::vector<LaSegment>& segments, bool closed, const Vec2& end) {
  Chain chain;
  chain.closed = closed;
  for (const LaSegment& s : segments) {
    chain.joints.push_back(s.start());
    chain.angles.push_back(chain.angles.empty() ? s.theta0()
                                                : chain.angles.back() + wrapAngle(s.theta0() - chain.angles.back()));
    ChainPiece piece;
    piece.kind = s.kappaStart() == 0.0 ? PieceKind::kInflectionStart
                 : s.kappaEnd() == 0.0 ? PieceKind::kInflectionEnd
                                       : PieceKind::kThreePoint;
    piece.alpha = s.alpha();
    chain.pieces.push_back(piece);
  }
  const LaSegment& last = segments.back();
  chain.joints.push_back(closed ? segments.front().start() : end);
  chain.angles.push_back(chain.angles.back() + wrapAngle(last.theta(last.length()) - chain.angles.back()));
  if (closed) {  // the closing angle keeps the total turning (a whole number of turns)
    const double turns = std::round((chain.angles.back() - chain.angles.front()) / (2.0 * std::numbers::pi));
    chain.angles.back() = chain.angles.front() + 2.0 * std::numbers::pi * turns;
  }
  return chain;
}

std::vector<LaSegment> movedOntoEnds(const std::vector<LaSegment>& segments, const Vec2& start, const Vec2& end) {
  const Vec2 origin = segments.front().start(), from = segments.back().end() - origin, to = end - start;
  const double scale = to.norm() / from.norm(), turn = signedAngle(from, to);
  const Eigen::Rotation2Dd rotation(turn);
  std::vector<LaSegment> out;
  for (const LaSegment& s : segments)
    out.emplace_back(s.alpha(), scale * s.length(), Vec2(start + scale * (rotation * (s.start() - origin))),
                     s.theta0() + turn, s.kappaStart() / scale, s.kappaEnd() / scale);
  return out;
}

std::vector<LaSegment> snapToJoints(const std::vector<LaSegment>& segments, bool closed, const Vec2& end,
                                    const G2Options& options, double reach) {
  if (closed && segments.size() == 1) {
    // (a closed chain of one segment is a circle: closed exactly at its mean curvature;
    // no joint is left to rotate)
    const LaSegment& s = segments.front();
    const double kappa = 0.5 * (s.kappaStart() + s.kappaEnd());
    return {LaSegment::arc(2.0 * std::numbers::pi / std::abs(kappa), s.start(), s.theta0(), kappa)};
  }
  if (!segments.empty()) {
    // A chain that ends there already (the fit closes its exact chain to rounding) stays.
    const LaSegment &first = segments.front(), &last = segments.back();
    double length = 0.0;
    for (const LaSegment& s : segments) length += s.length();
    const bool at_end = (last.end() - end).norm() <= kClosed * length;
    const bool smooth = !closed || std::abs(turnBetween(last, first)) <= kClosed;
    if (at_end && smooth && (!closed || (end - first.start()).norm() <= kClosed * length)) return segments;
  }
  if (!closed && !segments.empty()) {
    // The similarity about the start that takes the chain's end onto `end`. It moves a
    // point by the end's miss times the point's distance from the start over the end's,
    // and no point is further from the start than the chain's length.
    const Vec2 start = segments.front().start(), from = segments.back().end() - start;
    double length = 0.0;
    for (const LaSegment& s : segments) length += s.length();
    if ((end - segments.back().end()).norm() * length <= reach * from.norm()) return movedOntoEnds(segments, start, end);
  }
  Chain chain = chainOfSegments(segments, closed, end);
  const G2Result res = makeG2(chain, options);
  if (res.segments.empty() || !res.report.usable()) return {};
  return res.segments;
}

}  // namespace la
