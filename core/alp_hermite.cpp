#include "core/alp_hermite.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "core/least_squares.h"
#include "core/quadrature.h"

namespace la {
namespace {

// Largest degree accepted: binomials and de Casteljau stay exact enough far beyond,
// but a curvature function of degree 40 is already more than a designer can steer.
constexpr int kMaxDegree = 40;
// Solver quadrature: 16-point Gauss-Legendre panels with at most this turning each
// (bounded by max |k_i| per panel, the convex hull property). The rule's error for
// cos theta over 2 rad is ~2^32/32! ~ 1e-26 relative.
constexpr int kNodesPerPanel = 16;
constexpr double kMaxPanelTurning = 2.0;
constexpr int kMaxPanels = 256;  // 512 rad of turning: far beyond a design curve
// Starting points (log L as a multiple of the circular arc's length, u): the first
// is the arc itself (for G2, the arc's length with the end curvatures given), the
// others catch solutions that are longer or shorter, or turn more at one end; u = 2
// is a difference of about 2 rad in the turning rates of the two ends.
struct StartPoint {
  double length_factor, u;
};
constexpr StartPoint kStarts[] = {{1.0, 0.0}, {1.6, 0.0}, {0.8, 0.0}, {1.0, 2.0}, {1.0, -2.0}, {3.0, 0.0}, {6.0, 0.0}};
// Levenberg-Marquardt damping bounds: beyond kMaxDamping no step reduces |F|, a
// local minimum that is not a solution.
constexpr double kInitialDamping = 1e-4;
constexpr double kMinDamping = 1e-12;
constexpr double kMaxDamping = 1e14;
// log L stays in [log 1e-3, log 1e3] of the chord: no designer's curve is 1000 chords long.
constexpr double kMinLogLength = -6.9, kMaxLogLength = 6.9;
// The curve built in the user's frame must meet the end point to this many times
// the requested tolerance (its own adaptive evaluation against the solver's fixed
// rule), else the solver's grid is refined and the solve resumed.
constexpr double kVerifyFactor = 10.0;
constexpr double kVerifyFloor = 1e-11;
constexpr int kMaxGridRefinements = 4;
// Accuracy of the turning coefficients mu_i (which sum to 1): 10-point sums round to
// ~1e-16, so a tighter tolerance would only split panels to the limit.
constexpr double kMuTolerance = 1e-14;

// All B_i^n(t), i = 0..n.
void bernsteinBasis(int n, double t, double* b) {
  const double u = 1.0 - t;
  b[0] = 1.0;
  for (int j = 1; j <= n; ++j) {
    b[j] = t * b[j - 1];
    for (int i = j - 1; i >= 1; --i) b[i] = u * b[i] + t * b[i - 1];
    b[0] *= u;
  }
}

// The problem in the normalized frame.
struct Problem {
  int n = 3;
  std::vector<double> weights;  // empty: polynomial
  Vec2 end{1.0, 0.0};           // normalized end point (|end| = 1)
  double theta_d = 0.0;
  Eigen::VectorXd mu, c0, c1, c2;  // k(L, u) = c0 + L c1 + u c2
};

// w_i B_i^n / sum_j w_j B_j^n at t (the rational turning basis), into g.
void rationalBasis(const Problem& pr, double t, Eigen::VectorXd& g) {
  g.resize(pr.n + 1);
  bernsteinBasis(pr.n, t, g.data());
  double d = 0.0;
  for (int i = 0; i <= pr.n; ++i) d += (g[i] *= pr.weights[i]);
  g /= d;
}

// theta at the quadrature nodes is Phi k; the three products Phi c0, c1, c2 are all
// a solve needs (theta = phi0 + L phi1 + u phi2).
class Evaluator {
 public:
  explicit Evaluator(const Problem& pr) : pr_(pr) {}

  int panels() const { return panels_; }

