// Stage 6, G2 by joint deformation (fitting/g2_joints.h, makeG2), both solvers: Newton
// over all joint angles and the paper's joint-by-joint bisection.
//
// Truth: chains of LA segments that are G2 by construction (core/la_segment.h: segment
// k + 1 starts where segment k ends, with its tangent angle and its end curvature). Their
// joints, tangent angles at the joints and alphas make a Chain (fitting/chain.h) whose
// G2 solution is that chain; the interior tangent angles are perturbed by a few degrees
// and makeG2 has to find them again. Checked from the returned segments by our own
// arithmetic: the relative curvature gap of DESIGN.md section 6 at every joint, the
// tangent and position continuity, the joints not moved, the angles and curvatures of
// the known chain.
//
// Failures: an S-shaped chain of two pieces turning opposite ways (no inflection piece)
// cannot be G2 for any tangent rotation (the curvatures at the joint have opposite signs
// and, for alpha = 2, are bounded away from 0); a triangle outside the chord angles that
// alpha = 2 reaches (limits in closed form here) has no LA segment at all.

#include "fitting/g2_joints.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "fitting/chain.h"
#include "tests/test_support.h"

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kG2Threshold = 1e-6;  // relative gap, DESIGN.md section 6 (G2Options default)
// How close a solution within the gap threshold lies to the known chain: a relative gap
// of 1e-6 leaves the angles ~1e-7 rad and the curvatures ~1e-6 relative off (measured:
// bisection 3e-7 rad and 6e-7 at worst, Newton 1e-9); a factor of about 10 to spare.
constexpr double kAngleTol = 3e-6, kKappaTol = 1e-5;

// The chain data of known segments: joints at the segment starts and the last end,
// tangent angles there (continuous, not wrapped), every piece a 3-point piece with the
// segment's alpha. A closed chain's last joint is its first (the angle 2 pi on).
Chain chainOf(const std::vector<LaSegment>& segments, bool closed) {
  Chain chain;
  chain.closed = closed;
  for (const LaSegment& s : segments) {
    chain.joints.push_back(s.start());
    chain.angles.push_back(s.theta0());
    chain.pieces.push_back({PieceKind::kThreePoint, s.alpha()});
  }
  const LaSegment& last = segments.back();
  chain.joints.push_back(closed ? segments.front().start() : last.end(1e-15));
  chain.angles.push_back(last.theta(last.length()));
  return chain;
}

// Rotates the tangents at the given joints by the given angles (closed chain: joint 0
// and its copy, the last joint, together).
void perturb(Chain& chain, const std::vector<std::size_t>& joints, const std::vector<double>& by) {
  for (std::size_t k = 0; k < joints.size(); ++k) {
    chain.angles[joints[k]] += by[k];
    if (chain.closed && joints[k] == 0) chain.angles.back() += by[k];
  }
}

double diagonalOf(const std::vector<LaSegment>& segments) {
  std::vector<Vec2> pts;
  for (const LaSegment& s : segments)
    for (const Vec2& p : s.sample(50).point) pts.push_back(p);
  return boundingBoxDiagonal(pts);
}

// Our own relative gap (DESIGN.md section 6).
double gapOf(double kl, double kr, double diagonal) {
  return std::abs(kl - kr) / std::max({std::abs(kl), std::abs(kr), 1.0 / diagonal});
}

