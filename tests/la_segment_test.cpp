// Tests of LaSegment (core/la_segment.h) against independent truth.
//
// Every oracle is written out here from its closed form (DESIGN.md section 2) and does
// not call the code under test: circle, logarithmic spiral (alpha = 1), clothoid via
// Fresnel integrals (alpha = -1), circle involute (alpha = 2), and for alpha = 0 a
// composite Simpson rule of the curvature law written in this file. Then derivatives
// against finite differences, the sign convention, invariance under rigid motions and
// scaling, reversal, the sampler against position(), bad input, and precision near
// the circle. Distances are compared relative to the segment length; each check
// states its threshold and prints both values when it fails.

#include "core/la_segment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/quadrature.h"

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr long double kPiL = std::numbers::pi_v<long double>;

// Tolerance passed to position() when it is compared with an exact oracle: well
// below every threshold used here, so the threshold measures the law, not the
// requested accuracy.
constexpr double kTightTolerance = 1e-13;

std::string str(const Vec2& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", p.x(), p.y());
  return buf;
}

Vec2 rotate(const Vec2& v, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// Places a point given in the local frame of a curve (origin at the start, +x along
// the start tangent, left-turning) at start/theta0, mirrored first if `sign` < 0.
Vec2 placeLocal(const Vec2& local, const Vec2& start, double theta0, double sign) {
  return start + rotate(Vec2(local.x(), sign * local.y()), theta0);
}

// Expects |got - expected| <= tol and prints both points on failure.
void expectNear(const Vec2& got, const Vec2& expected, double tol, const std::string& what) {
  const double err = (got - expected).norm();
  EXPECT_LE(err, tol) << what << ": got " << str(got) << " expected " << str(expected)
                      << " |diff| = " << err << " > tolerance " << tol;
}

void expectNearRel(double got, double expected, double rel_tol, const std::string& what) {
  const double err = std::abs(got - expected);
  const double tol = rel_tol * std::max(std::abs(expected), std::numeric_limits<double>::min());
  EXPECT_LE(err, tol) << what << ": got " << got << " expected " << expected << " |diff| = "
                      << err << " > tolerance " << tol << " (relative " << rel_tol << ")";
}

std::string describe(const LaSegment& seg) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "alpha=%g L=%g kappa %g -> %g", seg.alpha(), seg.length(),
                seg.kappaStart(), seg.kappaEnd());
  return buf;
}

// Arc-length stations 0, L/m, ..., L.
std::vector<double> stations(double length, int m) {
  std::vector<double> s;
  for (int i = 0; i <= m; ++i) s.push_back(i == m ? length : length * i / m);
  return s;
}

// ---------------------------------------------------------------------------------
// Independent oracles.

// Circle of signed curvature kappa through start with tangent angle theta0:
// center C = start + R (-sin theta0, cos theta0), P(s) = C + R (sin(theta0 + kappa s),
// -cos(theta0 + kappa s)), R = 1/kappa (signed). A line if kappa == 0.
Vec2 circleOracle(const Vec2& start, double theta0, double kappa, double s) {
  if (kappa == 0.0) return start + s * Vec2(std::cos(theta0), std::sin(theta0));
  const long double r = 1.0L / kappa;
  const long double cx = start.x() - r * std::sin((long double)theta0);
  const long double cy = start.y() + r * std::cos((long double)theta0);
  const long double th = (long double)theta0 + (long double)kappa * s;
  return {double(cx + r * std::sin(th)), double(cy - r * std::cos(th))};
}

// Left-turning logarithmic spiral in its local frame, rho(s) = rho0 + c s (c != 0):
// theta(s) = ln(1 + c s / rho0) / c, and since ds = rho dtheta with
// rho = rho0 e^{c theta}, integral_0^s e^{i theta} ds = rho0 (e^{(c+i) theta} - 1)/(c+i).
Vec2 logSpiralLocal(double rho0, double c, double s) {
  using Cx = std::complex<long double>;
  const long double phi = std::log1p((long double)c * s / rho0) / c;
  const Cx k((long double)c, 1.0L);
  const Cx q = (long double)rho0 * (std::exp(k * phi) - 1.0L) / k;
  return {double(q.real()), double(q.imag())};
}

// Fresnel integrals C(x), S(x) (integrand cos/sin(pi t^2/2)) by their power series
//   integral_0^x e^{i pi t^2/2} dt = sum_k (i pi/2)^k x^{2k+1} / (k! (2k+1))
// in long double. The largest term is about e^{pi x^2/2}, so with 64-bit mantissas the
// series is good to ~1e-15 for |x| <= 2.5; the tests keep |x| below that.
struct Fresnel {
  long double c, s;
};
Fresnel fresnelSeries(long double x) {
  const long double z = kPiL * x * x / 2.0L;
  long double a = 1.0L;  // z^k / k!
  long double c = 0.0L, s = 0.0L;
  for (int k = 0; k < 200; ++k) {
    if (k > 0) a *= z / k;
    const long double term = a * x / (2 * k + 1);
    switch (k % 4) {
      case 0: c += term; break;
      case 1: s += term; break;
      case 2: c -= term; break;
      case 3: s -= term; break;
    }
    if (k > 2 * z + 5 && std::abs(term) < 1e-30L) break;
  }
  return {c, s};
}

// Composite Simpson of f on [a, b] with n (even) intervals, in long double.
template <class F>
long double simpson(F&& f, long double a, long double b, int n) {
  const long double h = (b - a) / n;
  long double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0L : 2.0L) * f(a + i * h);
  return sum * h / 3.0L;
}