  // (Re)builds the node tables for `panels` panels.
  void build(int panels) {
    panels_ = panels;
    const auto& rule = gaussLegendre<kNodesPerPanel>();
    const int n = pr_.n, count = panels * kNodesPerPanel;
    Eigen::MatrixXd phi(count, n + 1);
    weight_.resize(count);
    std::vector<double> b(n + 2);
    Eigen::VectorXd cumulative = Eigen::VectorXd::Zero(n + 1), g;
    for (int p = 0; p < panels; ++p) {
      const double a = double(p) / panels, h = 1.0 / panels;
      for (int k = 0; k < kNodesPerPanel; ++k) {
        const int row = p * kNodesPerPanel + k;
        const double t = a + h * rule.node[k];
        weight_[row] = h * rule.weight[k];
        if (pr_.weights.empty()) {
          // integral_0^t B_i^n = (1/(n+1)) sum_{j > i} B_j^{n+1}(t)
          bernsteinBasis(n + 1, t, b.data());
          double suffix = 0.0;
          for (int i = n; i >= 0; --i) {
            suffix += b[i + 1];
            phi(row, i) = suffix / (n + 1);
          }
        } else {
          // cumulative at the panel start plus the rule on [a, t]
          Eigen::VectorXd part = Eigen::VectorXd::Zero(n + 1);
          for (int j = 0; j < kNodesPerPanel; ++j) {
            rationalBasis(pr_, a + (t - a) * rule.node[j], g);
            part += rule.weight[j] * g;
          }
          phi.row(row) = (cumulative + (t - a) * part).transpose();
        }
      }
      if (!pr_.weights.empty()) {
        Eigen::VectorXd part = Eigen::VectorXd::Zero(n + 1);
        for (int j = 0; j < kNodesPerPanel; ++j) {
          rationalBasis(pr_, a + h * rule.node[j], g);
          part += rule.weight[j] * g;
        }
        cumulative += h * part;
      }
    }
    phi0_ = phi * pr_.c0;
    phi1_ = phi * pr_.c1;
    phi2_ = phi * pr_.c2;
  }

  // The largest |k_i| at (L, u): bounds the turning per unit tau.
  double maxRate(double L, double u) const { return (pr_.c0 + L * pr_.c1 + u * pr_.c2).cwiseAbs().maxCoeff(); }

  // F = L D - end and its Jacobian in (log L, u).
  void evaluate(double log_l, double u, Eigen::Vector2d& F, Eigen::Matrix2d* J) const {
    const double L = std::exp(log_l);
    Eigen::Vector2d D = Eigen::Vector2d::Zero(), dDL = D, dDu = D;
    for (Eigen::Index k = 0; k < weight_.size(); ++k) {
      const double th = phi0_[k] + L * phi1_[k] + u * phi2_[k];
      const double c = std::cos(th), s = std::sin(th), w = weight_[k];
      D += w * Eigen::Vector2d(c, s);
      if (J) {
        const Eigen::Vector2d normal(-s, c);
        dDL += (w * phi1_[k]) * normal;
        dDu += (w * phi2_[k]) * normal;
      }
    }
    F = L * D - pr_.end;
    if (J) {
      J->col(0) = L * (D + L * dDL);
      J->col(1) = L * dDu;
    }
  }

 private:
  const Problem& pr_;
  int panels_ = 0;
  Eigen::VectorXd weight_, phi0_, phi1_, phi2_;
};

struct Attempt {
  double log_l = 0.0, u = 0.0;
  double residual = INFINITY;
  int iterations = 0;
  bool converged = false;
  bool out_of_iterations = false;
  bool grid_exhausted = false;
};

// Levenberg-Marquardt (core/least_squares.h) from (log_l, u) on the evaluator's grid,
// refining the grid when the turning per panel grows past kMaxPanelTurning; a step
// changes L by at most a factor e.
Attempt levenbergMarquardt(Evaluator& ev, double log_l, double u, double tol, int max_iterations) {
  Attempt at;
  at.log_l = log_l;
  at.u = u;
  auto fitGrid = [&](double ll, double uu) {
    const double rate = ev.maxRate(std::exp(ll), uu);
    int p = ev.panels();
    while (rate / p > kMaxPanelTurning && p < kMaxPanels) p *= 2;
    if (rate / p > kMaxPanelTurning) return false;
    if (p != ev.panels()) ev.build(p);
    return true;
  };
  if (!fitGrid(log_l, u)) {
    at.grid_exhausted = true;
    return at;
  }
  LeastSquaresProblem problem;
  problem.residual = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    if (!fitGrid(x[0], x[1])) return false;
    Eigen::Vector2d f;
    ev.evaluate(x[0], x[1], f, nullptr);
    r = f;
    return true;
  };
  problem.jacobian = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd& jacobian) {
    Eigen::Vector2d f;
    Eigen::Matrix2d j;
    ev.evaluate(x[0], x[1], f, &j);
    r = f;
    jacobian = j;
    return true;
  };
  LeastSquaresOptions options;
  options.max_iterations = max_iterations;
  options.tolerance = tol;
  options.initial_damping = kInitialDamping;
  options.min_damping = kMinDamping;
  options.max_damping = kMaxDamping;
  options.max_step = Eigen::Vector2d(1.0, INFINITY);
  options.lower = Eigen::Vector2d(kMinLogLength, -INFINITY);
  options.upper = Eigen::Vector2d(kMaxLogLength, INFINITY);
  Eigen::VectorXd x = Eigen::Vector2d(log_l, u), r;
  const LeastSquaresSummary summary = solveLeastSquares(problem, x, r, options);
  at.log_l = x[0];
  at.u = x[1];
  at.residual = summary.final_cost;
  at.iterations = summary.successful_steps;
  at.converged = summary.end == LeastSquaresEnd::kConverged;
  at.out_of_iterations = summary.end == LeastSquaresEnd::kIterationLimit;
  return at;
}

