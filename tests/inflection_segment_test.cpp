// Tests of the inflection-end LA segment (core/inflection_segment.h): segments built
// with known alpha < 0 and kappa = 0 at one end are read off as control triangles and
// solved back; the clothoid (alpha = -1) is checked against Fresnel integrals computed
// here by their power series. Random sweeps use std::mt19937 with the seed given.

#include "core/inflection_segment.h"

#include <gtest/gtest.h>

#include "tests/test_support.h"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <random>

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;

using test::Triangle;
using test::triangleOf;
using test::relDiff;

// Fresnel integrals int_0^x cos(t^2) dt and int_0^x sin(t^2) dt by their power series
// (alternating, fine for x <= 2 in long double).
void fresnel(double x, double& c, double& s) {
  long double sc = 0, ss = 0, term = x;  // term = (-1)^n x^(4n+1) / (2n)! for the cos part
  const long double x4 = static_cast<long double>(x) * x * x * x;
  for (int n = 0; n < 60; ++n) {
    // cos(t^2) = sum (-1)^n t^(4n) / (2n)!, integral -> x^(4n+1)/((4n+1)(2n)!)
    sc += term / (4 * n + 1);
    // sin(t^2) = sum (-1)^n t^(4n+2)/(2n+1)!, integral -> x^(4n+3)/((4n+3)(2n+1)!)
    ss += term * x * x / ((4 * n + 3) * (2.0L * n + 1));
    term *= -x4 / ((2.0L * n + 1) * (2.0L * n + 2));
  }
  c = static_cast<double>(sc);
  s = static_cast<double>(ss);
}

TEST(InflectionSegment, ClothoidAgainstFresnel) {
  // theta = s^2 (alpha = -1, q = 2): the end of the standard clothoid at s_d is
  // (C(s_d), S(s_d)) with C, S the Fresnel integrals of t^2.
  for (double theta_d : {0.1, 0.8, 1.6, 2.5}) {
    const double s_d = std::sqrt(theta_d);
    double c, s;
    fresnel(s_d, c, s);
    const Vec2 q0(0, 0), q2(c, s);
    const Vec2 t1 = unitVector(theta_d);
    const Vec2 q1(q2.x() - q2.y() / t1.y() * t1.x(), 0.0);  // end tangent meets the x axis
    const SegmentSolve r = solveInflectionSegment(q0, q1, q2, InflectionEnd::kStart);
    ASSERT_TRUE(r.report.usable()) << r.report.message;
    EXPECT_NEAR(r.shape, -1.0, 1e-9) << "theta_d " << theta_d;
    EXPECT_LE(relDiff(r.segment->length(), s_d), 1e-9) << "theta_d " << theta_d;
    EXPECT_LE(relDiff(r.segment->kappaEnd(), 2.0 * s_d), 1e-9) << "kappa = 2 s";
    EXPECT_EQ(r.segment->kappaStart(), 0.0);
  }
}

TEST(InflectionSegment, RoundTripBothEndsSeededSweep) {
  std::mt19937 rng(7);  // seed 7
  std::uniform_real_distribution<double> log_alpha(std::log(0.15), std::log(8.0)), unit(0, 1), angle(-kPi, kPi);
  int solved = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const double alpha = -std::exp(log_alpha(rng));
    const double scale = (trial % 3 == 0) ? 1e-3 : (trial % 3 == 1 ? 1.0 : 1e3);
    const double sign = (trial % 2 == 0) ? 1.0 : -1.0;
    const double kappa = sign * (0.5 + 2.0 * unit(rng)) / scale;
    const double length = scale * (0.2 + 1.2 * unit(rng));
    const Vec2 start(scale * angle(rng), scale * angle(rng));
    const bool at_end = (trial % 4) >= 2;
    const LaSegment seg = at_end ? LaSegment(alpha, length, start, angle(rng), kappa, 0.0)
                                 : LaSegment(alpha, length, start, angle(rng), 0.0, kappa);
    const double turn = std::abs(seg.turning());
    if (!(turn > 0.02 && turn < kPi - 0.05)) continue;
    const Triangle t = triangleOf(seg);
    const SegmentSolve r = solveInflectionSegment(t.q0, t.q1, t.q2, at_end ? InflectionEnd::kEnd : InflectionEnd::kStart);
    ASSERT_TRUE(r.report.usable()) << "trial " << trial << " alpha " << alpha << ": " << r.report.message;
    EXPECT_LE(relDiff(r.shape, alpha), 1e-9) << "trial " << trial << " alpha recovered " << r.shape << " vs " << alpha;
    EXPECT_LE(relDiff(r.segment->length(), length), 1e-9) << "trial " << trial;
    EXPECT_LE(relDiff(r.segment->kappaStart() + r.segment->kappaEnd(), kappa), 1e-9) << "trial " << trial;
    EXPECT_LE((r.segment->end(1e-14) - t.q2).norm(), 1e-10 * length) << "trial " << trial;
    EXPECT_EQ(at_end ? r.segment->kappaEnd() : r.segment->kappaStart(), 0.0);
    ++solved;
  }
  EXPECT_GT(solved, 80);
}

TEST(InflectionSegment, ChordAngleAtOrPastHalfTurnIsInfeasible) {
  // An inflection start means the curve bends late: chord angle < theta_d / 2.
  const double theta_d = 1.0;
  const ChordAngleRange range = reachableInflectionChordAngles(theta_d);
  EXPECT_GT(range.lo, 0.0);
  EXPECT_LT(range.hi, 0.5 * theta_d);
  EXPECT_GT(range.hi, 0.5 * theta_d - 1e-5);
  const Vec2 q0(0, 0), q1(1, 0), q2 = q1 + unitVector(theta_d);  // isosceles: chord = theta_d/2
  const SegmentSolve r = solveInflectionSegment(q0, q1, q2, InflectionEnd::kStart);
  EXPECT_EQ(r.report.status, SolveStatus::kInfeasible) << r.report.message;
  EXPECT_FALSE(r.segment.has_value());
  EXPECT_NE(r.report.message.find("reachable"), std::string::npos);
  // A short second leg (Q1 near Q2) bends late: an inflection fits at the start only.
  const Vec2 q2b = q1 + 0.3 * unitVector(theta_d);
  EXPECT_TRUE(solveInflectionSegment(q0, q1, q2b, InflectionEnd::kStart).report.usable());
  EXPECT_EQ(solveInflectionSegment(q0, q1, q2b, InflectionEnd::kEnd).report.status, SolveStatus::kInfeasible);
}

TEST(InflectionSegment, BadInput) {
  const Vec2 a(0, 0), b(1, 0);
  EXPECT_EQ(solveInflectionSegment(a, a, b, InflectionEnd::kStart).report.status, SolveStatus::kBadInput);
  EXPECT_EQ(solveInflectionSegment(a, b, Vec2(std::nan(""), 1), InflectionEnd::kEnd).report.status,
            SolveStatus::kBadInput);
  EXPECT_EQ(solveInflectionSegment(a, b, Vec2(0.5, 0), InflectionEnd::kStart).report.status, SolveStatus::kBadInput);
}

}  // namespace
}  // namespace la
