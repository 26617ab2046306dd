// Tests of the ALP G1/G2 Hermite solve and the curvature checks (core/alp_hermite.h):
// end conditions met, the seed's special cases (n = 1 clothoid, p = 0 independent of
// n, unit weights = polynomial), invariance under similarity transforms, checks
// against dense sampling, bad input. Random sweeps use std::mt19937 with the seed
// written at each use.

#include "core/alp_hermite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <Eigen/Geometry>

#include "core/la_segment.h"

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;

// Every condition of the Hermite problem, measured on the returned curve.
void expectMeetsConditions(const AlpSolve& s, const HermiteEnd& a, const HermiteEnd& b, int continuity,
                           double tol, const std::string& what) {
  ASSERT_TRUE(s.report.usable()) << what << ": " << s.report.message;
  ASSERT_TRUE(s.curve.has_value()) << what;
  const AlpCurve& c = *s.curve;
  const double chord = (b.point - a.point).norm();
  EXPECT_LE((c.position(0.0) - a.point).norm() / chord, tol) << what << " start point";
  EXPECT_LE((c.position(c.length(), 1e-14) - b.point).norm() / chord, tol)
      << what << " end point " << c.end().transpose() << " vs " << b.point.transpose();
  EXPECT_NEAR(c.theta(0.0), a.theta, tol) << what << " start tangent";
  EXPECT_NEAR(c.theta(c.length()), b.theta, tol) << what << " end tangent";
  if (continuity == 2) {
    EXPECT_LE(std::abs(c.kappa(0.0) - a.kappa) * chord, tol) << what << " start curvature " << c.kappa(0.0);
    EXPECT_LE(std::abs(c.kappa(c.length()) - b.kappa) * chord, tol) << what << " end curvature "
                                                                       << c.kappa(c.length());
  }
}

TEST(AlpHermite, G1SeededSweepMeetsConditions) {
  std::mt19937 rng(5150);  // seed: fixed, so failures reproduce
  std::uniform_real_distribution<double> unit(0.0, 1.0), angle(-kPi, kPi);
  int solved = 0, tried = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const double scale = std::pow(10.0, 4.0 * unit(rng) - 2.0);
    const HermiteEnd a{Vec2(10 * angle(rng), 10 * angle(rng)) * scale, angle(rng), 0.0};
    const Vec2 chord = unitVector(angle(rng)) * scale * (0.5 + unit(rng));
    // end tangent within 80 degrees of the chord's mirror image: from C-shaped to S-shaped
    const double phi = angleOf(chord) - a.theta;
    const double turn = 2.0 * wrapAngle(phi) + (unit(rng) - 0.5) * 2.8;
    const HermiteEnd b{a.point + chord, a.theta + turn, 0.0};
    AlpShape shape;
    shape.degree = 1 + trial % 6;
    shape.p = (trial % 3 - 1) * 0.5;
    shape.rational = trial % 4 == 3;
    shape.w_e = 0.5 + 2.0 * unit(rng);
    shape.p_w = unit(rng) - 0.5;
    ++tried;
    const AlpSolve s = solveAlpHermite(a, b, 1, shape);
    if (!s.report.usable()) continue;
    ++solved;
    expectMeetsConditions(s, a, b, 1, 1e-9, "trial " + std::to_string(trial));
  }
  EXPECT_GE(solved, tried * 9 / 10) << "G1 with moderate turning should almost always solve";
}


TEST(AlpHermite, G2SeededSweepMeetsConditions) {
  std::mt19937 rng(6060);  // seed
  std::uniform_real_distribution<double> unit(0.0, 1.0), angle(-kPi, kPi);
  int solved = 0, tried = 0;
  for (int trial = 0; trial < 80; ++trial) {
    // A C-shaped condition in the normalized frame (chord (0,0)-(1,0), symmetric-ish
    // tangents), end curvatures near those of the circular arc, then a random
    // similarity transform.
    const double half = 0.2 + 1.0 * unit(rng);
    const double t0 = half * (0.7 + 0.6 * unit(rng)), t1 = -half * (0.7 + 0.6 * unit(rng));
    const double k_arc = 2.0 * std::sin(half);
    const double ks = k_arc * (0.5 + unit(rng)), ke = k_arc * (0.5 + unit(rng));
    const double scale = std::pow(10.0, 2.0 * unit(rng) - 1.0), rot = angle(rng);
    const Vec2 shift(5 * angle(rng), 5 * angle(rng));
    auto place = [&](const Vec2& p) { return Vec2(shift + scale * (Eigen::Rotation2Dd(rot) * p)); };
    const HermiteEnd a{place(Vec2(0, 0)), t0 + rot, ks / scale};
    const HermiteEnd b{place(Vec2(1, 0)), t1 + rot, ke / scale};
    AlpShape shape;
    shape.degree = 3 + trial % 4;
    shape.p = (trial % 3 - 1) * 0.4;
    shape.rational = trial % 5 == 4;
    shape.w_e = 0.5 + 2.0 * unit(rng);
    ++tried;
    const AlpSolve s = solveAlpHermite(a, b, 2, shape);
    if (!s.report.usable()) continue;
    ++solved;
    expectMeetsConditions(s, a, b, 2, 1e-9, "trial " + std::to_string(trial));
  }
  EXPECT_GE(solved, tried * 9 / 10) << "G2 near a circular arc should almost always solve";
}