// The returned curve is G2: positions and tangents continuous, relative curvature gap
// below the threshold at every joint (our arithmetic), its segments start and end on the
// chain's joints.
void expectG2(const G2Result& r, const Chain& chain, double diagonal) {
  ASSERT_EQ(r.segments.size(), chain.size());
  const std::size_t n = r.segments.size();
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const LaSegment& s = r.segments[i];
    EXPECT_LT((s.start() - chain.joints[i]).norm(), 1e-12 * diagonal) << "segment " << i << " start";
    EXPECT_LT((s.end(1e-14) - chain.joints[i + 1]).norm(), 1e-9 * s.length()) << "segment " << i << " end";
    if (i + 1 == n && !chain.closed) break;
    const LaSegment& next = r.segments[(i + 1) % n];
    EXPECT_LT(std::abs(wrapAngle(next.theta0() - s.theta(s.length()))), 1e-9) << "tangent at joint " << i + 1;
    const double g = gapOf(s.kappaEnd(), next.kappaStart(), diagonal);
    worst = std::max(worst, g);
    EXPECT_LE(g, kG2Threshold) << "joint " << (i + 1) % n << ": kappa " << s.kappaEnd() << " | " << next.kappaStart();
  }
  EXPECT_LE(r.max_gap, kG2Threshold);
  EXPECT_GE(r.max_gap, 0.5 * worst) << "reported max_gap " << r.max_gap << ", measured " << worst;
}

// The solution is the known chain: tangent angles at every joint and end curvatures.
void expectKnownChain(const G2Result& r, const Chain& chain, const std::vector<LaSegment>& truth,
                      double angle_tol, double kappa_tol) {
  ASSERT_EQ(r.segments.size(), truth.size());
  double worst_angle = 0.0, worst_kappa = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double da = std::abs(wrapAngle(chain.angles[i] - truth[i].theta0()));
    worst_angle = std::max(worst_angle, da);
    EXPECT_LT(da, angle_tol) << "angle at joint " << i << ": " << chain.angles[i] << " vs " << truth[i].theta0();
    EXPECT_LT(std::abs(wrapAngle(r.segments[i].theta0() - truth[i].theta0())), angle_tol) << "segment " << i;
    for (const auto& [got, want] : {std::pair{r.segments[i].kappaStart(), truth[i].kappaStart()},
                                    std::pair{r.segments[i].kappaEnd(), truth[i].kappaEnd()}}) {
      const double rel = test::relDiff(got, want);
      worst_kappa = std::max(worst_kappa, rel);
      EXPECT_LT(rel, kappa_tol) << "segment " << i << " kappa " << got << " vs " << want;
    }
  }
  std::printf("  angles within %.2g rad, curvatures within %.2g relative of the known chain\n", worst_angle, worst_kappa);
}

G2Options optionsFor(G2Method method, double diagonal) {
  G2Options o;
  o.method = method;
  o.diagonal = diagonal;
  return o;
}

// Every joint kept exactly where it was (bitwise: joints do not slide here).
void expectJointsUnmoved(const Chain& after, const Chain& before) {
  ASSERT_EQ(after.joints.size(), before.joints.size());
  for (std::size_t j = 0; j < after.joints.size(); ++j) {
    EXPECT_EQ(after.joints[j].x(), before.joints[j].x()) << "joint " << j;
    EXPECT_EQ(after.joints[j].y(), before.joints[j].y()) << "joint " << j;
  }
}

// ---------------------------------------------------------------------------------
// Open chains.

// Four left-turning segments with different laws (clothoid, alpha 2, 0.5, log spiral),
// curvature extrema at the joints, turning 0.6 to 1.2 rad each.
std::vector<LaSegment> openTruth() {
  return test::buildChain({10, -5}, 0.2, 0.01,
                          {{-1.0, 60.0, 0.03}, {2.0, 50.0, 0.012}, {0.5, 70.0, 0.025}, {1.0, 40.0, 0.008}});
}

class G2BothMethods : public ::testing::TestWithParam<G2Method> {};

