// Tests of the 3-point LA segment (core/three_point_segment.h): round trips from
// segments built with known parameters, closed forms, invariance, feasibility and
// bad input. Random sweeps use std::mt19937 with the seed written at each use.

#include "core/three_point_segment.h"

#include <gtest/gtest.h>

#include "tests/test_support.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <complex>
#include <limits>

#include <cmath>
#include <numbers>
#include <iostream>
#include <random>

#include "core/quadrature.h"

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;

using test::Triangle;
using test::triangleOf;
using test::relDiff;

// Checks that the solved segment reproduces the given one (same end points and curvatures).
void expectSameSegment(const LaSegment& want, const LaSegment& got, double tol, const std::string& what) {
  const double L = want.length();
  EXPECT_LE(relDiff(got.length(), want.length()), tol) << what << " length " << got.length() << " vs " << want.length();
  EXPECT_LE(std::abs(got.kappaStart() - want.kappaStart()) * L, tol)
      << what << " kappa_start " << got.kappaStart() << " vs " << want.kappaStart();
  EXPECT_LE(std::abs(got.kappaEnd() - want.kappaEnd()) * L, tol)
      << what << " kappa_end " << got.kappaEnd() << " vs " << want.kappaEnd();
  EXPECT_LE((got.end(1e-14) - want.end(1e-14)).norm() / L, tol) << what << " end point";
  EXPECT_LE(std::abs(wrapAngle(got.theta(got.length()) - want.theta(L))), tol) << what << " end tangent";
}

TEST(ThreePointSegment, RoundTripSeededSweep) {
  std::mt19937 rng(20261122);  // seed: fixed, so failures reproduce
  std::uniform_real_distribution<double> alpha_dist(-3.0, 3.0), log_ratio(-3.0, 3.0),
      unit(0.0, 1.0), angle(-kPi, kPi);
  int solved = 0;
  for (int trial = 0; trial < 400; ++trial) {
    double alpha = alpha_dist(rng);
    if (trial % 10 == 0) alpha = std::round(alpha);  // the integer alphas: -3..3 incl. 0 and 1
    const double scale = (trial % 3 == 0) ? 1e-3 : (trial % 3 == 1 ? 1.0 : 1e3);
    const double sign = (trial % 2 == 0) ? 1.0 : -1.0;  // mirrored half the time
    const double k0 = sign / scale * (0.2 + 2.0 * unit(rng));
    const double k1 = k0 * std::exp(log_ratio(rng));
    // choose the length so the turning angle is in (0.05, 3.0)
    const double wanted_turn = 0.05 + 2.95 * unit(rng);
    LaSegment probe(alpha, 1.0 * scale, Vec2::Zero(), 0.0, k0, k1);
    const double turn_per = std::abs(probe.turning());
    const double length = scale * wanted_turn / turn_per;  // turning is not linear in L; re-check below
    const Vec2 start(scale * 10.0 * angle(rng), scale * 10.0 * angle(rng));
    const LaSegment seg(alpha, length, start, angle(rng), k0, k1 * 1.0);
    const double turn = std::abs(seg.turning());
    if (!(turn > 1e-3 && turn < kPi - 1e-3)) continue;
    const Triangle t = triangleOf(seg);
    const SegmentSolve s = solveThreePointSegment(alpha, t.q0, t.q1, t.q2);
    ASSERT_TRUE(s.report.usable()) << "trial " << trial << " alpha " << alpha << ": " << s.report.message;
    expectSameSegment(seg, *s.segment, 1e-9, "trial " + std::to_string(trial) + " alpha " + std::to_string(alpha));
    EXPECT_NEAR(s.shape, std::log(std::abs(k0 / k1)), 1e-9) << "shape m = log(rho1/rho0)";
    ++solved;
  }
  EXPECT_GT(solved, 300) << "too few valid trials";
}

