#include "fitting/chain_polish.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/quadrature.h"

namespace la {
namespace {

// A segment with a zero-curvature end needs alpha < 0 (DESIGN.md section 2); the polish
// keeps it at most this (a steeper law than that is a straight line in all but name).
constexpr double kInflectionAlphaCap = -0.05;
// Alpha's range is widened by this where a segment starts on its edge, and the start
// kept this far inside the tanh map (atanh(1 - 1e-9) ~ 10.7: a finite unknown).
constexpr double kAlphaMargin = 1e-3;
constexpr double kTanhEdge = 1.0 - 1e-9;
// Chords per segment of the polyline the foot points are projected on.
constexpr int kFootSamplesPerSegment = 48;

// Where each unknown sits in the parameter vector (a normalized frame: the chain's start
// at the origin, lengths in units of the points' bounding-box diagonal).
struct Layout {
  std::size_t segments = 0;
  std::vector<double> alpha_lo, alpha_hi;  // per segment: alpha = lo + (hi - lo) (1 + tanh w) / 2
  bool fix_start = false;
  std::vector<int> kappa_index;   // per joint: index of log|kappa|, or -1 for a fixed zero
  std::vector<double> kappa_sign;
  int theta_index = 0, length_index = 0, alpha_index = 0, size = 0;
};

struct Foot {
  std::size_t segment = 0;
  double u = 0.0;  // fraction of the segment's length
};

// Panels of the fixed rule that carries a segment's end to the next segment's start
// while the optimizer runs (the final chain uses LaSegment's adaptive end instead).
constexpr int kEndPanels = 12;

// The end of a segment by a composite 4-point Gauss-Legendre rule: cheap and, for the
// optimizer, accurate enough; the adaptive rule can take milliseconds on the extreme
// curvature ratios a trial step may ask for.
Vec2 approximateEnd(const LaSegment& seg) {
  Vec2 p = seg.start();
  const double h = seg.length() / kEndPanels;
  for (int k = 0; k < kEndPanels; ++k)
    p += integrateFixed<4>([&](double t) { return Vec2(unitVector(seg.theta(t))); }, k * h, (k + 1) * h);
  return p;
}

// exact: segment ends by LaSegment::end (for the result), else approximateEnd.
bool buildChain(const double* x, const Layout& layout, std::vector<LaSegment>& out, bool exact = false) {
  out.clear();
  Vec2 start = layout.fix_start ? Vec2::Zero() : Vec2(x[0], x[1]);
  double theta = x[layout.theta_index];
  auto kappa = [&](std::size_t j) {
    return layout.kappa_index[j] < 0 ? 0.0 : layout.kappa_sign[j] * std::exp(x[layout.kappa_index[j]]);
  };
  for (std::size_t i = 0; i < layout.segments; ++i) {
    const double length = std::exp(x[layout.length_index + i]);
    const double alpha = layout.alpha_lo[i] + (layout.alpha_hi[i] - layout.alpha_lo[i]) * 0.5 *
                                                  (1.0 + std::tanh(x[layout.alpha_index + i]));
    if (!std::isfinite(length) || !std::isfinite(alpha)) return false;
    try {
      out.emplace_back(alpha, length, start, theta, kappa(i), kappa(i + 1));
    } catch (const std::invalid_argument&) {  // the step left the LA family (e.g. alpha through 0 at a zero end)
      return false;
    }
    start = exact ? out.back().end() : approximateEnd(out.back());
    theta = out.back().theta(length);
  }
  return true;
}

// Positions and unit normals of the chain at the feet. Points come in stroke order, so
// the feet mostly increase along each segment: positions are carried from one foot to
// the next by a 4-point Gauss-Legendre rule on (cos theta, sin theta), theta in closed
// form, instead of integrating from the segment's start every time.
void evaluateFeet(const std::vector<LaSegment>& chain, const std::vector<Foot>& feet, std::vector<Vec2>& position,
                  std::vector<Vec2>& normal) {
  position.resize(feet.size());
  normal.resize(feet.size());
  std::vector<std::vector<std::size_t>> order(chain.size());
  for (std::size_t k = 0; k < feet.size(); ++k) order[feet[k].segment].push_back(k);
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const LaSegment& seg = chain[i];
    auto& idx = order[i];
    std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return feet[a].u < feet[b].u; });
    Vec2 p = seg.start();
    double s_prev = 0.0;
    for (std::size_t k : idx) {
      const double s = std::clamp(feet[k].u, 0.0, 1.0) * seg.length();
      if (s > s_prev) p += integrateFixed<4>([&](double t) { return Vec2(unitVector(seg.theta(t))); }, s_prev, s);
      s_prev = s;
      position[k] = p;
      const double theta = seg.theta(s);
      normal[k] = Vec2(-std::sin(theta), std::cos(theta));
    }
  }
}