// The interior tangent angles of the open chain turned by +4, -3, +5 degrees: G2 again,
// at the known chain's angles and curvatures (the end tangents are data and stay).
TEST_P(G2BothMethods, OpenChainReturnsToTheKnownG2Chain) {
  const std::vector<LaSegment> truth = openTruth();
  const double diag = diagonalOf(truth);
  Chain chain = chainOf(truth, false);
  perturb(chain, {1, 2, 3}, {4 * kDeg, -3 * kDeg, 5 * kDeg});
  const Chain before = chain;
  const G2Result r = makeG2(chain, optionsFor(GetParam(), diag));
  std::printf("open chain, %s: %s, %d iterations, max gap %.2g\n", toString(GetParam()), r.report.message.c_str(),
              r.report.iterations, r.max_gap);
  ASSERT_EQ(r.report.status, SolveStatus::kConverged) << r.report.message;
  expectG2(r, chain, diag);
  expectJointsUnmoved(chain, before);
  EXPECT_EQ(chain.angles.front(), before.angles.front());
  EXPECT_EQ(chain.angles.back(), before.angles.back());
  expectKnownChain(r, chain, truth, kAngleTol, kKappaTol);
  ASSERT_EQ(r.gaps.size(), 3u);  // one per interior joint
}

// The perturbed chain really had curvature gaps (so the test above can fail), and
// kOff leaves them: it only builds the pieces.
TEST(MakeG2, OffLeavesThePerturbedGapsOpen) {
  const std::vector<LaSegment> truth = openTruth();
  const double diag = diagonalOf(truth);
  Chain chain = chainOf(truth, false);
  perturb(chain, {1, 2, 3}, {4 * kDeg, -3 * kDeg, 5 * kDeg});
  const Chain before = chain;
  const G2Result r = makeG2(chain, optionsFor(G2Method::kOff, diag));
  ASSERT_EQ(r.segments.size(), 4u);
  for (std::size_t j = 0; j < chain.angles.size(); ++j) EXPECT_EQ(chain.angles[j], before.angles[j]);
  double worst = 0.0;
  for (std::size_t i = 0; i + 1 < r.segments.size(); ++i)
    worst = std::max(worst, gapOf(r.segments[i].kappaEnd(), r.segments[i + 1].kappaStart(), diag));
  std::printf("perturbed open chain: largest relative curvature gap %.3g\n", worst);
  EXPECT_GT(worst, 0.1);
  EXPECT_NEAR(r.max_gap, worst, 1e-9);
}

// The unperturbed chain data is G2 already: both solvers accept it at once, unchanged.
TEST_P(G2BothMethods, KnownG2ChainIsAFixedPoint) {
  const std::vector<LaSegment> truth = openTruth();
  const double diag = diagonalOf(truth);
  Chain chain = chainOf(truth, false);
  const G2Result r = makeG2(chain, optionsFor(GetParam(), diag));
  ASSERT_EQ(r.report.status, SolveStatus::kConverged) << r.report.message;
  EXPECT_EQ(r.report.iterations, 0);
  expectG2(r, chain, diag);
  expectKnownChain(r, chain, truth, 1e-9, 1e-7);
}

// An S-shaped chain: a segment ending in an inflection (alpha -1, kappa 0.02 -> 0), one
// starting in one (alpha -1.5, 0 -> -0.025), then a right-turning alpha 1.5 segment.
// Pieces 0 and 1 are inflection pieces (alpha solved: the segments carry it); their joint has no
// equation and keeps its angle; the joint between pieces 1 and 2 is perturbed by 4
// degrees and comes back, alphas with it.
TEST_P(G2BothMethods, ChainWithAnInflectionJointReturnsToTheKnownChain) {
  const std::vector<LaSegment> truth =
      test::buildChain({0, 0}, 0.3, 0.02, {{-1.0, 60.0, 0.0}, {-1.5, 50.0, -0.025}, {1.5, 45.0, -0.01}});
  const double diag = diagonalOf(truth);
  Chain chain = chainOf(truth, false);
  chain.pieces[0] = {PieceKind::kInflectionEnd, -3.0};    // alpha to be solved
  chain.pieces[1] = {PieceKind::kInflectionStart, -3.0};
  perturb(chain, {2}, {4 * kDeg});
  const Chain before = chain;
  const G2Result r = makeG2(chain, optionsFor(GetParam(), diag));
  ASSERT_EQ(r.report.status, SolveStatus::kConverged) << r.report.message;
  expectG2(r, chain, diag);
  expectJointsUnmoved(chain, before);
  EXPECT_EQ(chain.angles[1], before.angles[1]) << "the joint between two inflection ends keeps its angle";
  EXPECT_EQ(r.segments[0].kappaEnd(), 0.0);
  EXPECT_EQ(r.segments[1].kappaStart(), 0.0);
  expectKnownChain(r, chain, truth, kAngleTol, kKappaTol);
  EXPECT_NEAR(r.segments[0].alpha(), -1.0, 1e-4);
  EXPECT_NEAR(r.segments[1].alpha(), -1.5, 1e-4);
}

