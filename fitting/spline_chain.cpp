#include "fitting/spline_chain.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>

#include "core/least_squares.h"
#include "fitting/chain_fit.h"
#include "fitting/paper_stages.h"

namespace la {
namespace {

// The chain stage 7 starts from where stages 5-6 found none (a piece whose tangents form
// no control triangle, a joint no tangent angle makes G2): read off the spline in
// intrinsic form. A piece turning against both its neighbours (between two inflections)
// is cut at its largest curvature first (`spans` is updated). Each piece turns as the
// spline does between its splits; a joint's curvature is 0 where the turning direction
// changes (an inflection), else the spline's (a small value of the piece's sign where the
// spline's has the other) to start with, then adjusted as each segment is shot towards
// the next split point (below). G2 by construction; empty if some piece has no LA
// segment. `length`: the spline's length between each piece's splits.
std::vector<LaSegment> shotChain(const CubicBSpline& spline, std::vector<PieceReport>& spans, bool closed,
                                 double min_alpha, double max_alpha, const Budget& budget,
                                 std::vector<double>& length, const std::optional<ChainStart>& from) {
  constexpr int kSteps = 16;           // per piece, for its turning and length
  constexpr double kSmallKappa = 0.3;  // of the piece's mean curvature, where the spline's has the wrong sign
  auto measure = [&](double t0, double t1, double& turning, double& length) {
    double prev = splineTangentAngle(spline, spline.wrap(t0));
    Vec2 p = spline.point(spline.wrap(t0));
    turning = length = 0.0;
    for (int k = 1; k <= kSteps; ++k) {
      const double t = spline.wrap(t0 + (t1 - t0) * k / kSteps);
      const double a = splineTangentAngle(spline, t);
      turning += wrapAngle(a - prev);
      prev = a;
      const Vec2 q = spline.point(t);
      length += (q - p).norm();
      p = q;
    }
  };
  auto sign = [](double v) { return v < 0.0 ? -1.0 : 1.0; };
  std::vector<double> turning;
  for (bool again = true; again;) {
    again = false;
    const std::size_t n = spans.size();
    turning.assign(n, 0.0);
    length.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) measure(spans[i].t0, spans[i].t1, turning[i], length[i]);
    for (std::size_t i = 0; i < n; ++i) {
      // (a chain that goes on from zero curvature starts at an inflection)
      const bool zero_start = i == 0 && from && from->kappa == 0.0;
      const bool has_before = closed || i > 0 || zero_start, has_after = closed || i + 1 < n;
      if (!has_before || !has_after || (n < 3 && !zero_start)) continue;
      const double s = sign(turning[i]);
      if ((!zero_start && sign(turning[(i + n - 1) % n]) == s) || sign(turning[(i + 1) % n]) == s) continue;
      double best_t = 0.5 * (spans[i].t0 + spans[i].t1), best = 0.0;
      for (int k = 1; k < kSteps; ++k) {
        const double t = spans[i].t0 + (spans[i].t1 - spans[i].t0) * k / kSteps;
        const double kappa = std::abs(spline.curvature(spline.wrap(t)));
        if (kappa > best) best = kappa, best_t = t;
      }
      PieceReport second = spans[i];
      spans[i].t1 = second.t0 = best_t;
      spans[i].end_kind = second.start_kind = SplitKind::kExtremum;
      spans.insert(spans.begin() + static_cast<std::ptrdiff_t>(i) + 1, second);
      again = true;
      break;
    }
  }
  const std::size_t n = spans.size(), joints = closed ? n : n + 1;
  std::vector<double> kappa(joints, 0.0);
  for (std::size_t j = 0; j < joints; ++j) {
    const bool has_before = closed || j > 0, has_after = closed || j < n;
    const std::size_t before = (j + n - 1) % n, after = j % n;
    if (has_before && has_after && sign(turning[before]) != sign(turning[after])) continue;  // inflection: 0
    const std::size_t piece = has_after ? after : before;
    const double s = sign(turning[piece]);
    const double k = spline.curvature(spline.wrap(has_after ? spans[after].t0 : spans[before].t1));
    const double mean = std::abs(turning[piece]) / std::max(length[piece], 1e-300);
    kappa[j] = sign(k) == s && std::abs(k) > kSmallKappa * mean ? k : s * kSmallKappa * mean;
  }
  // Shoot segment by segment: each starts where the previous ended (tangent and
  // curvature continuous), turns as the spline does between its splits, and takes the
  // end curvature and alpha that bring its end closest to the next split point (Gauss-
  // Newton on two unknowns, one at an inflection joint, numeric derivatives): the chain
  // then follows the spline's joints instead of drifting with its curvature errors.
  if (from) kappa[0] = from->kappa;
  // The chain with `turns`, and the largest miss of its segments' ends from their split
  // points (none where some segment has no LA shot).
  struct Shot {
    std::vector<LaSegment> chain;
    double miss = INFINITY;
  };
  auto shoot = [&](const std::vector<double>& turns) {
    Shot shot{{}, 0.0};
    Vec2 start = from ? from->point : spline.point(spline.wrap(spans.front().t0));
    double theta = from ? from->theta : splineTangentAngle(spline, spline.wrap(spans.front().t0));
    for (std::size_t i = 0; i < n; ++i) {
      // (out of time: no chain; a hostile stroke's shots, each end of a segment with a cusp
      // placed to 1e-10 of its length, took seconds past the budget)
      if (budget.spent()) return Shot{};
      const double k0 = i == 0 ? kappa[0] : shot.chain.back().kappaEnd();
      const bool free_end = kappa[(i + 1) % joints] != 0.0;
      const double end_sign = sign(turns[i]);
      const Vec2 target = spline.point(spline.wrap(spans[i].t1));
      const bool zero_end = k0 == 0.0 || !free_end;
      const double hi = zero_end ? std::min(kInflectionAlphaCap, max_alpha) : max_alpha, lo = std::min(min_alpha, hi);
      const double k1 = free_end ? kappa[(i + 1) % joints] : 0.0;
      const auto seg = shootSegment(turns[i], start, theta, k0, free_end ? std::copysign(std::abs(k1), end_sign) : 0.0,
                                    zero_end ? -1.0 : kStage7StartAlpha, lo, hi, target);
      if (!seg) return Shot{};
      shot.chain.push_back(*seg);
      start = seg->end();
      theta = seg->theta(seg->length());
      shot.miss = std::max(shot.miss, (start - target).norm());
    }
    return shot;
  };
  Shot shot = shoot(turning);
  // A held start's tangent off the spline's: every segment turning as the spline does,
  // the whole chain is turned by that angle, and its shots curl back towards the split
  // points (walked strokes' pieces looped hundreds of pixels off). The first segment
  // taking up the turn onto the spline's tangent is tried too (not where it would turn
  // it against its start's curvature); the chain whose segments end nearer their split
  // points is kept (a large turn can be too much for one segment to take up).
  if (from) {
    std::vector<double> turned = turning;
    turned[0] += wrapAngle(splineTangentAngle(spline, spline.wrap(spans.front().t0)) - from->theta);
    if (turned[0] != turning[0] && sign(turned[0]) == sign(turning[0]) &&
        (from->kappa == 0.0 || sign(from->kappa) == sign(turned[0]))) {
      Shot other = shoot(turned);
      if (other.miss < shot.miss) shot = std::move(other);
    }
  }
  return shot.chain;
}

}  // namespace