// Clothoid with kappa(s) = k0 + a s (a != 0) in its own frame (start at origin,
// theta0 = 0): theta(s) = k0 s + a s^2/2 = a/2 (s + k0/a)^2 - k0^2/(2a). With
// u = sqrt(|a|/pi) (s + k0/a):
//   integral_0^s e^{i theta} = e^{-i k0^2/(2a)} sqrt(pi/|a|) [dC +- i dS],
// + for a > 0, - for a < 0, dC = C(u(s)) - C(u(0)).
Vec2 clothoidLocal(double k0, double a, double s) {
  const long double scale = std::sqrt(std::abs((long double)a) / kPiL);
  const long double shift = (long double)k0 / a;
  const Fresnel f0 = fresnelSeries(scale * shift);
  const Fresnel f1 = fresnelSeries(scale * (s + shift));
  const long double dc = f1.c - f0.c;
  const long double ds = (a > 0 ? 1.0L : -1.0L) * (f1.s - f0.s);
  const long double phase = -(long double)k0 * k0 / (2.0L * a);
  const long double len = std::sqrt(kPiL / std::abs((long double)a));
  const std::complex<long double> z =
      std::polar(1.0L, phase) * std::complex<long double>(dc, ds) * len;
  return {double(z.real()), double(z.imag())};
}

// Position on a segment with an inflection end (kappa = 0 at s = 0 or s = L), without
// the inflection series that LaSegment uses there: adaptive Gauss-Legendre
// (core/quadrature.h) of the closed-form tangent in w, with t = c + d w^4 measured from
// the inflection c. The substitution turns the r^(-1/alpha) law into a mild w^(-4/alpha)
// and theta into w^(4 - 4/alpha), so the quadrature reaches 1e-15 L with few panels.
Vec2 inflectionReference(const LaSegment& seg, double s) {
  auto from = [&](double c, double d) {  // integral of the tangent from c to c + d
    auto f = [&](double w) -> Vec2 {
      const double w3 = w * w * w;
      return (4.0 * d * w3) * seg.tangent(c + d * w3 * w);
    };
    return integrateAdaptive(f, 0.0, 1.0, 1e-15 * seg.length()).value;
  };
  if (s == 0.0) return seg.start();
  const double length = seg.length();
  if (seg.kappaStart() == 0.0) return seg.start() + from(0.0, s);
  // integral_0^s = integral_0^L - integral_s^L, both from the inflection at L
  return seg.start() - from(length, -length) + (s < length ? from(length, s - length) : Vec2::Zero());
}

// Circle involute x = a(cos t + t sin t), y = a(sin t - t cos t): tangent angle t,
// ds/dt = a t, s = a t^2 / 2, curvature 1/(a t).
Vec2 involute(double a, double t) {
  return {a * (std::cos(t) + t * std::sin(t)), a * (std::sin(t) - t * std::cos(t))};
}

// ---------------------------------------------------------------------------------
// Circle.

TEST(LaSegmentTest, CircleMatchesClosedFormForInfiniteAndFiniteAlpha) {
  // Positions of a circular arc equal the centre-radius formula to 1e-12 L, both for
  // alpha = inf (LaSegment::arc) and for finite alphas with kappa_start == kappa_end.
  constexpr double kRelTol = 1e-12;
  const Vec2 start(1.5, -0.75);
  struct Case {
    double theta0, kappa, length;
  };
  const std::vector<Case> cases = {{0.3, 0.8, 6.0},  {-2.0, -1.7, 3.0}, {1.0, 2.5, 2.4},
                                   {0.0, 0.0, 4.0},  {2.9, -0.01, 50.0}};
  const std::vector<double> alphas = {kInf, -kInf, -2.0, -1.0, 0.0, 0.5, 1.0, 3.0};
  for (const Case& c : cases) {
    for (double alpha : alphas) {
      const LaSegment seg(alpha, c.length, start, c.theta0, c.kappa, c.kappa);
      EXPECT_TRUE(seg.isCircular()) << describe(seg);
      for (double s : stations(c.length, 16)) {
        expectNear(seg.position(s), circleOracle(start, c.theta0, c.kappa, s), kRelTol * c.length,
                   describe(seg) + " s=" + std::to_string(s));
        expectNearRel(seg.theta(s), c.theta0 + c.kappa * s, 1e-15, describe(seg) + " theta");
        EXPECT_EQ(seg.kappa(s), c.kappa) << describe(seg);
      }
    }
    const LaSegment arc = LaSegment::arc(c.length, start, c.theta0, c.kappa);
    expectNear(arc.end(), circleOracle(start, c.theta0, c.kappa, c.length), kRelTol * c.length,
               "arc() end");
  }
}

// ---------------------------------------------------------------------------------
// Logarithmic spiral, alpha = 1.