TEST(ThreePointSegment, IsoscelesGivesCircleForEveryAlpha) {
  // seed 003 footnote 2: equal legs Q0Q1 = Q1Q2 -> circular arc
  for (double alpha : {-3.0, -1.0, 0.0, 0.5, 1.0, 2.0, 3.0, 25.0, std::numeric_limits<double>::infinity()}) {
    for (double theta_d : {1e-6, 0.3, 1.5, 3.0}) {
      const Vec2 q0(0, 0), q1(1, 0), q2 = q1 + unitVector(theta_d);
      const SegmentSolve s = solveThreePointSegment(alpha, q0, q1, q2);
      ASSERT_TRUE(s.report.usable()) << alpha << " " << s.report.message;
      const double kappa = 2.0 * std::sin(theta_d / 2) / (q2 - q0).norm();  // chord = 2R sin(theta/2)
      EXPECT_LE(relDiff(s.segment->kappaStart(), kappa), 1e-12) << "alpha " << alpha << " theta_d " << theta_d;
      EXPECT_LE(relDiff(s.segment->kappaEnd(), kappa), 1e-12) << "alpha " << alpha << " theta_d " << theta_d;
      EXPECT_LE(relDiff(s.segment->length(), theta_d / kappa), 1e-12);
    }
  }
}

TEST(ThreePointSegment, LogarithmicSpiralClosedForm) {
  // alpha = 1: rho = rho0 e^{k theta}; chord E = integral rho e^{i theta} dtheta has the
  // closed form rho0 (e^{(k+i) theta_d} - 1)/(k + i).
  for (double k : {-1.5, -0.3, 0.4, 2.0}) {
    const double theta_d = 2.0;
    const std::complex<double> ki(k, 1.0);
    const std::complex<double> e = (std::exp(ki * theta_d) - 1.0) / ki;
    const Vec2 q0(0, 0), q2(e.real(), e.imag());
    // tangent at the end is theta_d: Q1 on the x axis where the end tangent crosses it
    const Vec2 t1 = unitVector(theta_d);
    const Vec2 q1(q2.x() - q2.y() / t1.y() * t1.x(), 0.0);
    const SegmentSolve s = solveThreePointSegment(1.0, q0, q1, q2);
    ASSERT_TRUE(s.report.usable()) << s.report.message;
    EXPECT_LE(relDiff(s.segment->kappaStart(), 1.0), 1e-11) << "k " << k;
    EXPECT_LE(relDiff(s.segment->kappaEnd(), std::exp(-k * theta_d)), 1e-11) << "k " << k;
    const double length = (std::exp(k * theta_d) - 1.0) / k;  // integral of rho dtheta
    EXPECT_LE(relDiff(s.segment->length(), length), 1e-11) << "k " << k;
  }
}

TEST(ThreePointSegment, InvariantUnderRotationTranslationScaleMirror) {
  const Vec2 q0(0.1, -0.2), q1(1.3, 0.1), q2(1.9, 1.4);
  const SegmentSolve base = solveThreePointSegment(-0.7, q0, q1, q2);
  ASSERT_TRUE(base.report.usable()) << base.report.message;
  const double L = base.segment->length();
  for (double phi : {0.3, 2.0, -2.9}) {
    for (double k : {1e-3, 7.0, 1e3}) {
      const Eigen::Rotation2Dd rot(phi);
      const Vec2 shift(5.0, -3.0);
      auto map = [&](const Vec2& p) { return Vec2(k * (rot * p) + shift); };
      const SegmentSolve moved = solveThreePointSegment(-0.7, map(q0), map(q1), map(q2));
      ASSERT_TRUE(moved.report.usable());
      EXPECT_LE(relDiff(moved.segment->length(), k * L), 1e-12);
      EXPECT_LE(relDiff(moved.segment->kappaStart(), base.segment->kappaStart() / k), 1e-12);
      EXPECT_LE(relDiff(moved.segment->kappaEnd(), base.segment->kappaEnd() / k), 1e-10);
      for (double f : {0.25, 0.5, 1.0}) {
        const Vec2 want = map(base.segment->position(f * L, 1e-14));
        EXPECT_LE((moved.segment->position(f * k * L, 1e-14) - want).norm(), 1e-11 * k * L);
      }
    }
  }
  // Mirror (y -> -y): same curve mirrored, curvature signs flip.
  auto mirror = [](const Vec2& p) { return Vec2(p.x(), -p.y()); };
  const SegmentSolve m = solveThreePointSegment(-0.7, mirror(q0), mirror(q1), mirror(q2));
  ASSERT_TRUE(m.report.usable());
  EXPECT_LE(relDiff(m.segment->kappaStart(), -base.segment->kappaStart()), 1e-12);
  EXPECT_LE((m.segment->end(1e-14) - mirror(q2)).norm(), 1e-11 * L);
}