std::optional<LaSegment> shootSegment(double turning, const Vec2& start, double theta0, double kappa_start,
                                      double kappa_end, double alpha, double min_alpha, double max_alpha,
                                      const Vec2& target) {
  // Unknowns x: y = log|kappa_end| where the end is no inflection, and alpha. Gauss-
  // Newton steps (core/least_squares.h), damped a little, each unknown's by at most 1,
  // on the miss of the end point with numeric derivatives; it stops at the first step
  // that does not bring the end closer.
  const bool free_end = kappa_end != 0.0;
  const double end_sign = kappa_end < 0.0 ? -1.0 : 1.0;
  auto build = [&](const Eigen::VectorXd& x) -> std::optional<LaSegment> {
    try {
      return LaSegment::withTurning(x[x.size() - 1], turning, start, theta0, kappa_start,
                                    free_end ? end_sign * std::exp(x[0]) : 0.0);
    } catch (const std::invalid_argument&) {
      return std::nullopt;
    }
  };
  constexpr double kStep = 1e-4;  // (of the numeric derivatives)
  LeastSquaresProblem problem;
  problem.residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    const auto seg = build(x);
    if (seg) r = seg->end() - target;
    return seg.has_value();
  };
  problem.jacobian = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd& jac) {
    jac.resize(2, x.size());
    Eigen::VectorXd moved = x, r_moved;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      moved[i] = x[i] + kStep;
      if (!problem.residual(moved, r_moved)) return false;
      jac.col(i) = (r_moved - r) / kStep;
      moved[i] = x[i];
    }
    return true;
  };
  LeastSquaresOptions options;
  options.max_iterations = 8;
  options.initial_damping = options.min_damping = options.max_damping = 1e-9;
  options.damping_floor = 1.0;
  options.max_step = Eigen::VectorXd::Ones(free_end ? 2 : 1);
  options.clamp_step = true;
  options.lower = Eigen::Vector2d(-INFINITY, min_alpha).tail(free_end ? 2 : 1);
  options.upper = Eigen::Vector2d(INFINITY, max_alpha).tail(free_end ? 2 : 1);
  Eigen::VectorXd x = Eigen::Vector2d(free_end ? std::log(std::abs(kappa_end)) : 0.0, alpha).tail(free_end ? 2 : 1), r;
  solveLeastSquares(problem, x, r, options);
  return build(x);
}