TEST(LaSegmentTest, LogSpiralMatchesClosedForm) {
  // rho linear in s. theta(s) = theta0 + sign * ln(1 + c s/rho0)/c, positions from
  // the complex-exponential integral in logSpiralLocal, mirrored for right turns.
  // Thresholds: positions 1e-11 L, theta 1e-13 relative to the turning.
  constexpr double kPosRelTol = 1e-11;
  struct Case {
    double rho0, c, length, sign, theta0;
    Vec2 start;
  };
  const std::vector<Case> cases = {
      {1.0, 0.2, 10.0, +1.0, 0.4, Vec2(0.0, 0.0)},     // rho 1 -> 3, 5.5 rad
      {2.0, -0.15, 10.0, +1.0, -1.0, Vec2(3.0, 1.0)},  // rho 2 -> 0.5, 9.2 rad
      {1.0, 0.2, 10.0, -1.0, 2.0, Vec2(-1.0, 4.0)},    // right-turning
      {0.5, -0.04, 5.0, -1.0, 0.0, Vec2(0.0, 2.0)},    // right, rho 0.5 -> 0.3
      {3.0, 1.0, 0.5, +1.0, 0.1, Vec2(0.0, 0.0)},      // gentle
  };
  for (const Case& c : cases) {
    const double rho1 = c.rho0 + c.c * c.length;
    const LaSegment seg(1.0, c.length, c.start, c.theta0, c.sign / c.rho0, c.sign / rho1);
    const double turning = std::log1p(c.c * c.length / c.rho0) / c.c;
    expectNearRel(seg.turning(), c.sign * turning, 1e-13, describe(seg) + " turning");
    for (double s : stations(c.length, 20)) {
      const std::string at = describe(seg) + " s=" + std::to_string(s);
      const double theta = c.theta0 + c.sign * std::log1p(c.c * s / c.rho0) / c.c;
      EXPECT_NEAR(seg.theta(s), theta, 1e-13 * std::max(1.0, turning)) << at;
      expectNearRel(seg.kappa(s), c.sign / (c.rho0 + c.c * s), 1e-13, at + " kappa");
      const Vec2 expected = placeLocal(logSpiralLocal(c.rho0, c.c, s), c.start, c.theta0, c.sign);
      expectNear(seg.position(s, kTightTolerance), expected, kPosRelTol * c.length, at);
      // The default accuracy (1e-10 relative) is met as documented.
      expectNear(seg.position(s), expected, kDefaultRelativeTolerance * c.length, at + " default");
    }
  }
}

// ---------------------------------------------------------------------------------
// Clothoid, alpha = -1, via Fresnel integrals.

TEST(LaSegmentTest, FresnelOracleMatchesKnownValuesAndSimpson) {
  // The Fresnel series used by the clothoid oracle against tabulated values
  // (Abramowitz & Stegun 7.3) and a composite Simpson of cos/sin(pi t^2/2) with 2e5
  // intervals (error ~ h^4 (pi x)^4 / 180 < 1e-17 for x <= 2.5).
  const Fresnel one = fresnelSeries(1.0L);
  EXPECT_NEAR(double(one.c), 0.7798934003768228, 1e-15);
  EXPECT_NEAR(double(one.s), 0.4382591473903548, 1e-15);
  for (long double x : {0.3L, 1.5L, -1.2L, 2.5L}) {
    const Fresnel f = fresnelSeries(x);
    const long double c =
        simpson([](long double t) { return std::cos(kPiL * t * t / 2); }, 0.0L, x, 200000);
    const long double s =
        simpson([](long double t) { return std::sin(kPiL * t * t / 2); }, 0.0L, x, 200000);
    EXPECT_NEAR(double(f.c), double(c), 1e-14) << "C(" << double(x) << ")";
    EXPECT_NEAR(double(f.s), double(s), 1e-14) << "S(" << double(x) << ")";
  }
}

TEST(LaSegmentTest, ClothoidMatchesFresnelIntegrals) {
  // kappa linear in s; positions to 1e-10 L against clothoidLocal, including
  // inflection ends (kappa 0 at the start or at the end) and right turns.
  constexpr double kPosRelTol = 1e-10;
  struct Case {
    double k0, k1, length, theta0;
    Vec2 start;
  };
  const std::vector<Case> cases = {
      {0.0, 2.0, 3.0, 0.0, Vec2(0.0, 0.0)},     // inflection at the start, 3 rad
      {0.5, 2.5, 2.0, 0.7, Vec2(1.0, -2.0)},    // not at an inflection
      {-3.0, -0.5, 2.5, -0.4, Vec2(2.0, 2.0)},  // right-turning, |kappa| decreasing
      {2.0, 0.0, 1.5, 1.2, Vec2(-1.0, 0.5)},    // inflection at the end
      {0.0, -1.2, 4.0, 3.0, Vec2(0.0, 5.0)},    // right, inflection at the start
  };
  for (const Case& c : cases) {
    const LaSegment seg(-1.0, c.length, c.start, c.theta0, c.k0, c.k1);
    const double a = (c.k1 - c.k0) / c.length;
    for (double s : stations(c.length, 20)) {
      const std::string at = describe(seg) + " s=" + std::to_string(s);
      EXPECT_NEAR(seg.kappa(s), c.k0 + a * s, 1e-14 * std::max(std::abs(c.k0), std::abs(c.k1)))
          << at;
      EXPECT_NEAR(seg.theta(s), c.theta0 + c.k0 * s + 0.5 * a * s * s, 1e-14 * (1.0 + c.length))
          << at;
      const Vec2 expected = c.start + rotate(clothoidLocal(c.k0, a, s), c.theta0);
      expectNear(seg.position(s, kTightTolerance), expected, kPosRelTol * c.length, at);
    }
  }
}

// ---------------------------------------------------------------------------------
// Circle involute, alpha = 2.

