// Why the project's small shape solves iterate in core/least_squares.h and not in
// ceres::Solver: the same problem solved both ways, Levenberg-Marquardt with bounds and
// forward-difference derivatives in each. The problem is stage 5's shot segment
// (fitting/spline_chain.h, shootSegment): from a start point, tangent and curvature,
// the end curvature and alpha of the LA segment turning by a given angle whose end
// meets a target; two unknowns, a residual of two, each evaluation a segment solve.
// 30 cases: LA segments of alpha -2..2, turning 0.5..3 rad and end curvature 1/3 or 3
// times the start's, each started 0.3 off in alpha and 10% off in the end curvature.
//
//   build/tests/benchmarks/least_squares_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// Both must bring every end within 1e-9 of the segment's length of its target before
// they are timed (SkipWithError otherwise; `worst_miss` says how close each got, and
// `evaluations` how many segment solves a case took). Ceres stops, as the shared
// solver does, once the end is within 1e-12 of the length (an iteration callback; at
// its default tolerances it stops at about 1e-9).
// Measured (2 cores at 2.6 GHz, Release): the shared solver 24 us and 15 evaluations a
// case, Ceres 63 us and 35 evaluations (it evaluates the residual again with every
// Jacobian).

#include <benchmark/benchmark.h>
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/la_segment.h"
#include "core/least_squares.h"

namespace la {
namespace {

struct Case {
  double turning, kappa_start, kappa_end, start_kappa_end, start_alpha;
  Vec2 target;
  double length;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const double alpha : {-2.0, -1.0, -0.5, 0.5, 2.0})
    for (const double turning : {0.5, 1.5, 3.0})
      for (const double ratio : {1.0 / 3.0, 3.0}) {
        const LaSegment truth = LaSegment::withTurning(alpha, turning, Vec2(0, 0), 0.0, 1.0, ratio);
        out.push_back({turning, 1.0, ratio, 1.1 * ratio, alpha + 0.3, truth.end(), truth.length()});
      }
  return out;
}

// The residual for Ceres: (log |kappa_end|, alpha) -> end - target.
int evaluations = 0;  // (of EndMiss, counted before the timed loop)

struct EndMiss {
  const Case* c;
  bool operator()(const double* x, double* r) const {
    ++evaluations;
    try {
      const LaSegment s = LaSegment::withTurning(x[1], c->turning, Vec2(0, 0), 0.0, c->kappa_start, std::exp(x[0]));
      const Vec2 miss = s.end() - c->target;
      r[0] = miss.x();
      r[1] = miss.y();
      return true;
    } catch (const std::invalid_argument&) {
      return false;
    }
  }
};

double sharedSolve(const Case& c) {
  const EndMiss miss{&c};
  LeastSquaresProblem problem;
  problem.residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r.resize(2);
    return miss(x.data(), r.data());
  };
  problem.jacobian = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd& jacobian) {
    jacobian.resize(2, 2);
    for (int i = 0; i < 2; ++i) {  // forward differences, the step Ceres' NumericDiffCostFunction takes
      Eigen::VectorXd moved = x, r_moved(2);
      const double h = 1e-6 * std::max(std::abs(x[i]), 1.0);
      moved[i] += h;
      if (!miss(moved.data(), r_moved.data())) return false;
      jacobian.col(i) = (r_moved - r) / h;
    }
    return true;
  };
  LeastSquaresOptions options;
  options.max_iterations = 50;
  options.tolerance = 1e-12 * c.length;
  options.initial_damping = 1e-4;
  options.min_damping = 1e-12;
  options.max_damping = 1e14;
  options.lower = Eigen::Vector2d(-INFINITY, -3.0);
  options.upper = Eigen::Vector2d(INFINITY, 3.0);
  Eigen::VectorXd x = Eigen::Vector2d(std::log(c.start_kappa_end), c.start_alpha), r;
  solveLeastSquares(problem, x, r, options);
  double end[2];
  if (!miss(x.data(), end)) return INFINITY;
  return std::hypot(end[0], end[1]) / c.length;
}

double ceresSolve(const Case& c) {
  double x[2] = {std::log(c.start_kappa_end), c.start_alpha};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::NumericDiffCostFunction<EndMiss, ceres::FORWARD, 2, 2>(new EndMiss{&c}), nullptr, x);
  problem.SetParameterLowerBound(x, 1, -3.0);
  problem.SetParameterUpperBound(x, 1, 3.0);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 50;
  options.function_tolerance = options.parameter_tolerance = 1e-15;
  options.gradient_tolerance = 1e-20;
  options.logging_type = ceres::SILENT;
  // (stop, as the shared solver does, once the end is within 1e-12 of the length)
  struct Reached : ceres::IterationCallback {
    double cost;
    explicit Reached(double c) : cost(c) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
      return s.cost <= cost ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
    }
  } reached(0.5 * std::pow(1e-12 * c.length, 2));
  options.callbacks.push_back(&reached);
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  double r[2];
  if (!EndMiss{&c}(x, r)) return INFINITY;
  return std::hypot(r[0], r[1]) / c.length;
}

template <double (*Solve)(const Case&)>
void BM_ShotSegment(benchmark::State& state) {
  const std::vector<Case> all = cases();
  double worst = 0.0;
  evaluations = 0;
  for (const Case& c : all) worst = std::max(worst, Solve(c));
  state.counters["worst_miss"] = worst;
  state.counters["evaluations"] = static_cast<double>(evaluations) / static_cast<double>(all.size());
  if (!(worst <= 1e-9)) {
    state.SkipWithError("a shot segment misses its target");
    return;
  }
  for (auto _ : state)
    for (const Case& c : all) benchmark::DoNotOptimize(Solve(c));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * all.size()));
}
BENCHMARK(BM_ShotSegment<sharedSolve>)->Name("BM_ShotSegment/shared")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ShotSegment<ceresSolve>)->Name("BM_ShotSegment/ceres")->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace la