// The residuals of DESIGN: tangent distance inside, full offset at the two ends.
struct ChainResidual {
  const Layout& layout;
  const std::vector<Vec2>& points;
  const std::vector<Foot>& feet;

  bool operator()(double const* const* params, double* residual) const {
    std::vector<LaSegment> chain;
    if (!buildChain(params[0], layout, chain)) return false;
    std::vector<Vec2> position, normal;
    evaluateFeet(chain, feet, position, normal);
    const std::size_t m = points.size();
    for (std::size_t k = 0; k < m; ++k) residual[k] = normal[k].dot(position[k] - points[k]);
    // the ends: the component along the tangent too
    const Vec2 t0(normal[0].y(), -normal[0].x()), t1(normal[m - 1].y(), -normal[m - 1].x());
    residual[m] = t0.dot(position[0] - points[0]);
    residual[m + 1] = t1.dot(position[m - 1] - points[m - 1]);
    return true;
  }
};

// Nearest point of a dense polyline of the chain, for every point (the ends go to the
// chain's ends).
std::vector<Foot> projectFeet(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points) {
  struct Node {
    Vec2 p;
    std::size_t segment;
    double u;
  };
  std::vector<Node> nodes;
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const CurveSamples smp = chain[i].sample(kFootSamplesPerSegment + 1);
    for (std::size_t k = 0; k < smp.size(); ++k) nodes.push_back({smp.point[k], i, smp.s[k] / chain[i].length()});
  }
  std::vector<Foot> feet(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    double best = INFINITY;
    for (std::size_t e = 0; e + 1 < nodes.size(); ++e) {
      if (nodes[e].segment != nodes[e + 1].segment) continue;
      const Vec2 d = nodes[e + 1].p - nodes[e].p;
      const double len2 = d.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((points[k] - nodes[e].p).dot(d) / len2, 0.0, 1.0) : 0.0;
      const double dist = (nodes[e].p + t * d - points[k]).squaredNorm();
      if (dist < best) {
        best = dist;
        feet[k] = {nodes[e].segment, nodes[e].u + t * (nodes[e + 1].u - nodes[e].u)};
      }
    }
  }
  feet.front() = {0, 0.0};
  feet.back() = {chain.size() - 1, 1.0};
  return feet;
}

double rmsOf(const ChainResidual& f, const std::vector<double>& x) {
  std::vector<double> r(f.points.size() + 2);
  const double* params[] = {x.data()};
  if (!f(params, r.data())) return INFINITY;
  double sum = 0.0;
  for (double v : r) sum += v * v;
  return std::sqrt(sum / static_cast<double>(r.size()));
}

}  // namespace