TEST(LaSegmentTest, CircleInvoluteMatchesClosedForm) {
  // rho^2 linear in s. The involute of a circle of radius a between t0 and t1 is an
  // LA segment with start involute(a, t0), theta0 = t0, kappa 1/(a t0) -> 1/(a t1),
  // length a (t1^2 - t0^2)/2; at arc length s, t = sqrt(t0^2 + 2 s / a). Traversed
  // backwards it turns right with growing |kappa|. Threshold 1e-10 L.
  constexpr double kPosRelTol = 1e-10;
  struct Case {
    double a, t0, t1;
  };
  for (const Case& c : std::vector<Case>{{0.7, 0.5, 4.0}, {2.0, 1.0, 1.3}, {0.1, 0.05, 6.0}}) {
    const double length = c.a * (c.t1 * c.t1 - c.t0 * c.t0) / 2.0;
    const LaSegment fwd(2.0, length, involute(c.a, c.t0), c.t0, 1.0 / (c.a * c.t0),
                        1.0 / (c.a * c.t1));
    const LaSegment bwd(2.0, length, involute(c.a, c.t1), c.t1 + kPi, -1.0 / (c.a * c.t1),
                        -1.0 / (c.a * c.t0));
    for (double s : stations(length, 24)) {
      const double tf = std::sqrt(c.t0 * c.t0 + 2.0 * s / c.a);
      const double tb = std::sqrt(std::max(c.t1 * c.t1 - 2.0 * s / c.a, 0.0));
      const std::string at = " s=" + std::to_string(s);
      expectNear(fwd.position(s, kTightTolerance), involute(c.a, tf), kPosRelTol * length,
                 describe(fwd) + at);
      expectNear(bwd.position(s, kTightTolerance), involute(c.a, tb), kPosRelTol * length,
                 describe(bwd) + at);
      EXPECT_NEAR(fwd.theta(s), tf, 1e-13 * (1.0 + c.t1)) << describe(fwd) << at;
      EXPECT_NEAR(bwd.theta(s), tb + kPi, 1e-13 * (1.0 + c.t1)) << describe(bwd) << at;
    }
  }
}

// ---------------------------------------------------------------------------------
// Exponential law, alpha = 0.

TEST(LaSegmentTest, ExponentialLawMatchesSimpsonIntegrals) {
  // kappa = kappa0 exp(-g s), g = ln(kappa0/kappa1)/L. theta(s) is checked against a
  // composite Simpson integral of that kappa (2e4 intervals, long double), and the
  // closed form theta0 + kappa0 (1 - e^{-g s})/g written here feeds a Simpson
  // integral of (cos, sin)(theta) for the positions. Thresholds: theta 1e-12 rad,
  // positions 1e-12 L (Simpson error here ~h^4 max|theta'|^4 L/180 < 1e-15 L).
  constexpr int kIntervals = 20000;
  struct Case {
    double k0, k1, length, theta0;
    Vec2 start;
  };
  const std::vector<Case> cases = {{2.0, 0.25, 3.0, 0.2, Vec2(0.0, 0.0)},
                                   {-0.5, -3.0, 2.0, -1.0, Vec2(1.0, 1.0)},
                                   {1.0, 1.5, 0.4, 2.0, Vec2(-3.0, 0.0)}};
  for (const Case& c : cases) {
    const LaSegment seg(0.0, c.length, c.start, c.theta0, c.k0, c.k1);
    const long double g = std::log((long double)c.k0 / c.k1) / c.length;
    auto kappa_law = [&](long double s) { return c.k0 * std::exp(-g * s); };
    auto theta_law = [&](long double s) { return c.theta0 + c.k0 * -std::expm1(-g * s) / g; };
    for (double s : stations(c.length, 8)) {
      const std::string at = describe(seg) + " s=" + std::to_string(s);
      EXPECT_NEAR(seg.kappa(s), double(kappa_law(s)), 1e-14 * std::abs(c.k1) + 1e-14 * std::abs(c.k0))
          << at;
      const long double theta_num = c.theta0 + simpson(kappa_law, 0.0L, s, kIntervals);
      EXPECT_NEAR(seg.theta(s), double(theta_num), 1e-12) << at;
      EXPECT_NEAR(double(theta_law(s)), double(theta_num), 1e-12) << at << " (oracle self-check)";
      const long double x =
          simpson([&](long double t) { return std::cos(theta_law(t)); }, 0.0L, s, kIntervals);
      const long double y =
          simpson([&](long double t) { return std::sin(theta_law(t)); }, 0.0L, s, kIntervals);
      expectNear(seg.position(s, kTightTolerance), c.start + Vec2(double(x), double(y)),
                 1e-12 * c.length, at);
    }
  }
}

// ---------------------------------------------------------------------------------
// Sign convention.

TEST(LaSegmentTest, PositiveCurvatureTurnsLeft) {
  // kappa > 0: theta increases with s and the curve bends to the left of its start
  // tangent, cross(tangent(0), p(s) - p(0)) > 0; kappa < 0 mirrors both.
  for (double alpha : {-2.0, -1.0, 0.0, 0.5, 1.0, 2.0, kInf}) {
    for (double sign : {+1.0, -1.0}) {
      const double k1 = std::isinf(alpha) ? 1.0 : 2.0;
      const LaSegment seg(alpha, 1.0, Vec2(0.3, 0.4), 0.9, sign * 1.0, sign * k1);
      EXPECT_EQ(seg.turnSign(), sign) << describe(seg);
      double prev_theta = seg.theta(0.0);
      for (double s : {0.01, 0.1, 0.5, 1.0}) {
        const double side = cross(seg.tangent(0.0), seg.position(s) - seg.start());
        EXPECT_GT(sign * side, 0.0) << describe(seg) << " s=" << s << " cross=" << side;
        EXPECT_GT(sign * (seg.theta(s) - prev_theta), 0.0) << describe(seg) << " s=" << s;
        EXPECT_GT(sign * seg.kappa(s), 0.0) << describe(seg) << " s=" << s;
        prev_theta = seg.theta(s);
      }
      EXPECT_GT(sign * seg.turning(), 0.0) << describe(seg);
    }
  }
}

// ---------------------------------------------------------------------------------
// Derivatives against finite differences.

