// Tests of the ALP curve (core/alp_curve.h), its Bezier-function numerics
// (core/bernstein.h) and its JSON form (core/alp_curve_json.h): theta against
// quadrature of kappa, positions against an independent ODE integration, dkappa
// against finite differences, rational with unit weights = polynomial, degree 1 =
// clothoid (against LaSegment), round trips. Random curves use std::mt19937 with the
// seed written at each use.

#include "core/alp_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "core/alp_curve_json.h"
#include "core/bernstein.h"
#include "core/curve_json.h"
#include "core/la_segment.h"
#include "core/quadrature.h"

namespace la {
namespace {

// A random curve: degree 1..7, control curvatures in [-3, 3] / length, weights in
// [0.3, 3] when rational.
AlpCurve randomCurve(std::mt19937& rng, bool rational) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 1 + static_cast<int>(unit(rng) * 7);
  const double length = std::pow(10.0, 2.0 * unit(rng) - 1.0);
  std::vector<double> kappa(n + 1), weights;
  for (double& k : kappa) k = (6.0 * unit(rng) - 3.0) / length;
  if (rational)
    for (int i = 0; i <= n; ++i) weights.push_back(0.3 + 2.7 * unit(rng));
  return AlpCurve(kappa, weights, length, Vec2(unit(rng) * 10, unit(rng) * 10), 6.0 * unit(rng) - 3.0);
}

// Independent positions: classical RK4 on (x, y, theta)' = (cos theta, sin theta,
// kappa(s)) using only kappa(s), with N and 2N steps and Richardson extrapolation
// (error O(h^5) after it).
Vec2 rk4Position(const AlpCurve& c, double s_end, int steps) {
  auto run = [&](int n) {
    const double h = s_end / n;
    double x = c.start().x(), y = c.start().y(), th = c.theta0();
    for (int i = 0; i < n; ++i) {
      const double s = i * h;
      const double k1 = c.kappa(s), k2 = c.kappa(s + 0.5 * h), k4 = c.kappa(s + h);
      // RK4 on the state (x, y, theta): the stage values of theta
      const double a1 = th;
      const double a2 = th + 0.5 * h * k1;
      const double a3 = th + 0.5 * h * k2;
      const double a4 = th + h * k2;
      x += h / 6.0 * (std::cos(a1) + 2 * std::cos(a2) + 2 * std::cos(a3) + std::cos(a4));
      y += h / 6.0 * (std::sin(a1) + 2 * std::sin(a2) + 2 * std::sin(a3) + std::sin(a4));
      th += h / 6.0 * (k1 + 4 * k2 + k4);
    }
    return Vec2(x, y);
  };
  const Vec2 coarse = run(steps), fine = run(2 * steps);
  return fine + (fine - coarse) / 15.0;
}

TEST(AlpCurve, ThetaIsTheIntegralOfKappa) {
  std::mt19937 rng(101);  // seed
  for (int trial = 0; trial < 40; ++trial) {
    const AlpCurve c = randomCurve(rng, trial % 2 == 1);
    for (double f : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      const double s = f * c.length();
      const double integral = integrateAdaptive([&](double t) { return c.kappa(t); }, 0.0, s, 1e-14).value;
      const double scale = std::max(1.0, c.totalTurning());
      EXPECT_LE(std::abs(c.theta(s) - c.theta0() - integral), 1e-12 * scale)
          << "trial " << trial << " s " << s << ": theta " << c.theta(s) - c.theta0() << " vs " << integral;
    }
  }
}

TEST(AlpCurve, PositionsMatchIndependentIntegration) {
  std::mt19937 rng(202);  // seed
  for (int trial = 0; trial < 30; ++trial) {
    const AlpCurve c = randomCurve(rng, trial % 2 == 1);
    for (double f : {0.31, 1.0}) {
      const double s = f * c.length();
      const Vec2 want = rk4Position(c, s, 4000);
      const Vec2 got = c.position(s, 1e-12);
      EXPECT_LE((got - want).norm() / c.length(), 1e-10)
          << "trial " << trial << " s " << s << ": " << got.transpose() << " vs RK4 " << want.transpose();
    }
    EXPECT_LE((c.end() - c.position(c.length() * (1 - 1e-15), 1e-13)).norm() / c.length(), 1e-12);
  }
}

TEST(AlpCurve, DkappaMatchesFiniteDifferences) {
  std::mt19937 rng(303);  // seed
  for (int trial = 0; trial < 40; ++trial) {
    const AlpCurve c = randomCurve(rng, trial % 2 == 1);
    const double L = c.length(), h = 1e-5 * L;
    for (double f : {0.1, 0.35, 0.5, 0.9}) {
      const double s = f * L;
      const double fd = (c.kappa(s + h) - c.kappa(s - h)) / (2 * h);
      double scale = 0.0;
      for (double k : c.controlKappa()) scale = std::max(scale, std::abs(k));
      // central differences: error ~ h^2 kappa''' / 6, and kappa varies on the scale L
      EXPECT_LE(std::abs(c.dkappa(s) - fd), 1e-6 * scale / L) << "trial " << trial << " dkappa " << c.dkappa(s)
                                                               << " vs " << fd;
    }
  }
}

TEST(AlpCurve, RationalWithUnitWeightsEqualsPolynomial) {
  std::mt19937 rng(404);  // seed
  for (int trial = 0; trial < 20; ++trial) {
    const AlpCurve p = randomCurve(rng, false);
    const AlpCurve r(p.controlKappa(), std::vector<double>(p.controlKappa().size(), 1.7), p.length(), p.start(),
                     p.theta0());
    ASSERT_TRUE(r.isRational());
    for (double f : {0.0, 0.2, 0.6, 1.0}) {
      const double s = f * p.length();
      EXPECT_NEAR(r.kappa(s), p.kappa(s), 1e-12 * (1 + std::abs(p.kappa(s))));
      EXPECT_NEAR(r.dkappa(s) * p.length(), p.dkappa(s) * p.length(), 1e-10 * (1 + std::abs(p.dkappa(s) * p.length())));
      EXPECT_NEAR(r.theta(s), p.theta(s), 1e-12 * (1 + std::abs(p.theta(s))));
      EXPECT_LE((r.position(s, 1e-13) - p.position(s, 1e-13)).norm() / p.length(), 1e-11);
    }
  }
}

TEST(AlpCurve, DegreeOneIsAClothoid) {
  // Same-sign end curvatures: an LA segment with alpha = -1 is the same clothoid.
  for (double k1 : {0.2, 1.0, 3.5}) {
    const double k0 = 1.3, L = 2.0;
    const AlpCurve c({k0, k1}, {}, L, Vec2(1, 2), 0.4);
    const LaSegment seg(-1.0, L, Vec2(1, 2), 0.4, k0, k1);
    for (double f : {0.25, 0.5, 1.0}) {
      const double s = f * L;
      EXPECT_NEAR(c.kappa(s), seg.kappa(s), 1e-13);
      EXPECT_NEAR(c.theta(s), seg.theta(s), 1e-13);
      EXPECT_LE((c.position(s, 1e-13) - seg.position(s, 1e-13)).norm(), 1e-11)
          << c.position(s).transpose() << " vs LA " << seg.position(s).transpose();
      EXPECT_NEAR(c.dkappa(s), (k1 - k0) / L, 1e-13);
    }
  }
}

TEST(AlpCurve, SamplesAgreeWithEvaluation) {
  std::mt19937 rng(505);  // seed
  for (int trial = 0; trial < 10; ++trial) {
    const AlpCurve c = randomCurve(rng, trial % 2 == 1);
    CurveSamples smp;
    c.sample(2, smp);  // sample() appends to what is there
    c.sample(33, smp, 5.0);
    ASSERT_EQ(smp.size(), 35u);
    EXPECT_DOUBLE_EQ(smp.s.back(), 5.0 + c.length());
    for (std::size_t i = 2; i < smp.size(); ++i) {
      const double s = smp.s[i] - 5.0;
      EXPECT_LE((smp.point[i] - c.position(s, 1e-13)).norm() / c.length(), 1e-10) << "sample " << i;
      EXPECT_NEAR(smp.theta[i], c.theta(s), 1e-12);
      EXPECT_NEAR(smp.kappa[i], c.kappa(s), 1e-12 * (1 + std::abs(c.kappa(s))));
      EXPECT_NEAR(smp.tangent[i].x(), std::cos(smp.theta[i]), 1e-15);
    }
  }
}

TEST(AlpCurve, TotalTurningAndMaxKappaAgainstDenseSampling) {
  std::mt19937 rng(606);  // seed
  for (int trial = 0; trial < 20; ++trial) {
    const AlpCurve c = randomCurve(rng, trial % 2 == 1);
    constexpr int kSamples = 20000;
    double variation = 0.0, kmax = 0.0, prev = c.theta(0.0);
    for (int i = 0; i <= kSamples; ++i) {
      const double s = c.length() * i / kSamples;
      const double th = c.theta(s);
      variation += std::abs(th - prev);
      prev = th;
      kmax = std::max(kmax, std::abs(c.kappa(s)));
    }
    EXPECT_NEAR(c.totalTurning(), variation, 1e-7 * (1 + variation)) << "trial " << trial;
    EXPECT_GE(c.maxAbsKappa(), kmax * (1 - 1e-12)) << "trial " << trial;
    EXPECT_LE(c.maxAbsKappa(), kmax * (1 + 1e-6)) << "trial " << trial;
  }
}

TEST(AlpCurve, RejectsBadParameters) {
  EXPECT_THROW(AlpCurve({}, {}, 1.0, Vec2::Zero(), 0.0), std::invalid_argument);
  EXPECT_THROW(AlpCurve({1.0, 2.0}, {1.0}, 1.0, Vec2::Zero(), 0.0), std::invalid_argument);
  EXPECT_THROW(AlpCurve({1.0, 2.0}, {1.0, 0.0}, 1.0, Vec2::Zero(), 0.0), std::invalid_argument);
  EXPECT_THROW(AlpCurve({1.0, 2.0}, {}, 0.0, Vec2::Zero(), 0.0), std::invalid_argument);
  EXPECT_THROW(AlpCurve({1.0, NAN}, {}, 1.0, Vec2::Zero(), 0.0), std::invalid_argument);
  EXPECT_THROW(AlpCurve({1.0, 2.0}, {}, 1.0, Vec2(NAN, 0), 0.0), std::invalid_argument);
  const AlpCurve c({1.0, 2.0}, {}, 1.0, Vec2::Zero(), 0.0);
  CurveSamples smp;
  EXPECT_THROW(c.sample(1, smp), std::invalid_argument);
}

TEST(AlpCurveJson, RoundTripsExactly) {
  std::mt19937 rng(707);  // seed
  for (int trial = 0; trial < 10; ++trial) {
    const AlpCurve c = randomCurve(rng, trial % 2 == 1);
    const AlpCurvatureCheck check{true, false, {0.25 * c.length()}, {0.5 * c.length()}};
    const nlohmann::json j = alpCurveToJson(c, check);
    EXPECT_EQ(j["type"], "alp");
    EXPECT_EQ(j["checks"]["has_inflection"], true);
    const AlpCurve back = alpCurveFromJson(nlohmann::json::parse(j.dump()), "curve");
    EXPECT_EQ(back.controlKappa(), c.controlKappa());
    EXPECT_EQ(back.weights(), c.weights());
    EXPECT_EQ(back.length(), c.length());
    EXPECT_EQ(back.start(), c.start());
    EXPECT_EQ(back.theta0(), c.theta0());
  }
}

TEST(AlpCurveJson, MalformedInputSaysWhere) {
  const AlpCurve c({1.0, 2.0, 0.5}, {}, 1.0, Vec2::Zero(), 0.0);
  nlohmann::json j = alpCurveToJson(c, {});
  auto expectError = [](const nlohmann::json& bad, const std::string& fragment) {
    try {
      alpCurveFromJson(bad, "curves[1]");
      ADD_FAILURE() << "no error for " << bad.dump();
    } catch (const CurveFormatError& e) {
      EXPECT_NE(std::string(e.what()).find("curves[1]: "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  nlohmann::json bad = j;
  bad.erase("length");
  expectError(bad, "\"length\"");
  bad = j;
  bad["degree"] = 3;
  expectError(bad, "degree");
  bad = j;
  bad["type"] = "la";
  expectError(bad, "type");
  bad = j;
  bad["length"] = -1.0;
  expectError(bad, "length");
}

// Bernstein numerics: sign changes against dense sampling of random functions, and a
// root placed exactly on a subdivision point.
TEST(Bernstein, SignChangesAgainstDenseSampling) {
  std::mt19937 rng(808);  // seed
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    BernsteinCoefficients c(2 + trial % 12);
    for (double& v : c) v = unit(rng);
    const std::vector<double> roots = bernsteinSignChanges(c);
    constexpr int kSamples = 100000;
    std::vector<double> sampled;
    double prev = evaluateBernstein(c, 0.0);
    for (int i = 1; i <= kSamples; ++i) {
      const double t = double(i) / kSamples, v = evaluateBernstein(c, t);
      if ((v > 0) != (prev > 0) && v != 0.0) sampled.push_back(t);
      prev = v;
    }
    ASSERT_EQ(roots.size(), sampled.size()) << "trial " << trial;
    for (std::size_t k = 0; k < roots.size(); ++k) {
      EXPECT_NEAR(roots[k], sampled[k], 1.0 / kSamples) << "trial " << trial;
      EXPECT_NEAR(evaluateBernstein(c, roots[k]), 0.0, 1e-13);
    }
  }
  // (t - 0.5)(t - 0.2)(t - 0.8) in degree 3: the middle root is the first split point
  BernsteinCoefficients exact(4);
  // from the power basis a0 + a1 t + a2 t^2 + a3 t^3
  const double a0 = -0.08, a1 = 0.66, a2 = -1.5, a3 = 1.0;
  exact[0] = a0;
  exact[1] = a0 + a1 / 3;
  exact[2] = a0 + 2 * a1 / 3 + a2 / 3;
  exact[3] = a0 + a1 + a2 + a3;
  const auto r = bernsteinSignChanges(exact);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_NEAR(r[0], 0.2, 1e-14);
  EXPECT_NEAR(r[1], 0.5, 1e-14);
  EXPECT_NEAR(r[2], 0.8, 1e-14);
  // a double root is no sign change
  EXPECT_TRUE(bernsteinSignChanges({0.25, -0.25, 0.25}).empty());
  EXPECT_TRUE(bernsteinSignChanges({0.0, 0.0, 0.0}).empty());
}

TEST(Bernstein, IntegralDerivativeProduct) {
  const BernsteinCoefficients f = {1.0, -2.0, 0.5, 3.0}, g = {0.3, 1.1, -0.7};
  const auto F = bernsteinIntegral(f), df = bernsteinDerivative(f), fg = bernsteinProduct(f, g);
  for (double t : {0.0, 0.3, 0.71, 1.0}) {
    const double integral = integrateFixed<10>([&](double x) { return evaluateBernstein(f, x); }, 0.0, t);
    EXPECT_NEAR(evaluateBernstein(F, t), integral, 1e-14);
    const double h = 1e-6;
    EXPECT_NEAR(evaluateBernstein(df, t),
                (evaluateBernstein(f, std::min(t + h, 1.0)) - evaluateBernstein(f, std::max(t - h, 0.0))) /
                    (std::min(t + h, 1.0) - std::max(t - h, 0.0)),
                1e-4);  // one-sided at the ends: error ~ h f'' / 2
    EXPECT_NEAR(evaluateBernstein(fg, t), evaluateBernstein(f, t) * evaluateBernstein(g, t), 1e-14);
  }
}

}  // namespace
}  // namespace la