TEST(ThreePointSegment, EndPointAndEndTangentMatchTriangle) {
  // independent of the solver's own quadrature: LaSegment integrates in arc length
  for (double alpha : {-2.5, -1.0, 0.0, 0.3, 1.0, 1.7, 2.0, 4.0}) {
    const Vec2 q0(0, 0), q1(2, 0), q2(2.6, 1.1);
    const SegmentSolve s = solveThreePointSegment(alpha, q0, q1, q2);
    if (!s.report.usable()) {
      EXPECT_EQ(s.report.status, SolveStatus::kInfeasible) << alpha << " " << s.report.message;
      continue;
    }
    EXPECT_LE((s.segment->end(1e-14) - q2).norm(), 1e-11) << "alpha " << alpha;
    EXPECT_LE(std::abs(wrapAngle(s.segment->theta(s.segment->length()) - angleOf(q2 - q1))), 1e-11);
    EXPECT_NEAR(s.segment->theta0(), 0.0, 1e-15);
  }
}

TEST(ThreePointSegment, NearlyStraightTriangles) {
  for (double alpha : {-1.0, 0.0, 1.0, 2.0}) {
    for (double theta_d : {1e-4, 1e-7}) {
      const Vec2 q0(0, 0), q1(1, 0), q2 = q1 + 0.6 * unitVector(theta_d);
      const SegmentSolve s = solveThreePointSegment(alpha, q0, q1, q2);
      ASSERT_TRUE(s.report.usable()) << alpha << " " << theta_d << " " << s.report.message;
      EXPECT_LE((s.segment->end(1e-14) - q2).norm(), 1e-12);
      EXPECT_LE(std::abs(s.segment->turning() - theta_d), 1e-12 * theta_d + 1e-16);
    }
  }
}

TEST(ThreePointSegment, InfeasibleTriangleReportsRange) {
  // alpha = 2 cannot reach chord angles near the ends of (0, theta_d): its limit
  // shapes (rho -> 0 at one end) stop short.
  const double theta_d = 1.2;
  const ChordAngleRange range = reachableChordAngles(2.0, theta_d);
  ASSERT_TRUE(range.lo > 0.0 && range.hi < theta_d && range.lo < range.hi)
      << range.lo << " " << range.hi;
  const double phi = 0.5 * range.lo;  // outside
  const Vec2 q0(0, 0), q1(1, 0);
  // put Q2 on the ray at angle theta_d from Q1 such that the chord angle is phi
  const double t = std::sin(phi) / std::sin(theta_d - phi);  // law of sines, |Q1Q0| = 1
  const Vec2 q2 = q1 + t * unitVector(theta_d);
  const SegmentSolve s = solveThreePointSegment(2.0, q0, q1, q2);
  EXPECT_EQ(s.report.status, SolveStatus::kInfeasible) << s.report.message;
  EXPECT_FALSE(s.segment.has_value());
  EXPECT_NEAR(s.reachable.lo, range.lo, 1e-12);
  EXPECT_NE(s.report.message.find("reachable"), std::string::npos) << s.report.message;
  // inside the range it solves, close to both ends
  for (double f : {0.02, 0.5, 0.98}) {
    const double phi_in = range.lo + f * (range.hi - range.lo);
    const double u = std::sin(phi_in) / std::sin(theta_d - phi_in);
    const SegmentSolve ok = solveThreePointSegment(2.0, q0, q1, q1 + u * unitVector(theta_d));
    EXPECT_TRUE(ok.report.usable()) << f << " " << ok.report.message;
  }
  // circles: only the isosceles triangle
  EXPECT_EQ(solveThreePointSegment(std::numeric_limits<double>::infinity(), q0, q1, q2).report.status, SolveStatus::kInfeasible);
}