// Fourth-order central difference of f at s with step h.
template <class F>
double centralDifference(F&& f, double s, double h) {
  return (-f(s + 2 * h) + 8 * f(s + h) - 8 * f(s - h) + f(s - 2 * h)) / (12 * h);
}

TEST(LaSegmentTest, DerivativesMatchFiniteDifferences) {
  // dkappa ~ d/ds kappa and kappa ~ d/ds theta by 4th-order central differences with
  // h = 1e-5 L at interior points. The steepest law here (alpha = 3, rho^3 growing
  // 244-fold) varies on a scale l ~ 4e-3 L, so truncation ~ (h/l)^4 ~ 1e-10 relative;
  // rounding ~ 1e-16 |theta| / h ~ 1e-11. Threshold 1e-8 relative to
  // max(|derivative|, max|kappa|/L); left and right turns, |kappa| growing and falling.
  constexpr double kRelTol = 1e-8;
  const double length = 2.0;
  const double h = 1e-5 * length;
  for (double alpha : {-3.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0, 3.0}) {
    for (auto [k0, k1] : std::vector<std::pair<double, double>>{{1.0, 3.0}, {2.5, 0.4}, {-0.3, -1.1}}) {
      const LaSegment seg(alpha, length, Vec2(0.0, 0.0), 0.5, k0, k1);
      const double scale = std::max(std::abs(k0), std::abs(k1));
      for (double s : {0.01, 0.3, 1.0, 1.7, 1.99}) {
        const std::string at = describe(seg) + " s=" + std::to_string(s);
        const double dk_fd = centralDifference([&](double t) { return seg.kappa(t); }, s, h);
        const double dk = seg.dkappa(s);
        EXPECT_LE(std::abs(dk - dk_fd), kRelTol * std::max(std::abs(dk), scale / length))
            << at << ": dkappa " << dk << " finite difference " << dk_fd;
        const double k_fd = centralDifference([&](double t) { return seg.theta(t); }, s, h);
        const double k = seg.kappa(s);
        EXPECT_LE(std::abs(k - k_fd), kRelTol * scale)
            << at << ": kappa " << k << " finite difference of theta " << k_fd;
      }
    }
  }
}

TEST(LaSegmentTest, DkappaAtInflectionEndFollowsLaw) {
  // With kappa_start = 0 (alpha < 0) kappa ~ s^(-1/alpha): dkappa(0) is infinite for
  // alpha < -1 (documented), finite and equal to the FD slope for alpha = -1, and 0
  // for -1 < alpha < 0.
  EXPECT_TRUE(std::isinf(LaSegment(-2.0, 1.0, Vec2(0, 0), 0.0, 0.0, 1.0).dkappa(0.0)));
  EXPECT_NEAR(LaSegment(-1.0, 2.0, Vec2(0, 0), 0.0, 0.0, 1.0).dkappa(0.0), 0.5, 1e-15);
  EXPECT_EQ(LaSegment(-0.5, 1.0, Vec2(0, 0), 0.0, 0.0, 1.0).dkappa(0.0), 0.0);
}

// ---------------------------------------------------------------------------------
// Invariance under rotation, translation and scaling.

TEST(LaSegmentTest, PositionsTransformWithRigidMotionsAndScaling) {
  // Segment B = rotation(phi) and translation(t) of A: B.position(s) = R A.position(s)
  // + t. Segment C = A scaled by k (length k L, start k P0, kappa / k): C.position(k s)
  // = k A.position(s). Threshold 1e-12 L of the larger segment.
  constexpr double kRelTol = 1e-12;
  const double phi = 2.1, k = 3.7;
  const Vec2 shift(-4.0, 10.5);
  for (double alpha : {-2.0, -1.0, 0.0, 0.5, 1.0, 2.0, 3.0}) {
    const double length = 2.5;
    const Vec2 p0(0.4, -1.3);
    const double theta0 = 0.3;
    const LaSegment a(alpha, length, p0, theta0, 0.4, 2.2);
    const LaSegment b(alpha, length, rotate(p0, phi) + shift, theta0 + phi, 0.4, 2.2);
    const LaSegment c(alpha, k * length, k * p0, theta0, 0.4 / k, 2.2 / k);
    for (double s : stations(length, 10)) {
      const Vec2 pa = a.position(s, kTightTolerance);
      const std::string at = describe(a) + " s=" + std::to_string(s);
      expectNear(b.position(s, kTightTolerance), rotate(pa, phi) + shift, kRelTol * length,
                 at + " rotated+translated");
      expectNear(c.position(k * s, kTightTolerance), k * pa, kRelTol * k * length, at + " scaled");
      EXPECT_NEAR(b.theta(s), a.theta(s) + phi, 1e-14 * 10) << at;
      EXPECT_NEAR(c.theta(k * s), a.theta(s), 1e-14 * 10) << at;
    }
  }
}

// ---------------------------------------------------------------------------------
// Reversal.