// Random open chains of five segments (std::mt19937, seeds 1..8): alpha in [-2, 3],
// |kappa| rising and falling by factors 1.5 to 3 in turn, 0.4 to 1.4 rad per segment, all
// turning one way; every interior tangent turned by up to 5 degrees (drawn again while a
// piece of the perturbed chain has no LA segment at the start, which makeG2 rightly
// refuses: see TriangleWithoutAnLaSegmentReportsInfeasible).
TEST_P(G2BothMethods, RandomOpenChainsReturnToTheKnownG2Chain) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto uni = [&](double a, double b) { return a + (b - a) * u(rng); };
    const double sign = u(rng) < 0.5 ? 1.0 : -1.0;
    double kappa = sign * uni(0.005, 0.02), theta = uni(-kPi, kPi);
    bool rising = u(rng) < 0.5;
    std::vector<LaSegment> truth;
    Vec2 start(uni(-50, 50), uni(-50, 50));
    for (int k = 0; k < 5; ++k, rising = !rising) {
      const double alpha = uni(-2.0, 3.0);
      const double kappa_end = rising ? kappa * uni(1.5, 3.0) : kappa / uni(1.5, 3.0);
      truth.push_back(LaSegment::withTurning(alpha, uni(0.4, 1.4), start, theta, kappa, kappa_end));
      start = truth.back().end(1e-15);
      theta = truth.back().theta(truth.back().length());
      kappa = kappa_end;
    }
    const double diag = diagonalOf(truth);
    Chain chain;
    for (int attempt = 0;; ++attempt) {
      ASSERT_LT(attempt, 100) << "no feasible perturbation";
      chain = chainOf(truth, false);
      perturb(chain, {1, 2, 3, 4}, {uni(-5, 5) * kDeg, uni(-5, 5) * kDeg, uni(-5, 5) * kDeg, uni(-5, 5) * kDeg});
      bool feasible = true;
      for (std::size_t i = 0; i < chain.size(); ++i) feasible = feasible && solvePiece(chain, i).report.usable();
      if (feasible) break;
    }
    const Chain before = chain;
    const G2Result r = makeG2(chain, optionsFor(GetParam(), diag));
    ASSERT_EQ(r.report.status, SolveStatus::kConverged) << r.report.message;
    expectG2(r, chain, diag);
    expectJointsUnmoved(chain, before);
    expectKnownChain(r, chain, truth, kAngleTol, kKappaTol);
  }
}

// ---------------------------------------------------------------------------------
// A closed chain.