TEST(AlpHermite, DegreeOneG1IsAClothoid) {
  // kappa linear in s; with end curvatures of one sign it is the LA segment alpha = -1
  const HermiteEnd a{Vec2(0, 0), 0.0, 0}, b{Vec2(3, 1), 0.75, 0};
  AlpShape shape;
  shape.degree = 1;
  const AlpSolve s = solveAlpHermite(a, b, 1, shape);
  expectMeetsConditions(s, a, b, 1, 1e-9, "n = 1");
  const AlpCurve& c = *s.curve;
  const double slope = (c.kappa(c.length()) - c.kappa(0)) / c.length();
  for (double f : {0.1, 0.5, 0.9}) EXPECT_NEAR(c.dkappa(f * c.length()), slope, 1e-12);
  ASSERT_GT(c.kappa(0) * c.kappa(c.length()), 0.0) << "this condition has no inflection";
  const LaSegment seg(-1.0, c.length(), a.point, a.theta, c.kappa(0), c.kappa(c.length()));
  EXPECT_LE((seg.end(1e-14) - b.point).norm(), 1e-9) << "the clothoid with these ends meets the end point";
  EXPECT_NEAR(seg.theta(seg.length()), b.theta, 1e-12);
}

TEST(AlpHermite, G1WithPZeroIsTheSameCurveForEveryDegree) {
  // seed 000 section 5.1: with p = 0 the control curvatures are a linear function
  // degree-elevated, so every n gives the n = 1 clothoid.
  const HermiteEnd a{Vec2(1, 1), 0.3, 0}, b{Vec2(4, 2), -0.5, 0};
  AlpShape shape;
  shape.degree = 1;
  const AlpSolve ref = solveAlpHermite(a, b, 1, shape);
  ASSERT_TRUE(ref.report.usable()) << ref.report.message;
  for (int n = 2; n <= 9; ++n) {
    shape.degree = n;
    const AlpSolve s = solveAlpHermite(a, b, 1, shape);
    ASSERT_TRUE(s.report.usable()) << "n = " << n << ": " << s.report.message;
    EXPECT_NEAR(s.curve->length(), ref.curve->length(), 1e-10 * ref.curve->length()) << "n = " << n;
    for (double f : {0.0, 0.3, 0.6, 1.0}) {
      const double t = f * ref.curve->length();
      EXPECT_NEAR(s.curve->kappa(t), ref.curve->kappa(t), 1e-9) << "n = " << n << " s = " << t;
      EXPECT_LE((s.curve->position(t, 1e-13) - ref.curve->position(t, 1e-13)).norm(), 1e-9) << "n = " << n;
    }
  }
}

TEST(AlpHermite, RationalWithUnitWeightsEqualsPolynomial) {
  const HermiteEnd a{Vec2(0, 0), 0.5, 0.8}, b{Vec2(2, 0), -0.4, 1.1};
  for (int continuity : {1, 2}) {
    AlpShape poly;
    poly.degree = 5;
    poly.p = 0.3;
    AlpShape rat = poly;
    rat.rational = true;
    rat.w_e = 1.0;
    rat.p_w = 0.7;  // irrelevant when w_e = 1: every weight is 1
    const AlpSolve sp = solveAlpHermite(a, b, continuity, poly), sr = solveAlpHermite(a, b, continuity, rat);
    ASSERT_TRUE(sp.report.usable() && sr.report.usable()) << sp.report.message << " / " << sr.report.message;
    for (double w : sr.curve->weights()) EXPECT_EQ(w, 1.0);
    EXPECT_NEAR(sr.curve->length(), sp.curve->length(), 1e-10);
    for (std::size_t i = 0; i < sp.curve->controlKappa().size(); ++i)
      EXPECT_NEAR(sr.curve->controlKappa()[i], sp.curve->controlKappa()[i], 1e-8) << "G" << continuity << " i " << i;
  }
}