TEST(LaSegmentTest, ReversedTraversesTheSameCurveBackwards) {
  // r = seg.reversed(): r starts at seg.end(), ends at seg.start(); r.kappa(s) =
  // -seg.kappa(L - s), r.theta(s) = seg.theta(L - s) + pi, r.position(s) =
  // seg.position(L - s). r's start comes from end() at the default accuracy (1e-10 L),
  // so positions are compared to 2e-10 L; curvatures to 1e-12 relative.
  constexpr double kPosRelTol = 2 * kDefaultRelativeTolerance;
  struct Case {
    double alpha, k0, k1, length;
  };
  const std::vector<Case> cases = {{-2.0, 0.0, 1.5, 2.0}, {-1.0, 2.0, 0.0, 1.5},
                                   {0.0, 1.0, 3.0, 2.0},  {1.0, -0.5, -4.0, 6.0},
                                   {2.0, 3.0, 0.5, 3.0},  {kInf, -1.0, -1.0, 2.0},
                                   {-0.5, 0.0, -2.0, 1.0}};
  for (const Case& c : cases) {
    const LaSegment seg(c.alpha, c.length, Vec2(1.0, 2.0), 0.4, c.k0, c.k1);
    const LaSegment r = seg.reversed();
    const std::string what = describe(seg);
    EXPECT_EQ(r.length(), seg.length()) << what;
    EXPECT_EQ(r.kappaStart(), -seg.kappaEnd()) << what;
    EXPECT_EQ(r.kappaEnd(), -seg.kappaStart()) << what;
    expectNear(r.start(), seg.end(kTightTolerance), kPosRelTol * c.length, what + " r.start");
    expectNear(r.end(kTightTolerance), seg.start(), kPosRelTol * c.length, what + " r.end");
    const double scale = std::max(std::abs(c.k0), std::abs(c.k1));
    for (double s : stations(c.length, 12)) {
      const double back = c.length - s;
      const std::string at = what + " s=" + std::to_string(s);
      EXPECT_NEAR(r.kappa(s), -seg.kappa(back), 1e-12 * scale) << at;
      EXPECT_NEAR(r.theta(s), seg.theta(back) + kPi, 1e-12 * (1.0 + std::abs(seg.turning()))) << at;
      expectNear(r.position(s, kTightTolerance), seg.position(back, kTightTolerance),
                 kPosRelTol * c.length, at + " position");
    }
  }
}

TEST(LaSegmentTest, CuspEndPositionIsExactBothWays) {
  // A segment of a fuzzed stroke's chain (alpha 0.5): almost straight, then turning in
  // its last 1e-9 of length, its end curvature 3e17 times its start's. Near that end the
  // rounding of the quadrature nodes, times the curvature, made the tangent noisy at the
  // scale of the tolerance, so that each position took 20,000 panels and came back
  // unconverged (the quadrature of its tangent, below, as position() does it). Its
  // reverse, whose sharp end is at its start where the nodes are exact, must come back to
  // the start within the two positions' tolerances.
  const double length = 3.5751400602179983e-4;
  const LaSegment seg(0.5, length, Vec2(1.0, 2.0), 0.4, 8.34555e-06, 2.3132e+12);
  EXPECT_GT(std::abs(seg.turning()), 1.0) << describe(seg);
  const LaSegment r = seg.reversed();
  expectNear(r.end(), seg.start(), 2 * kDefaultRelativeTolerance * length, describe(seg) + " there and back");
  expectNear(seg.end(), seg.end(kTightTolerance), 2 * kDefaultRelativeTolerance * length, describe(seg) + " end");
  const auto tangent = integrateAdaptive([&](double s) { return seg.tangent(s); }, 0.0, length,
                                         kDefaultRelativeTolerance * length);
  EXPECT_TRUE(tangent.converged);
  EXPECT_LE(tangent.panels, 200);
}

// ---------------------------------------------------------------------------------
// Sampling.

TEST(LaSegmentTest, SamplesAgreeWithPointEvaluation) {
  // sample(n): s uniform with s.back() == L exactly; every point within 1e-10 L of
  // position(s, 1e-13); tangent, theta and kappa equal tangent(s), theta(s), kappa(s)
  // (1e-14). Cases include inflection ends and segments turning several radians (with
  // n = 2 and 7 a panel turns radians: beyond the series, it is integrated in steps).
  constexpr double kPosRelTol = 1e-10;
  struct Case {
    double alpha, k0, k1, length;
  };
  const std::vector<Case> cases = {
      {-2.0, 0.0, 1.5, 2.0},   // inflection at the start
      {-2.0, 1.5, 0.0, 2.0},   // inflection at the end
      {1.0, 0.5, 4.0, 6.0},    // log spiral, 7.1 rad
      {1.0, -4.0, -0.25, 30.0},  // log spiral, right, 22 rad
      {-1.0, 0.2, 5.0, 3.0},   // clothoid, 7.8 rad
      {0.0, 3.0, 0.5, 2.5},    // exponential law
      {0.5, 1.0, 2.0, 1.0},
      {3.0, 2.0, 0.7, 4.0},
      {kInf, 2.0, 2.0, 5.0},   // circle, 10 rad
      {2.0, 1e-3, 2e-3, 0.5},  // nearly straight
  };
  for (const Case& c : cases) {
    const LaSegment seg(c.alpha, c.length, Vec2(-0.5, 0.25), 1.1, c.k0, c.k1);
    for (int n : {2, 7, 1000}) {
      const CurveSamples samples = seg.sample(n);
      const std::string what = describe(seg) + " n=" + std::to_string(n);
      ASSERT_EQ(samples.size(), static_cast<std::size_t>(n)) << what;
      ASSERT_EQ(samples.point.size(), samples.size());
      ASSERT_EQ(samples.tangent.size(), samples.size());
      ASSERT_EQ(samples.theta.size(), samples.size());
      ASSERT_EQ(samples.kappa.size(), samples.size());
      EXPECT_EQ(samples.s.front(), 0.0) << what;
      EXPECT_EQ(samples.s.back(), c.length) << what;
      double worst = 0.0;
      for (int i = 0; i < n; ++i) {
        const double s = samples.s[i];
        EXPECT_NEAR(s, c.length * i / (n - 1), 1e-15 * c.length) << what;
        const Vec2 expected = seg.position(s, kTightTolerance);
        worst = std::max(worst, (samples.point[i] - expected).norm());
        if (i == 0 || i == n - 1 || i % 97 == 0)
          expectNear(samples.point[i], expected, kPosRelTol * c.length, what + " i=" + std::to_string(i));
        EXPECT_NEAR(samples.theta[i], seg.theta(s), 1e-14) << what << " i=" << i;
        expectNear(samples.tangent[i], seg.tangent(s), 1e-14, what + " tangent");
        EXPECT_NEAR(samples.kappa[i], seg.kappa(s), 1e-14 * std::max(std::abs(c.k0), std::abs(c.k1)))
            << what << " i=" << i;
      }
      EXPECT_LE(worst, kPosRelTol * c.length) << what << ": worst sample deviation " << worst;
    }
  }
}