// A closed G2 chain of four segments with point symmetry: segment 1 (alpha 0.5) turns
// 1.2 rad from kappa 0.05 to 0.012, segment 2 (alpha -1) turns pi - 1.2 from 0.012 back
// to 0.05, segments 3 and 4 are the first two turned by pi about the centre; the start is
// placed so that the half-turn closes (J2 = -J0 about the origin).
std::vector<LaSegment> closedTruth() {
  constexpr double kTheta0 = 0.4, kTurn = 1.2, kK1 = 0.05, kK2 = 0.012;
  const LaSegment a = LaSegment::withTurning(0.5, kTurn, Vec2::Zero(), kTheta0, kK1, kK2);
  const LaSegment b = LaSegment::withTurning(-1.0, kPi - kTurn, Vec2::Zero(), kTheta0 + kTurn, kK2, kK1);
  const Vec2 d1 = a.end(1e-15), d2 = b.end(1e-15);
  const Vec2 j0 = -0.5 * (d1 + d2);
  return {LaSegment(0.5, a.length(), j0, kTheta0, kK1, kK2), LaSegment(-1.0, b.length(), j0 + d1, kTheta0 + kTurn, kK2, kK1),
          LaSegment(0.5, a.length(), -j0, kTheta0 + kPi, kK1, kK2),
          LaSegment(-1.0, b.length(), -j0 - d1, kTheta0 + kPi + kTurn, kK2, kK1)};
}

TEST(MakeG2, ClosedTruthIsAClosedG2Chain) {
  const std::vector<LaSegment> truth = closedTruth();
  for (std::size_t i = 0; i < 4; ++i) {
    const LaSegment &s = truth[i], &next = truth[(i + 1) % 4];
    EXPECT_LT((s.end(1e-15) - next.start()).norm(), 1e-9) << i;
    EXPECT_LT(std::abs(wrapAngle(s.theta(s.length()) - next.theta0())), 1e-12) << i;
    EXPECT_EQ(s.kappaEnd(), next.kappaStart()) << i;
  }
  EXPECT_NEAR(truth[3].theta(truth[3].length()) - truth[0].theta0(), 2.0 * kPi, 1e-12);
}

// All four joint angles of the closed chain turned (joint 0 and its copy together) by
// +3, -4, +2, +5 degrees: G2 again at every joint, the seam included, and the known chain.
TEST_P(G2BothMethods, ClosedChainReturnsToTheKnownG2Chain) {
  const std::vector<LaSegment> truth = closedTruth();
  const double diag = diagonalOf(truth);
  Chain chain = chainOf(truth, true);
  ASSERT_EQ(chain.joints.size(), 5u);
  perturb(chain, {0, 1, 2, 3}, {3 * kDeg, -4 * kDeg, 2 * kDeg, 5 * kDeg});
  const Chain before = chain;
  const G2Result r = makeG2(chain, optionsFor(GetParam(), diag));
  std::printf("closed chain, %s: %s, %d iterations, max gap %.2g\n", toString(GetParam()), r.report.message.c_str(),
              r.report.iterations, r.max_gap);
  ASSERT_EQ(r.report.status, SolveStatus::kConverged) << r.report.message;
  expectG2(r, chain, diag);
  expectJointsUnmoved(chain, before);
  EXPECT_NEAR(chain.angles.back() - chain.angles.front(), 2.0 * kPi, 1e-12) << "joint 0 and its copy move together";
  ASSERT_EQ(r.gaps.size(), 4u);  // one per joint, the seam included
  expectKnownChain(r, chain, truth, kAngleTol, kKappaTol);
}

// ---------------------------------------------------------------------------------
// Failures.

// Joints (0,0), (10,0), (20,0), end tangents at +60 degrees: piece 0 must turn right
// and piece 1 left whatever the middle tangent, so the curvatures at the joint have
// opposite signs; with alpha = 2 neither can reach 0 (its limit shapes have zero radius
// at one end, not infinite), so no rotation makes the chain G2. Started from the circular
// arcs (middle tangent -60 degrees), both solvers must say so, not converge.
TEST_P(G2BothMethods, SChainWithoutInflectionPieceReportsFailure) {
  Chain chain;
  chain.joints = {{0, 0}, {10, 0}, {20, 0}};
  chain.angles = {60 * kDeg, -60 * kDeg, 60 * kDeg};
  chain.pieces = {{PieceKind::kThreePoint, 2.0}, {PieceKind::kThreePoint, 2.0}};
  const Chain before = chain;
  const G2Result r = makeG2(chain, optionsFor(GetParam(), 20.0));
  std::printf("S chain, %s: %s (%s), max gap %.3g\n", toString(GetParam()), toString(r.report.status),
              r.report.message.c_str(), r.max_gap);
  EXPECT_FALSE(r.report.usable());
  EXPECT_NE(r.report.status, SolveStatus::kConverged);
  expectJointsUnmoved(chain, before);
  if (!r.segments.empty()) {  // whatever it returns, it does not claim a G2 curve
    ASSERT_EQ(r.segments.size(), 2u);
    EXPECT_GT(gapOf(r.segments[0].kappaEnd(), r.segments[1].kappaStart(), 20.0), 0.5);
    EXPECT_GT(r.max_gap, 0.5);
  }
}