TEST(AlpHermite, InvariantUnderSimilarityTransforms) {
  const HermiteEnd a{Vec2(0, 0), 0.4, 0.9}, b{Vec2(1.5, 0.2), -0.3, 0.6};
  AlpShape shape;
  shape.degree = 4;
  shape.p = -0.3;
  for (int continuity : {1, 2}) {
    const AlpSolve ref = solveAlpHermite(a, b, continuity, shape);
    ASSERT_TRUE(ref.report.usable()) << ref.report.message;
    for (double scale : {1e-3, 0.7, 250.0})
      for (double rot : {-2.0, 0.0, 1.1}) {
        const Vec2 shift(3.0, -7.0);
        auto place = [&](const Vec2& p) { return Vec2(shift + scale * (Eigen::Rotation2Dd(rot) * p)); };
        const HermiteEnd a2{place(a.point), a.theta + rot, a.kappa / scale};
        const HermiteEnd b2{place(b.point), b.theta + rot, b.kappa / scale};
        const AlpSolve s = solveAlpHermite(a2, b2, continuity, shape);
        ASSERT_TRUE(s.report.usable()) << s.report.message;
        EXPECT_NEAR(s.curve->length() / scale, ref.curve->length(), 1e-10);
        for (std::size_t i = 0; i < ref.curve->controlKappa().size(); ++i)
          EXPECT_NEAR(s.curve->controlKappa()[i] * scale, ref.curve->controlKappa()[i], 1e-8);
        for (double f : {0.25, 0.5, 0.75}) {
          const Vec2 want = place(ref.curve->position(f * ref.curve->length(), 1e-13));
          EXPECT_LE((s.curve->position(f * s.curve->length(), 1e-13) - want).norm() / scale, 1e-9);
        }
      }
  }
}

TEST(AlpHermite, SymmetricG1IsACircularArc) {
  // equal tangent angles to the chord: u = 0 solves it, constant curvature for every n and p
  const HermiteEnd a{Vec2(0, 0), 0.6, 0}, b{Vec2(1, 0), -0.6, 0};
  for (int n : {1, 3, 6}) {
    AlpShape shape;
    shape.degree = n;
    shape.p = 0.5;
    const AlpSolve s = solveAlpHermite(a, b, 1, shape);
    ASSERT_TRUE(s.report.usable()) << s.report.message;
    const double k = -2.0 * std::sin(0.6);
    for (double ki : s.curve->controlKappa()) EXPECT_NEAR(ki, k, 1e-10) << "n = " << n;
    EXPECT_TRUE(s.check.monotone);
    EXPECT_FALSE(s.check.has_inflection);
  }
}

// The checks against dense sampling of kappa: the sign changes of kappa and of its
// differences, on solved and random curves.
TEST(AlpCurvatureCheck, AgreesWithDenseSampling) {
  std::mt19937 rng(9090);  // seed
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int with_inflection = 0, not_monotone = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 1 + trial % 6;
    std::vector<double> kappa(n + 1), weights;
    for (double& k : kappa) k = 4.0 * unit(rng) - 2.0;
    if (trial % 2) for (int i = 0; i <= n; ++i) weights.push_back(0.3 + 3.0 * unit(rng));
    const AlpCurve c(kappa, weights, 1.0 + unit(rng), Vec2::Zero(), 0.0);
    const AlpCurvatureCheck check = checkCurvature(c);
    constexpr int kSamples = 200000;
    std::vector<double> sign_changes, extrema;
    double prev = c.kappa(0.0), prev_diff = 0.0;
    for (int i = 1; i <= kSamples; ++i) {
      const double s = c.length() * i / kSamples, k = c.kappa(s), d = k - prev;
      if ((k > 0) != (prev > 0) && k != 0.0) sign_changes.push_back(s);
      if (i > 1 && (d > 0) != (prev_diff > 0) && d != 0.0 && prev_diff != 0.0) extrema.push_back(s);
      prev = k;
      if (d != 0.0) prev_diff = d;
    }
    const double ds = 2.0 * c.length() / kSamples;
    ASSERT_EQ(check.inflections.size(), sign_changes.size()) << "trial " << trial;
    for (std::size_t i = 0; i < sign_changes.size(); ++i) EXPECT_NEAR(check.inflections[i], sign_changes[i], ds);
    ASSERT_EQ(check.extrema.size(), extrema.size()) << "trial " << trial;
    for (std::size_t i = 0; i < extrema.size(); ++i) EXPECT_NEAR(check.extrema[i], extrema[i], ds);
    EXPECT_EQ(check.has_inflection, !sign_changes.empty());
    EXPECT_EQ(check.monotone, extrema.empty());
    with_inflection += check.has_inflection;
    not_monotone += !check.monotone;
  }
  EXPECT_GT(with_inflection, 10) << "the sample should exercise both outcomes";
  EXPECT_GT(not_monotone, 10);
}