TEST(ThreePointSegment, BadInputGivesStatusNotCrash) {
  const Vec2 a(0, 0), b(1, 0), c(2, 1);
  const double nan = std::nan("");
  EXPECT_EQ(solveThreePointSegment(nan, a, b, c).report.status, SolveStatus::kBadInput);
  EXPECT_EQ(solveThreePointSegment(1.0, Vec2(nan, 0), b, c).report.status, SolveStatus::kBadInput);
  EXPECT_EQ(solveThreePointSegment(1.0, a, a, c).report.status, SolveStatus::kBadInput);  // coincident
  EXPECT_EQ(solveThreePointSegment(1.0, a, b, b).report.status, SolveStatus::kBadInput);
  // Q2 behind Q1 on the same line: turning angle pi
  EXPECT_EQ(solveThreePointSegment(1.0, a, b, Vec2(0.5, 0)).report.status, SolveStatus::kBadInput);
  // collinear in order: a straight line, not an error
  const SegmentSolve line = solveThreePointSegment(-1.0, a, b, Vec2(3, 0));
  ASSERT_TRUE(line.report.usable());
  EXPECT_EQ(line.segment->kappaStart(), 0.0);
  EXPECT_NEAR(line.segment->length(), 3.0, 1e-15);
}


// ---------------------------------------------------------------------------------
// The speed paths of the solve: chord-angle limits (the logit's ends), the moment
// series near the branch point, and the predicted last Newton step.

TEST(ThreePointSegment, ChordAngleLimitsMatchTheLimitShapes) {
  // alpha < 0: the lower limit is the chord angle of the LA segment with an inflection
  // at its start (independent: LaSegment integrates in arc length); the upper one is
  // theta_d minus it (reversal).
  for (double alpha : {-5.0, -2.0, -1.0, -0.5, -0.1}) {
    for (double theta_d : {1e-4, 0.3, 1.5, 3.0}) {
      const LaSegment unit(alpha, 1.0, Vec2::Zero(), 0.0, 0.0, 1.0);
      const LaSegment seg(alpha, 1.0, Vec2::Zero(), 0.0, 0.0, theta_d / unit.turning());
      const Vec2 e = seg.end(1e-15);
      const double want = std::atan2(e.y(), e.x());
      const ChordAngleRange limits = chordAngleLimits(alpha, theta_d);
      EXPECT_LE(std::abs(limits.lo - want), 1e-13 * theta_d)
          << "alpha " << alpha << " theta_d " << theta_d << ": " << limits.lo << " vs " << want;
      EXPECT_LE(std::abs(limits.hi - (theta_d - want)), 1e-13 * theta_d) << "alpha " << alpha;
    }
  }
  // alpha > 1: the limit shape has rho(0) = 0; the reachable range at |m| = 30 (the
  // adaptive/log-base quadrature) is within e^{-30 (alpha-1)} of it.
  for (double alpha : {2.0, 3.0, 5.0}) {
    for (double theta_d : {0.3, 1.5, 3.0}) {
      const ChordAngleRange limits = chordAngleLimits(alpha, theta_d);
      const ChordAngleRange reach = reachableChordAngles(alpha, theta_d);
      EXPECT_LE(std::abs(limits.hi - reach.hi), 1e-11 * theta_d)
          << "alpha " << alpha << " theta_d " << theta_d << ": " << limits.hi << " vs " << reach.hi;
      EXPECT_LE(std::abs(limits.lo - reach.lo), 1e-11 * theta_d) << "alpha " << alpha;
    }
  }
  // 0 <= alpha <= 1: (0, theta_d); a circle: theta_d / 2.
  for (double alpha : {0.0, 0.5, 1.0}) {
    const ChordAngleRange limits = chordAngleLimits(alpha, 1.2);
    EXPECT_EQ(limits.lo, 0.0);
    EXPECT_EQ(limits.hi, 1.2);
  }
  const ChordAngleRange circle = chordAngleLimits(std::numeric_limits<double>::infinity(), 1.2);
  EXPECT_EQ(circle.lo, 0.6);
  EXPECT_EQ(circle.hi, 0.6);
  // the reachable range lies inside the limits (seeded sweep)
  std::mt19937 rng(4242);  // seed: fixed, so failures reproduce
  std::uniform_real_distribution<double> alpha_dist(-4.0, 4.0), turn(0.01, 3.1);
  for (int trial = 0; trial < 60; ++trial) {
    const double alpha = alpha_dist(rng), theta_d = turn(rng);
    const ChordAngleRange limits = chordAngleLimits(alpha, theta_d), reach = reachableChordAngles(alpha, theta_d);
    const double rounding = 1e-14 * theta_d;  // saturated alphas reach the limits to rounding at |m| = 30
    EXPECT_TRUE(limits.lo <= reach.lo + rounding && reach.lo < reach.hi && reach.hi <= limits.hi + rounding)
        << "alpha " << alpha << " theta_d " << theta_d << ": limits (" << limits.lo << ", " << limits.hi
        << "), reachable (" << reach.lo << ", " << reach.hi << ")";
  }
}