PolishResult polishChain(const std::vector<LaSegment>& segments, const std::vector<Vec2>& all_points,
                         const PolishOptions& options) {
  PolishResult result;
  result.segments = segments;
  if (segments.empty() || all_points.size() < 3) {
    result.report = {SolveStatus::kBadInput, 0, INFINITY, "polish: no chain or too few points"};
    return result;
  }
  for (const LaSegment& s : segments)
    if (!std::isfinite(s.alpha()) || s.turnSign() == 0.0) {
      result.report = {SolveStatus::kBadInput, 0, INFINITY, "polish: the chain has a circular or straight segment"};
      return result;
    }
  // Normalized frame: the chain's start at the origin, unit bounding-box diagonal.
  const Vec2 origin = segments.front().start();
  const double scale = boundingBoxDiagonal(all_points);
  if (!(scale > 0.0)) {
    result.report = {SolveStatus::kBadInput, 0, INFINITY, "polish: the points have no extent"};
    return result;
  }
  std::vector<Vec2> points;
  const std::size_t take = std::min(all_points.size(), std::max<std::size_t>(options.max_points, 3));
  for (std::size_t k = 0; k < take; ++k)
    points.push_back((all_points[k * (all_points.size() - 1) / (take - 1)] - origin) / scale);

  const std::size_t n = segments.size();
  Layout layout;
  layout.segments = n;
  layout.fix_start = options.fix_start;
  std::vector<double> x;
  if (!layout.fix_start) x = {0.0, 0.0};
  layout.theta_index = static_cast<int>(x.size());
  x.push_back(segments.front().theta0());
  for (std::size_t j = 0; j <= n; ++j) {
    const double k = j < n ? segments[j].kappaStart() : segments[n - 1].kappaEnd();
    layout.kappa_sign.push_back(k < 0.0 ? -1.0 : 1.0);
    if (k == 0.0) {
      layout.kappa_index.push_back(-1);
    } else {
      layout.kappa_index.push_back(static_cast<int>(x.size()));
      x.push_back(std::log(std::abs(k) * scale));
    }
  }
  layout.length_index = static_cast<int>(x.size());
  for (const LaSegment& s : segments) x.push_back(std::log(s.length() / scale));
  // Alpha stays inside its range through a smooth map instead of bounds (bounds make
  // Ceres search along projected steps, each needing a new numeric Jacobian); the range
  // is widened a little where the start sits on its edge.
  layout.alpha_index = static_cast<int>(x.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double a = segments[i].alpha();
    const bool zero_end = layout.kappa_index[i] < 0 || layout.kappa_index[i + 1] < 0;
    const double lo = std::min(options.min_alpha, a) - kAlphaMargin;
    const double hi = zero_end ? (a < kInflectionAlphaCap ? kInflectionAlphaCap : 0.5 * a)
                               : std::max(options.max_alpha, a) + kAlphaMargin;
    layout.alpha_lo.push_back(lo);
    layout.alpha_hi.push_back(hi);
    x.push_back(std::atanh(std::clamp(2.0 * (a - lo) / (hi - lo) - 1.0, -kTanhEdge, kTanhEdge)));
  }
  layout.size = static_cast<int>(x.size());

  auto toWorld = [&](const std::vector<LaSegment>& chain) {
    std::vector<LaSegment> out;
    for (const LaSegment& s : chain)
      out.emplace_back(s.alpha(), s.length() * scale, origin + s.start() * scale, s.theta0(), s.kappaStart() / scale,
                       s.kappaEnd() / scale);
    return out;
  };

  std::vector<LaSegment> chain;
  if (!buildChain(x.data(), layout, chain)) {
    result.report = {SolveStatus::kBadInput, 0, INFINITY, "polish: the chain is not an LA chain"};
    return result;
  }
  std::vector<Foot> feet = projectFeet(chain, points);
  result.rms_before = rmsOf(ChainResidual{layout, points, feet}, x) * scale;
  int iterations = 0;
  for (int round = 0; round < options.rounds; ++round) {
    auto* cost =
        new ceres::DynamicNumericDiffCostFunction<ChainResidual, ceres::FORWARD>(new ChainResidual{layout, points, feet});
    cost->AddParameterBlock(layout.size);
    cost->SetNumResiduals(static_cast<int>(points.size()) + 2);
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, x.data());
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = options.max_iterations;
    solver.logging_type = ceres::SILENT;
    solver.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    iterations += static_cast<int>(summary.iterations.size());
    if (!buildChain(x.data(), layout, chain)) break;  // cannot happen: Ceres keeps the last feasible x
    feet = projectFeet(chain, points);
    if (summary.initial_cost - summary.final_cost <= 1e-6 * summary.initial_cost) break;  // no more to gain
  }
  result.rms_after = rmsOf(ChainResidual{layout, points, feet}, x) * scale;
  result.improved = result.rms_after < result.rms_before && buildChain(x.data(), layout, chain, true);
  if (result.improved) result.segments = toWorld(chain);
  result.report = {SolveStatus::kConverged, iterations, result.rms_after,
                   result.improved ? "polished" : "kept: the polish did not bring the chain closer"};
  return result;
}

}  // namespace la