// shotChain; with `halve`, where a shot segment is far longer or shorter than the
// spline between its splits, it has set off away from the points (its start curvature,
// the previous one's end, does not suit it): its span is halved (at an inflection
// inside if any) and the chain shot again, at most kMaxHalvings times.
std::vector<LaSegment> chainFromSpline(const CubicBSpline& spline, std::vector<PieceReport>& spans, bool closed,
                                       double min_alpha, double max_alpha, bool halve,
                                       const Budget& budget, const std::optional<ChainStart>& from) {
  constexpr double kShotLengthRatio = 2.0;
  constexpr int kMaxHalvings = 6;
  for (int halvings = 0;; ++halvings) {
    std::vector<double> length;
    const std::vector<LaSegment> chain = shotChain(spline, spans, closed, min_alpha, max_alpha, budget, length, from);
    const std::size_t n = chain.size();
    std::size_t astray = n;
    for (std::size_t i = 0; i < n && astray == n; ++i)
      if (!(chain[i].length() < kShotLengthRatio * length[i] && kShotLengthRatio * chain[i].length() > length[i])) astray = i;
    if (!halve || astray == n || halvings >= kMaxHalvings || budget.spent()) return chain;
    const double t0 = spans[astray].t0, t1 = spans[astray].t1;
    double t = halvingPoint(spline, t0, t1).t;
    if (t < t0) t += spline.tMax() - spline.tMin();  // (wrapped past a closed spline's seam)
    if (!(t > t0 && t < t1)) return chain;
    PieceReport second = spans[astray];
    spans[astray].t1 = second.t0 = t;
    spans[astray].end_kind = second.start_kind = SplitKind::kTurning;
    spans.insert(spans.begin() + static_cast<std::ptrdiff_t>(astray) + 1, second);
  }
}


}  // namespace la