SolveReport badInput(const std::string& why) {
  SolveReport r;
  r.status = SolveStatus::kBadInput;
  r.message = why;
  return r;
}

bool finite(const HermiteEnd& e) { return allFinite(e.point) && std::isfinite(e.theta) && std::isfinite(e.kappa); }

std::string fmt(double v) {
  std::ostringstream o;
  o.precision(3);
  o << v;
  return o.str();
}

}  // namespace

std::vector<double> alpInterpolate(double p_s, double p_e, int l, double p) {
  std::vector<double> out(std::max(l, 0));
  for (int i = 0; i < l; ++i) {
    const double v = double(i + 1) / (l + 1) * (p_e - p_s) + p_s;
    out[i] = p >= 0.0 ? p * (p_e - v) + v : p * (v - p_s) + v;
  }
  return out;
}

std::vector<double> alpWeights(const AlpShape& shape) {
  if (!shape.rational) return {};
  std::vector<double> w{1.0};
  for (double v : alpInterpolate(1.0, shape.w_e, shape.degree - 1, shape.p_w)) w.push_back(v);
  w.push_back(shape.w_e);
  return w;
}

AlpCurvatureCheck checkCurvature(const AlpCurve& curve) {
  AlpCurvatureCheck check;
  const double L = curve.length();
  for (double t : bernsteinSignChanges(curve.curvatureNumerator())) check.inflections.push_back(t * L);
  for (double t : bernsteinSignChanges(curve.curvatureDerivativeNumerator())) check.extrema.push_back(t * L);
  check.has_inflection = !check.inflections.empty();
  check.monotone = check.extrema.empty();
  return check;
}