// Chord angles an alpha = 2 segment reaches at turning angle theta_d, in closed form:
// rho is linear in theta, and its limit shapes rho ~ theta and rho ~ theta_d - theta
// give E = integral rho e^{i theta}: integral theta e^{i theta} = e^{i theta}(1 - i theta).
std::pair<double, double> alpha2ChordLimits(double theta_d) {
  using C = std::complex<double>;
  const C i(0.0, 1.0);
  const C up = std::exp(i * theta_d) * (1.0 - i * theta_d) - 1.0;       // rho ~ theta
  const C flat = theta_d * (std::exp(i * theta_d) - 1.0) / i;           // rho ~ 1
  const C down = flat - up;                                             // rho ~ theta_d - theta
  return {std::arg(down), std::arg(up)};
}

// A chain whose first piece has no LA segment: alpha = 2, turning 90 degrees, chord
// angle 15 degrees, outside the reachable (29.7, 60.3) degrees. makeG2 reports
// kInfeasible with no segments, and leaves the chain as it was.
TEST_P(G2BothMethods, TriangleWithoutAnLaSegmentReportsInfeasible) {
  const auto [lo, hi] = alpha2ChordLimits(kPi / 2);
  ASSERT_NEAR(lo / kDeg, 29.7, 0.1);
  ASSERT_NEAR(hi / kDeg, 60.3, 0.1);
  const double phi = 15 * kDeg;
  ASSERT_LT(phi, lo);
  Chain chain;
  chain.joints = {{0, 0}, 10.0 * unitVector(phi), 10.0 * unitVector(phi) + Vec2(-5.0, 8.0)};
  chain.angles = {0.0, kPi / 2, kPi / 2 + 1.0};  // piece 1: chord at 122 degrees, between 90 and 147
  chain.pieces = {{PieceKind::kThreePoint, 2.0}, {PieceKind::kThreePoint, 2.0}};
  const Chain before = chain;
  const G2Result r = makeG2(chain, optionsFor(GetParam(), 20.0));
  EXPECT_EQ(r.report.status, SolveStatus::kInfeasible) << r.report.message;
  EXPECT_TRUE(r.segments.empty());
  expectJointsUnmoved(chain, before);
  for (std::size_t j = 0; j < chain.angles.size(); ++j) EXPECT_EQ(chain.angles[j], before.angles[j]);
  // The same triangle with a reachable chord angle (45 degrees) is fine: it is the chord
  // angle that fails, not the set-up.
  Chain ok = chain;
  ok.joints[1] = 10.0 * unitVector(45 * kDeg);
  ok.joints[2] = ok.joints[1] + Vec2(-5.0, 8.0);
  EXPECT_FALSE(makeG2(ok, optionsFor(G2Method::kOff, 20.0)).segments.empty());
}

INSTANTIATE_TEST_SUITE_P(Methods, G2BothMethods, ::testing::Values(G2Method::kNewton, G2Method::kBisection),
                         [](const ::testing::TestParamInfo<G2Method>& info) {
                           return std::string(info.param == G2Method::kNewton ? "Newton" : "Bisection");
                         });

}  // namespace
}  // namespace la