TEST(AlpHermite, BadInput) {
  const HermiteEnd a{Vec2(0, 0), 0.0, 0.5}, b{Vec2(1, 0), 0.3, 0.5};
  AlpShape shape;
  auto status = [&](const HermiteEnd& x, const HermiteEnd& y, int m, const AlpShape& sh) {
    const AlpSolve s = solveAlpHermite(x, y, m, sh);
    EXPECT_FALSE(s.curve.has_value());
    EXPECT_FALSE(s.report.message.empty());
    return s.report.status;
  };
  EXPECT_EQ(status({Vec2(NAN, 0), 0.0, 0.0}, b, 1, shape), SolveStatus::kBadInput);
  EXPECT_EQ(status(a, {Vec2(1, 0), NAN, 0.0}, 1, shape), SolveStatus::kBadInput);
  EXPECT_EQ(status(a, {Vec2(1, 0), 0.3, NAN}, 2, shape), SolveStatus::kBadInput);
  EXPECT_EQ(status(a, a, 1, shape), SolveStatus::kBadInput) << "coincident points";
  EXPECT_EQ(status(a, b, 3, shape), SolveStatus::kBadInput) << "continuity 3";
  AlpShape low = shape;
  low.degree = 2;
  EXPECT_EQ(status(a, b, 2, low), SolveStatus::kBadInput) << "G2 needs n >= 3";
  low.degree = 0;
  EXPECT_EQ(status(a, b, 1, low), SolveStatus::kBadInput) << "G1 needs n >= 1";
  AlpShape rat = shape;
  rat.rational = true;
  rat.w_e = -1.0;
  EXPECT_EQ(status(a, b, 1, rat), SolveStatus::kBadInput) << "negative weight";
  rat.w_e = 3.0;
  rat.p_w = -5.0;
  EXPECT_EQ(status(a, b, 1, rat), SolveStatus::kBadInput) << "eq. 12 with p_w = -5 gives a negative weight";
  AlpShape nan_p = shape;
  nan_p.p = NAN;
  EXPECT_EQ(status(a, b, 1, nan_p), SolveStatus::kBadInput);
  // G1 ignores the curvatures, NaN or not
  EXPECT_TRUE(solveAlpHermite({Vec2(0, 0), 0.0, NAN}, b, 1, shape).report.usable());
}

TEST(AlpHermite, ImpossibleG2IsReportedNotReturned) {
  // a straight chord with straight tangents but huge opposite end curvatures and a
  // degree-3 function: whatever the solver says, it must not return a curve that
  // misses the conditions.
  const HermiteEnd a{Vec2(0, 0), 0.0, 200.0}, b{Vec2(1, 0), 0.0, 200.0};
  AlpShape shape;
  const AlpSolve s = solveAlpHermite(a, b, 2, shape);
  if (s.report.usable()) {
    expectMeetsConditions(s, a, b, 2, 1e-9, "if solved");
  } else {
    EXPECT_FALSE(s.curve.has_value());
    EXPECT_TRUE(s.report.status == SolveStatus::kInfeasible || s.report.status == SolveStatus::kIterationLimit)
        << toString(s.report.status);
    EXPECT_NE(s.report.message.find("end gap"), std::string::npos) << s.report.message;
  }
}

TEST(AlpHermite, WeightsFollowEquation12) {
  AlpShape shape;
  shape.degree = 4;
  shape.rational = true;
  shape.w_e = 3.0;
  shape.p_w = 0.0;
  const auto w = alpWeights(shape);
  ASSERT_EQ(w.size(), 5u);
  for (int i = 0; i <= 4; ++i) EXPECT_NEAR(w[i], 1.0 + 2.0 * i / 4.0, 1e-15) << "p_w = 0: linear";
  EXPECT_EQ(alpInterpolate(1.0, 3.0, 3, 1.0), std::vector<double>(3, 3.0)) << "p = 1: all p_e";
  EXPECT_EQ(alpInterpolate(1.0, 3.0, 3, -1.0), std::vector<double>(3, 1.0)) << "p = -1: all p_s";
}

}  // namespace
}  // namespace la