TEST(LaSegmentTest, SamplesNextToAnInflectionEndAgreeWithPointEvaluation) {
  // Next to a zero-curvature end the sampler's panels come from the inflection power
  // series (panelNearInflection), further on from the panel series. Truth:
  // inflectionReference (quadrature, no series). Both ends, both turning
  // directions, alphas from nearly 0 to -8, dense and sparse sampling; every sample
  // within 1e-12 of the length (the sampler's own target is 1e-10).
  constexpr double kPosRelTol = 1e-12;
  struct Case {
    double alpha, k0, k1, length;
  };
  const std::vector<Case> cases = {
      {-0.3, 0.0, 2.0, 1.5},  {-1.0, 0.0, -3.0, 1.0}, {-2.0, 0.0, 1.5, 2.0},  {-8.0, 0.0, 0.7, 3.0},
      {-0.3, 2.0, 0.0, 1.5},  {-1.0, -3.0, 0.0, 1.0}, {-2.0, 1.5, 0.0, 2.0},  {-8.0, 0.7, 0.0, 3.0},
  };
  for (const Case& c : cases) {
    const LaSegment seg(c.alpha, c.length, Vec2(0.2, -0.1), -0.6, c.k0, c.k1);
    for (int n : {30, 1000, 4000}) {
      const CurveSamples samples = seg.sample(n);
      const std::string what = describe(seg) + " n=" + std::to_string(n);
      double worst = 0.0;
      int worst_i = 0;
      for (int i = 0; i < n; ++i) {
        // the first and last 40 samples (the inflection panels) and every 37th
        if (i >= 40 && i < n - 40 && i % 37 != 0) continue;
        const double deviation = (samples.point[i] - inflectionReference(seg, samples.s[i])).norm();
        if (deviation > worst) {
          worst = deviation;
          worst_i = i;
        }
        EXPECT_NEAR(samples.theta[i], seg.theta(samples.s[i]), 1e-14) << what << " i=" << i;
      }
      EXPECT_LE(worst, kPosRelTol * c.length) << what << ": worst deviation " << worst << " at i=" << worst_i;
    }
  }
}

TEST(LaSegmentTest, PositionNextToAnInflectionEndMatchesQuadrature) {
  // position() takes the stretch within 1 rad of an inflection end from the inflection
  // series and the rest by adaptive quadrature. Truth: inflectionReference. Both ends,
  // both turning directions, alphas from nearly 0 to -8, segments turning 0.3 rad (all
  // series) and 3 rad (series, then quadrature), stations down to 1e-9 L from either
  // end; positions within 1e-13 L (position's tolerance here is 1e-14).
  constexpr double kPosRelTol = 1e-13;
  for (double alpha : {-0.3, -1.0, -1.5, -3.0, -8.0}) {
    for (double turning : {0.3, 3.0}) {
      for (double sign : {1.0, -1.0}) {
        for (bool zero_at_start : {true, false}) {
          // The turning of an inflection-end segment is kappa_far L / e, e = 1 - 1/alpha.
          const double length = 1.7, e = 1.0 - 1.0 / alpha;
          const double k_far = sign * turning * e / length;
          const LaSegment seg(alpha, length, Vec2(0.4, -1.1), 0.9, zero_at_start ? 0.0 : k_far,
                              zero_at_start ? k_far : 0.0);
          std::vector<double> at = stations(length, 24);
          for (double r : {1e-9, 1e-6, 1e-3}) {
            at.push_back(r * length);
            at.push_back((1.0 - r) * length);
          }
          for (double s : at) {
            expectNear(seg.position(s, 1e-14), inflectionReference(seg, s), kPosRelTol * length,
                       describe(seg) + " s=" + std::to_string(s));
          }
        }
      }
    }
  }
}

TEST(LaSegmentTest, SampleAppendsWithOffset) {
  // sample(n, out, s_offset) appends to out and offsets s; points are unchanged.
  const LaSegment seg(0.5, 2.0, Vec2(0, 0), 0.0, 1.0, 2.0);
  CurveSamples out = seg.sample(3);
  seg.sample(5, out, 10.0);
  ASSERT_EQ(out.size(), 8u);
  EXPECT_EQ(out.s[3], 10.0);
  EXPECT_EQ(out.s[7], 12.0);
  expectNear(out.point[7], seg.position(2.0, kTightTolerance), 1e-10 * 2.0, "appended end");
  EXPECT_THROW(seg.sample(1), std::invalid_argument);
}

// ---------------------------------------------------------------------------------
// End curvatures.

