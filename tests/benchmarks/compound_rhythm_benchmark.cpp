// Speed of the compound-rhythm solve (core/compound_rhythm.h; STYLE.md convention 9).
//
// Run (median of 5 repetitions is the figure to compare):
//   ./tests/benchmarks/compound_rhythm_benchmark --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
// (one command line; from the build directory).
//
// Groups:
//   CompoundSolve/<alpha0>,<alpha1>/known_joint   solveCompoundRhythm over the control
//       polygons of 16 compound curves built directly (G3 by the seed's eqs. 10-11) with
//       log radius ratios +-0.4 / +-1 on the first piece and +-0.3 / +-1 on the second,
//       first piece length 0.6 or 1.2 start radii; Q1, Q2 halfway to the tangents'
//       intersection; joint direction the built curve's. Time per solve.
//   CompoundSolve/<alpha0>,<alpha1>/default_joint the same polygons with the default joint
//       direction (midpoints of Q0Q1 and Q2Q3), the reachable ones only.
//   CompoundVerify/<alpha0>,<alpha1>              only the final check inside the solve:
//       LaSegment::end of both pieces at the solve's accuracy (5e-14 of the length), to
//       show how much of a solve it is.
// Before timing, every polygon is solved once and must converge with its end on Q3
// (1e-12 of the chord), else the benchmark is an error (SkipWithError). No random data.

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/compound_rhythm.h"
#include "core/la_segment.h"

namespace la {
namespace {

struct Case {
  std::array<Vec2, 4> q;
  double joint_theta;
};

// The compound curve with start radius 1 at the origin heading +x: rho^alpha = c s + d
// per piece (log rho for alpha = 0), d rho/ds continuous at the joint.
std::optional<Case> buildCase(double alpha0, double alpha1, double m0, double s_c, double m1) {
  const double rho0 = 1.0, rho_c = std::exp(m0), rho1 = rho_c * std::exp(m1);
  const double rho_s = alpha0 != 0.0 ? (std::pow(rho_c, alpha0) - 1.0) / s_c * std::pow(rho_c, 1.0 - alpha0) / alpha0
                                     : m0 / s_c * rho_c;
  const double length1 = alpha1 != 0.0 ? (std::pow(rho1, alpha1) - std::pow(rho_c, alpha1)) /
                                             (alpha1 * rho_s * std::pow(rho_c, alpha1 - 1.0))
                                       : m1 / (rho_s / rho_c);
  const LaSegment p0(alpha0, s_c, Vec2::Zero(), 0.0, 1.0 / rho0, 1.0 / rho_c);
  const LaSegment p1(alpha1, length1, p0.end(1e-15), p0.theta(s_c), 1.0 / rho_c, 1.0 / rho1);
  const double turning = p0.turning() + p1.turning();
  if (!(turning < std::numbers::pi - 0.05 && p0.turning() > 0.05 && p1.turning() > 0.05)) return std::nullopt;
  const Vec2 a = p0.start(), b = p1.end(1e-15), ta = p0.tangent(0.0), tb = p1.tangent(length1);
  Eigen::Matrix2d m;
  m << ta.x(), tb.x(), ta.y(), tb.y();
  const Eigen::Vector2d ab = m.colPivHouseholderQr().solve(b - a);
  return Case{{a, a + 0.5 * ab.x() * ta, b - 0.5 * ab.y() * tb, b}, p0.theta(s_c)};
}

std::vector<Case> cases(double alpha0, double alpha1) {
  std::vector<Case> out;
  for (double m0 : {-1.0, -0.4, 0.4, 1.0})
    for (double s_c : {0.6, 1.2})
      for (double m1 : {0.3, 1.0})
        if (auto c = buildCase(alpha0, alpha1, m0, s_c, m0 > 0 ? m1 : -m1)) out.push_back(*c);
  return out;
}

constexpr double kEndTolerance = 1e-12;  // relative to the chord

void compoundSolve(benchmark::State& state, double alpha0, double alpha1, bool known_joint) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Case> usable;
  double iterations = 0;
  for (const Case& c : cases(alpha0, alpha1)) {
    const CompoundRhythmSolve s = solveCompoundRhythm(alpha0, alpha1, c.q, known_joint ? c.joint_theta : nan);
    if (!s.report.usable()) {
      if (known_joint) {
        state.SkipWithError(("a built curve's polygon was not solved: " + s.report.message).c_str());
        return;
      }
      continue;  // the default joint direction need not be reachable
    }
    const Vec2 end = s.curve->pieces[1].segment.end(1e-14);
    if (!((end - c.q[3]).norm() <= kEndTolerance * (c.q[3] - c.q[0]).norm())) {
      state.SkipWithError("the solved curve misses Q3");
      return;
    }
    iterations += s.report.iterations;
    usable.push_back(c);
  }
  if (usable.empty()) {
    state.SkipWithError("no polygon to solve");
    return;
  }
  std::size_t k = 0;
  for (auto _ : state) {
    const Case& c = usable[k];
    k = (k + 1) % usable.size();
    benchmark::DoNotOptimize(solveCompoundRhythm(alpha0, alpha1, c.q, known_joint ? c.joint_theta : nan));
  }
  state.counters["polygons"] = static_cast<double>(usable.size());
  state.counters["mean_iterations"] = iterations / usable.size();
}

void compoundVerify(benchmark::State& state, double alpha0, double alpha1) {
  std::vector<Curve> curves;
  for (const Case& c : cases(alpha0, alpha1)) {
    const CompoundRhythmSolve s = solveCompoundRhythm(alpha0, alpha1, c.q, c.joint_theta);
    if (!s.report.usable()) {
      state.SkipWithError(s.report.message.c_str());
      return;
    }
    curves.push_back(*s.curve);
  }
  std::size_t k = 0;
  for (auto _ : state) {
    const Curve& c = curves[k];
    k = (k + 1) % curves.size();
    benchmark::DoNotOptimize(c.pieces[0].segment.end(5e-14));
    benchmark::DoNotOptimize(c.pieces[1].segment.end(5e-14));
  }
}

const std::array<std::array<double, 2>, 5> kAlphaPairs = {{{0.1, -0.1}, {-1.0, 2.0}, {2.0, -1.0}, {0.0, 1.0}, {-0.5, -2.0}}};

const bool kRegistered = [] {
  for (const auto& pair : kAlphaPairs) {
    const std::string name = std::to_string(pair[0]).substr(0, 4) + "," + std::to_string(pair[1]).substr(0, 4);
    benchmark::RegisterBenchmark(("CompoundSolve/" + name + "/known_joint").c_str(), compoundSolve, pair[0], pair[1], true);
    benchmark::RegisterBenchmark(("CompoundSolve/" + name + "/default_joint").c_str(), compoundSolve, pair[0], pair[1],
                                 false);
    benchmark::RegisterBenchmark(("CompoundVerify/" + name).c_str(), compoundVerify, pair[0], pair[1]);
  }
  return true;
}();

}  // namespace
}  // namespace la