AlpSolve solveAlpHermite(const HermiteEnd& start, const HermiteEnd& end, int continuity, const AlpShape& shape,
                         const AlpOptions& options) {
  AlpSolve out;
  const int n = shape.degree;
  if (!finite(start) || !finite(end)) {
    // G1 ignores the curvatures, so only they may be NaN there
    const bool g1_ok = continuity == 1 && allFinite(start.point) && allFinite(end.point) &&
                       std::isfinite(start.theta) && std::isfinite(end.theta);
    if (!g1_ok) {
      out.report = badInput("end conditions are not finite");
      return out;
    }
  }
  if (continuity != 1 && continuity != 2) {
    out.report = badInput("continuity must be 1 (G1) or 2 (G2), got " + std::to_string(continuity));
    return out;
  }
  if (n < 2 * continuity - 1 || n > kMaxDegree) {
    out.report = badInput("G" + std::to_string(continuity) + " needs a degree in [" +
                          std::to_string(2 * continuity - 1) + ", " + std::to_string(kMaxDegree) + "], got " +
                          std::to_string(n));
    return out;
  }
  if (!std::isfinite(shape.p) || !(options.tolerance > 0.0) || options.max_iterations < 1) {
    out.report = badInput("p, tolerance or iteration limit invalid");
    return out;
  }
  const Vec2 chord = end.point - start.point;
  const double lambda = chord.norm();
  const double scale = std::max({start.point.norm(), end.point.norm(), 1e-300});
  if (!(lambda > 1e-14 * scale)) {
    out.report = badInput("start and end points coincide");
    return out;
  }

  Problem pr;
  pr.n = n;
  if (shape.rational) {
    if (!(shape.w_e > 0.0) || !std::isfinite(shape.w_e) || !std::isfinite(shape.p_w)) {
      out.report = badInput("w_e must be positive and p_w finite");
      return out;
    }
    pr.weights = alpWeights(shape);
    for (double w : pr.weights)
      if (!(w > 0.0)) {
        out.report = badInput("p_w = " + fmt(shape.p_w) + " gives a non-positive weight (keep |p_w| <= 1)");
        return out;
      }
  }
  pr.theta_d = end.theta - start.theta;
  const Vec2 e = chord / lambda;
  const double c = std::cos(start.theta), s = std::sin(start.theta);
  pr.end = Vec2(c * e.x() + s * e.y(), -s * e.x() + c * e.y());

  // mu_i: the turning per unit rate k_i (seed 000 eq. 6 and 11).
  if (pr.weights.empty()) {
    pr.mu = Eigen::VectorXd::Constant(n + 1, 1.0 / (n + 1));
  } else {
    Eigen::VectorXd g;
    pr.mu = integrateAdaptive(
                [&](double t) {
                  rationalBasis(pr, t, g);
                  return Eigen::VectorXd(g);
                },
                0.0, 1.0, kMuTolerance)
                .value;
  }
  // The two free rates and what eq. 12 spreads between them.
  const int ia = continuity - 1, ib = n - continuity + 1, l = ib - ia - 1;
  Eigen::VectorXd A = Eigen::VectorXd::Zero(n + 1), B = A;
  A[ia] = 1.0;
  B[ib] = 1.0;
  const std::vector<double> from_a = alpInterpolate(1.0, 0.0, l, shape.p), from_b = alpInterpolate(0.0, 1.0, l, shape.p);
  for (int j = 0; j < l; ++j) {
    A[ia + 1 + j] = from_a[j];
    B[ia + 1 + j] = from_b[j];
  }
  const double alpha = pr.mu.dot(A), beta = pr.mu.dot(B);
  if (!(alpha + beta > 1e-12)) {
    out.report = badInput("p = " + fmt(shape.p) + " leaves the turning independent of the free curvatures (keep |p| <= 1)");
    return out;
  }
  pr.c0 = pr.theta_d / (alpha + beta) * (A + B);
  pr.c1 = Eigen::VectorXd::Zero(n + 1);
  if (continuity == 2) {
    const double ks = start.kappa * lambda, ke = end.kappa * lambda;  // normalized curvatures
    pr.c1[0] = ks;
    pr.c1[n] = ke;
    pr.c1 -= (ks * pr.mu[0] + ke * pr.mu[n]) / (alpha + beta) * (A + B);
  }
  pr.c2 = beta * A - alpha * B;

  // The circular arc of turning theta_d over the chord: length theta_d / (2 sin(theta_d/2)).
  const double half = 0.5 * std::abs(pr.theta_d);
  // (For |theta_d| near a multiple of 2 pi, where that arc cannot close, a long guess.)
  const double arc_length = half < 1e-8 ? 1.0 : half / std::max(std::abs(std::sin(half)), 0.1);

  Evaluator ev(pr);
  ev.build(1);
  Attempt best;
  int total_iterations = 0;
  for (const StartPoint& sp : kStarts) {
    Attempt at = levenbergMarquardt(ev, std::log(arc_length * sp.length_factor), sp.u, options.tolerance,
                                    options.max_iterations);
    total_iterations += at.iterations;
    for (int refine = 0; at.converged && refine <= kMaxGridRefinements; ++refine) {
      // Build the curve in the user's frame and check it by its own evaluation.
      const double L = std::exp(at.log_l);
      const Eigen::VectorXd k = pr.c0 + L * pr.c1 + at.u * pr.c2;
      std::vector<double> kappa(n + 1);
      for (int i = 0; i <= n; ++i) kappa[i] = k[i] / (L * lambda);
      if (continuity == 2) {  // exactly the given end curvatures
        kappa[0] = start.kappa;
        kappa[n] = end.kappa;
      }
      AlpCurve curve(kappa, pr.weights, L * lambda, start.point, start.theta);
      const double gap = (curve.end() - end.point).norm() / lambda;
      const double angle_gap = std::abs(curve.theta(curve.length()) - end.theta);
      if (gap <= std::max(kVerifyFactor * options.tolerance, kVerifyFloor) && angle_gap <= 1e-10) {
        out.report.status = SolveStatus::kConverged;
        out.report.iterations = total_iterations;
        out.report.residual = gap;
        out.report.message = "converged";
        out.check = checkCurvature(curve);
        out.curve = std::move(curve);
        return out;
      }
      // The fixed rule was not accurate enough for this curve: finer grid, resume.
      if (ev.panels() * 2 > kMaxPanels) break;
      ev.build(ev.panels() * 2);
      at = levenbergMarquardt(ev, at.log_l, at.u, options.tolerance, options.max_iterations);
      total_iterations += at.iterations;
    }
    if (at.residual < best.residual || !std::isfinite(best.residual)) best = at;
  }
  out.report.iterations = total_iterations;
  out.report.residual = best.residual;
  if (best.out_of_iterations) {
    out.report.status = SolveStatus::kIterationLimit;
    out.report.message = "iteration limit reached; smallest end gap " + fmt(best.residual) + " of the chord";
  } else {
    out.report.status = SolveStatus::kInfeasible;
    out.report.message = "no ALP curve of degree " + std::to_string(n) + " found from " +
                         std::to_string(std::size(kStarts)) + " starting points: smallest end gap " +
                         fmt(best.residual) + " of the chord" +
                         (best.grid_exhausted ? " (the curvature needed is beyond the solver's range)" : "");
  }
  return out;
}

}  // namespace la