TEST(ThreePointSegment, RoundTripNearTheBranchPoint) {
  // Large curvature ratios put rho's branch point next to one end of the standard form:
  // there the solve evaluates E(m) by moment recurrences (p > -2) or log-base quadrature.
  // Truth: the segment the triangle was made from (LaSegment, arc-length quadrature).
  // Curvature ratios e^{+-2..6}, |alpha m| <= 14. The curve must reproduce the triangle;
  // m itself is checked where the triangle determines it: its chord angle carries
  // rounding ~1e-16 rad, i.e. ~1e-11 relative at theta_d = 1e-5, which near the
  // saturated end moves m by ~1e-5 whatever the solver does.
  std::mt19937 rng(777);  // seed: fixed, so failures reproduce
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double alphas[] = {-3.0, -1.5, -0.7, -0.2, 0.0, 0.25, 0.45, 0.8, 1.2, 2.0, 3.5};
  const double turns[] = {1e-5, 0.05, 0.8, 2.0, 3.0};
  double worst_gap = 0.0, worst_m = 0.0;
  for (int trial = 0; trial < 440; ++trial) {
    const double alpha = alphas[trial % 11], theta_d = turns[(trial / 11) % 5];
    const double magnitude = std::min(2.0 + 4.0 * unit(rng), 14.0 / std::max(std::abs(alpha), 1.0));
    const double log_ratio = (trial % 2 == 0 ? 1.0 : -1.0) * magnitude;  // log(kappa_end / kappa_start)
    const LaSegment probe(alpha, 1.0, Vec2::Zero(), 0.0, 1.0, std::exp(log_ratio));
    const double k0 = theta_d / probe.turning();
    const LaSegment seg(alpha, 1.0, Vec2(0.3, -0.2), 0.4, k0, k0 * std::exp(log_ratio));
    const Triangle t = triangleOf(seg);
    const SegmentSolve s = solveThreePointSegment(alpha, t.q0, t.q1, t.q2);
    const std::string what = "alpha " + std::to_string(alpha) + " theta_d " + std::to_string(theta_d) +
                             " log ratio " + std::to_string(log_ratio);
    ASSERT_TRUE(s.report.usable()) << what << ": " << s.report.message;
    const double chord = (t.q2 - t.q0).norm();
    const double gap = (s.segment->end(1e-15) - t.q2).norm() / chord;
    const double m_error = std::abs(s.shape + log_ratio);  // m = log(rho_end / rho_start)
    worst_gap = std::max(worst_gap, gap);
    if (theta_d >= 0.05) worst_m = std::max(worst_m, m_error);
    EXPECT_LE(gap, 1e-12) << what << ": end misses Q2 by " << gap << " of the chord";
    if (theta_d >= 0.05) {
      EXPECT_LE(m_error, 1e-8) << what << ": m " << s.shape << " vs " << -log_ratio;
    }
    EXPECT_LE(std::abs(wrapAngle(s.segment->theta(s.segment->length()) - seg.theta(seg.length()))), 1e-12) << what;
  }
  std::cout << "worst end gap " << worst_gap << ", worst m error " << worst_m << "\n";
}

}  // namespace
}  // namespace la