TEST(LaSegmentTest, KappaAtEndsEqualsGivenEndCurvatures) {
  // kappa(0) == kappa_start and kappa(L) == kappa_end to 1e-12 of max |kappa| (0 at an
  // inflection end), for ordinary cases, a large curvature ratio (v1 = (rho1/rho0)^alpha
  // = 1e-9 must not be lost next to 1), an inflection end at s = L with lengths whose
  // reciprocal does not round-trip ((1/L)*L != 1 in doubles, e.g. L = 0.09 or 49),
  // and a large |alpha| where (rho1/rho0)^alpha underflows below 1e-16.
  struct Case {
    double alpha, k0, k1, length;
  };
  const std::vector<Case> cases = {
      {-3.0, 1.0, 3.0, 2.0}, {0.0, 2.0, 0.5, 1.0}, {2.0, -1.0, -4.0, 3.0}, {1.0, 0.3, 0.2, 7.0},
      {3.0, 1.0, 1000.0, 1.0},  // v1 = 1e-9
      {-3.0, 1000.0, 1.0, 1.0},
      {-2.0, 0.0, 1.5, 0.09},   // inflection at the start
      {-2.0, 1.5, 0.0, 0.09},   // inflection at the end, L*(1/L) < 1
      {-10.0, 1.5, 0.0, 0.09},  // same with a larger |alpha|
      {-10.0, 1.0, 0.0, 49.0},
      {-50.0, 3.0, 1.0, 1.0},   // (rho1/rho0)^alpha = 3^-50 ~ 1e-24 vanishes next to 1
      {50.0, 1.0, 3.0, 1.0},
      {20.0, 1.0, 10.0, 1.0},
  };
  for (const Case& c : cases) {
    const LaSegment seg(c.alpha, c.length, Vec2(0, 0), 0.0, c.k0, c.k1);
    const double tol = 1e-12 * std::max(std::abs(c.k0), std::abs(c.k1));
    EXPECT_NEAR(seg.kappa(0.0), c.k0, tol) << describe(seg) << " at s = 0";
    EXPECT_NEAR(seg.kappa(c.length), c.k1, tol) << describe(seg) << " at s = L";
    const CurveSamples samples = seg.sample(5);
    EXPECT_NEAR(samples.kappa.back(), c.k1, tol) << describe(seg) << " last sample";
  }
}

// ---------------------------------------------------------------------------------
// Bad parameters.

TEST(LaSegmentTest, RejectsParametersThatAreNotAnLaSegment) {
  const Vec2 o(0.0, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(LaSegment(nan, 1.0, o, 0.0, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(1.0, 0.0, o, 0.0, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(1.0, -1.0, o, 0.0, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(1.0, nan, o, 0.0, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(1.0, kInf, o, 0.0, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(-1.0, 1.0, o, 0.0, 1.0, -2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(kInf, 1.0, o, 0.0, -1.0, 1.0), std::invalid_argument);
  for (double alpha : {0.0, 0.5, 1.0, 2.0}) {
    EXPECT_THROW(LaSegment(alpha, 1.0, o, 0.0, 0.0, 1.0), std::invalid_argument) << alpha;
    EXPECT_THROW(LaSegment(alpha, 1.0, o, 0.0, -1.0, 0.0), std::invalid_argument) << alpha;
  }
  EXPECT_THROW(LaSegment(kInf, 1.0, o, 0.0, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(-kInf, 1.0, o, 0.0, 1.0, 1.5), std::invalid_argument);
  EXPECT_THROW(LaSegment(1.0, 1.0, o, nan, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(1.0, 1.0, Vec2(nan, 0.0), 0.0, 1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(LaSegment(1.0, 1.0, o, 0.0, nan, 2.0), std::invalid_argument);
  // Valid edge cases do not throw: inflection end with alpha < 0, a line, a circle.
  EXPECT_NO_THROW(LaSegment(-0.5, 1.0, o, 0.0, 0.0, 1.0));
  EXPECT_NO_THROW(LaSegment(-2.0, 1.0, o, 0.0, -1.0, 0.0));
  EXPECT_NO_THROW(LaSegment(1.0, 1.0, o, 0.0, 0.0, 0.0));
  EXPECT_NO_THROW(LaSegment(kInf, 1.0, o, 0.0, 2.0, 2.0));
}

// ---------------------------------------------------------------------------------
// Precision near the circle.

TEST(LaSegmentTest, NearlyCircularSegmentStaysCloseToTheCircle) {
  // kappa_end = kappa_start (1 + 1e-12): the true curve differs from the circle by at
  // most |delta kappa| L^2 / 2 = 1e-12 L (kappa L = 2 here), so positions must be
  // within 2e-12 L of the circle and theta within 2e-12 rad of kappa s; a formula
  // that cancels (1 - ratio^alpha) / (ratio - 1) style would lose ~1e-4 here.
  constexpr double kRelTol = 2e-12;
  const double length = 2.0, k0 = 1.0, k1 = k0 * (1.0 + 1e-12);
  const Vec2 start(0.5, 0.5);
  for (double alpha : {-3.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0, 5.0}) {
    for (double sign : {+1.0, -1.0}) {
      const LaSegment seg(alpha, length, start, 0.3, sign * k0, sign * k1);
      ASSERT_FALSE(seg.isCircular());
      for (double s : stations(length, 8)) {
        const std::string at = describe(seg) + " s=" + std::to_string(s);
        expectNear(seg.position(s, kTightTolerance), circleOracle(start, 0.3, sign * k0, s),
                   kRelTol * length, at);
        EXPECT_NEAR(seg.theta(s), 0.3 + sign * k0 * s, 2e-12) << at;
        EXPECT_NEAR(seg.kappa(s), sign * k0, 2e-12) << at;
      }
    }
  }
}

}  // namespace
}  // namespace la
