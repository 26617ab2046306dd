#include "fitting/g2_joints.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/least_squares.h"
#include "core/root_finding.h"

namespace la {
namespace {

// Finite-difference step of the joint angles for the Newton Jacobian (radians): the
// piece solves are accurate to ~1e-13 relative, so this leaves ~1e-6 relative error
// in the Jacobian, which costs Newton nothing noticeable.
constexpr double kAngleStep = 1e-7;
// Largest change of any joint angle in one Newton step (radians).
constexpr double kMaxAngleStep = 0.3;
// Halvings of a Newton step that does not shrink the largest gap.
constexpr int kMaxHalvings = 11;

class JointSystem {
 public:
  JointSystem(Chain& chain, const G2Options& options) : chain_(chain), options_(options) {
    const std::size_t n = chain.size();
    solves_.resize(n);
    for (std::size_t j = chain.closed ? 0 : 1; j < n; ++j) {
      const bool both_flat = chain.pieces[before(j)].kind == PieceKind::kInflectionEnd &&
                             chain.pieces[j].kind == PieceKind::kInflectionStart;
      if (!both_flat) equations_.push_back(j);
    }
  }

  std::size_t before(std::size_t joint) const { return (joint + chain_.size() - 1) % chain_.size(); }
  const std::vector<std::size_t>& equations() const { return equations_; }

  // Joint 0 of a closed chain is also joint n, whose angle differs by the curve's total
  // turning (a multiple of 2 pi): moving one moves the other by the same amount.
  void setAngle(std::size_t joint, double value) {
    if (chain_.closed && joint == 0) chain_.angles[chain_.size()] += value - chain_.angles[0];
    chain_.angles[joint] = value;
  }
  // The unknown of a joint's equation: its tangent angle, or for a sliding joint its
  // position along the tangent line.
  double unknown(std::size_t joint) const {
    return chain_.slides(joint) ? chain_.joints[joint].dot(unitVector(chain_.angles[joint])) : chain_.angles[joint];
  }
  void setUnknown(std::size_t joint, double value) {
    if (!chain_.slides(joint)) return setAngle(joint, value);
    const Vec2 shift = (value - unknown(joint)) * unitVector(chain_.angles[joint]);
    chain_.joints[joint] += shift;
    if (chain_.closed && joint == 0) chain_.joints[chain_.size()] += shift;
  }

  bool solvePieceAt(std::size_t i) {
    solves_[i] = solvePiece(chain_, i);
    return solves_[i].report.usable();
  }
  bool solveAll(std::string* why = nullptr) {
    for (std::size_t i = 0; i < chain_.size(); ++i)
      if (!solvePieceAt(i)) {
        if (why) *why = "piece " + std::to_string(i) + ": " + solves_[i].report.message;
        return false;
      }
    return true;
  }
  // Re-solves the two pieces that meet at a joint.
  bool solveAround(std::size_t joint) {
    const bool a = solvePieceAt(before(joint));
    return solvePieceAt(joint % chain_.size()) && a;
  }
  // The two pieces' solves at a joint, taken before its unknown moves, for setBack.
  std::pair<SegmentSolve, SegmentSolve> takeAround(std::size_t joint) {
    return {std::move(solves_[before(joint)]), std::move(solves_[joint % chain_.size()])};
  }
  // The joint's unknown back at `value`, with the two pieces' solves taken there: put
  // back where setting an angle restores the chain bit for bit, else solved again (a
  // closed chain's joint 0 and a slide move other values by differences).
  void setBack(std::size_t joint, double value, std::pair<SegmentSolve, SegmentSolve>&& taken) {
    setUnknown(joint, value);
    if (chain_.slides(joint) || (chain_.closed && joint == 0)) {
      solveAround(joint);
      return;
    }
    solves_[before(joint)] = std::move(taken.first);
    solves_[joint % chain_.size()] = std::move(taken.second);
  }

  double kappaLeft(std::size_t joint) const { return solves_[before(joint)].segment->kappaEnd(); }
  double kappaRight(std::size_t joint) const { return solves_[joint % chain_.size()].segment->kappaStart(); }
  double gap(std::size_t joint) const { return kappaLeft(joint) - kappaRight(joint); }
  double relGap(std::size_t joint) const {
    return relativeGap(kappaLeft(joint), kappaRight(joint), options_.diagonal);
  }
  double maxRelGap(std::size_t* worst = nullptr) const {
    double m = 0.0;
    std::size_t at = 0;
    for (std::size_t k = 0; k < equations_.size(); ++k) {
      const double g = relGap(equations_[k]);
      if (g > m) m = g, at = k;
    }
    if (worst) *worst = at;
    return m;
  }
  Eigen::VectorXd residual() const {
    Eigen::VectorXd f(equations_.size());
    for (std::size_t k = 0; k < equations_.size(); ++k) f[k] = gap(equations_[k]) * options_.diagonal;
    return f;
  }
  const std::vector<SegmentSolve>& solves() const { return solves_; }

 private:
  Chain& chain_;
  const G2Options& options_;
  std::vector<SegmentSolve> solves_;
  std::vector<std::size_t> equations_;  // joints with a curvature equation
};

// Newton on the joint unknowns (core/least_squares.h): every equation's gap must
// shrink (the cost is the largest), a step turns no joint by more than kMaxAngleStep and
// is halved while it does not help; the Jacobian by forward differences, one joint at a
// time (two piece solves each, to the other side where the forward step leaves the
// feasible range).
SolveReport newton(JointSystem& sys, const G2Options& options) {
  const auto& eq = sys.equations();
  const int m = static_cast<int>(eq.size());
  Eigen::VectorXd x(m), at(m);  // at: the unknowns the system's pieces are solved for
  for (int k = 0; k < m; ++k) x[k] = at[k] = sys.unknown(eq[k]);
  bool solved = true;  // (makeG2 solved them)
  auto moveTo = [&](const Eigen::VectorXd& to) {
    if (to == at) return solved;
    for (int k = 0; k < m; ++k) sys.setUnknown(eq[k], to[k]);
    at = to;
    return solved = sys.solveAll();
  };
  std::string infeasible;
  LeastSquaresProblem problem;
  problem.residual = [&](const Eigen::VectorXd& to, Eigen::VectorXd& f) {
    if (!moveTo(to)) return false;
    f = sys.residual();
    return true;
  };
  problem.converged = [&](const Eigen::VectorXd&, const Eigen::VectorXd&) { return sys.maxRelGap() <= options.threshold; };
  problem.jacobian = [&](const Eigen::VectorXd&, Eigen::VectorXd& f, Eigen::MatrixXd& jac) {
    jac.resize(m, m);
    for (int k = 0; k < m; ++k) {
      const double saved = sys.unknown(eq[k]);
      auto taken = sys.takeAround(eq[k]);
      sys.setUnknown(eq[k], saved + kAngleStep);
      const bool ok = sys.solveAround(eq[k]);
      if (ok) jac.col(k) = (sys.residual() - f) / kAngleStep;
      sys.setBack(eq[k], saved, std::move(taken));
      if (!ok) {  // step to the other side
        auto again = sys.takeAround(eq[k]);
        sys.setUnknown(eq[k], saved - kAngleStep);
        if (!sys.solveAround(eq[k])) {
          infeasible = "joint " + std::to_string(eq[k]) + " is at the edge of feasibility";
          return false;
        }
        jac.col(k) = (f - sys.residual()) / kAngleStep;
        sys.setBack(eq[k], saved, std::move(again));
      }
    }
    return true;
  };
  LeastSquaresOptions o;
  o.max_iterations = options.max_iterations;
  o.cost = LeastSquaresCost::kLargest;
  o.max_halvings = kMaxHalvings;
  o.max_step = Eigen::VectorXd::Constant(m, kMaxAngleStep);
  Eigen::VectorXd f;
  const LeastSquaresSummary s = solveLeastSquares(problem, x, f, o);
  moveTo(x);
  const int steps = s.successful_steps;
  switch (s.end) {
    case LeastSquaresEnd::kConverged: return {SolveStatus::kConverged, steps, sys.maxRelGap(), "G2 by Newton"};
    case LeastSquaresEnd::kNoJacobian: return {SolveStatus::kInfeasible, steps, sys.maxRelGap(), infeasible};
    case LeastSquaresEnd::kNoDescent:
      return {SolveStatus::kIterationLimit, steps + 1, sys.maxRelGap(), "G2 Newton stalled (" + s.message + ")"};
    default: return {SolveStatus::kIterationLimit, steps, sys.maxRelGap(), "G2 Newton: iteration limit"};
  }
}

// The paper's method: the joint with the largest gap is bisected to zero gap, repeatedly.
SolveReport bisection(JointSystem& sys, const G2Options& options) {
  const auto& eq = sys.equations();
  const int budget = options.max_iterations * std::max<int>(1, static_cast<int>(eq.size()));
  for (int round = 0; round <= budget; ++round) {
    std::size_t worst_k = 0;
    const double worst = sys.maxRelGap(&worst_k);
    if (worst <= options.threshold) return {SolveStatus::kConverged, round, worst, "G2 by joint bisection"};
    if (round == budget) break;
    const std::size_t joint = eq[worst_k];
    const double a0 = sys.unknown(joint), g0 = sys.gap(joint);
    auto gap_at = [&](double a, bool* ok) {
      sys.setUnknown(joint, a);
      *ok = sys.solveAround(joint);
      return *ok ? sys.gap(joint) : NAN;
    };
    // Which way closes the gap: a tiny probe.
    bool ok = false;
    const double gp = gap_at(a0 + kAngleStep, &ok);
    const bool increasing = ok ? gp > g0 : true;
    const double dir = ((g0 > 0) == increasing) ? -1.0 : 1.0;
    // Expand the step until the gap changes sign (or pieces stop existing).
    double step = 1e-3, lo = a0, hi = a0, found = false;
    for (int k = 0; k < 40 && !found; ++k, step *= 2.0) {
      const double g = gap_at(a0 + dir * step, &ok);
      if (!ok) {
        step *= 0.25;  // went past feasibility: creep closer instead
        if (step < 1e-12) break;
        continue;
      }
      if ((g > 0) != (g0 > 0)) {
        lo = std::min(a0, a0 + dir * step);
        hi = std::max(a0, a0 + dir * step);
        found = true;
      }
    }
    if (!found) {
      sys.setUnknown(joint, a0);
      sys.solveAround(joint);
      return {SolveStatus::kInfeasible, round, worst, "joint " + std::to_string(joint) + ": no tangent angle closes the curvature gap"};
    }
    const double kappa_scale = std::max({std::abs(sys.kappaLeft(joint)), std::abs(sys.kappaRight(joint)), 1.0 / options.diagonal});
    RootOptions root;
    root.f_tol = 0.1 * options.threshold * kappa_scale;
    root.x_tol = 1e-15;
    root.max_iterations = 200;
    auto f = [&](double a) {
      bool good = false;
      const double g = gap_at(a, &good);
      // an infeasible angle lies beyond the root's side: report it as far from zero
      return std::pair{good ? g : (increasing ? -1e300 : 1e300), NAN};  // NaN slope: pure bisection
    };
    const RootResult r = solveMonotone(f, lo, hi, 0.5 * (lo + hi), increasing, root);
    sys.setUnknown(joint, r.report.usable() ? r.x : a0);
    if (!sys.solveAround(joint)) {
      sys.setUnknown(joint, a0);
      sys.solveAround(joint);
      return {SolveStatus::kInfeasible, round, worst, "joint " + std::to_string(joint) + ": bisection left the feasible range"};
    }
  }
  return {SolveStatus::kIterationLimit, budget, sys.maxRelGap(), "G2 bisection: round limit"};
}

}  // namespace

const char* toString(G2Method method) {
  switch (method) {
    case G2Method::kNewton: return "newton";
    case G2Method::kBisection: return "bisection";
    case G2Method::kOff: return "off";
  }
  return "unknown";
}

double relativeGap(double kl, double kr, double diagonal) {
  return std::abs(kl - kr) / std::max({std::abs(kl), std::abs(kr), 1.0 / diagonal});
}

G2Result makeG2(Chain& chain, const G2Options& options) {
  G2Result out;
  JointSystem sys(chain, options);
  std::string why;
  if (!sys.solveAll(&why)) {
    out.report = {SolveStatus::kInfeasible, 0, INFINITY, why};
    return out;
  }
  if (options.method == G2Method::kNewton) {
    out.report = newton(sys, options);
    if (!out.report.usable()) {  // Newton stalls near the edge of feasibility; joint by joint may still get there
      const SolveReport fallback = bisection(sys, options);
      out.report = fallback.usable() ? SolveReport{SolveStatus::kConverged, out.report.iterations + fallback.iterations, fallback.residual,
                                                   "G2 by Newton, finished joint by joint (" + out.report.message + ")"}
                                     : SolveReport{fallback.status, out.report.iterations + fallback.iterations, fallback.residual,
                                                   out.report.message + "; then " + fallback.message};
    }
  }
  else if (options.method == G2Method::kBisection) out.report = bisection(sys, options);
  else out.report = {SolveStatus::kConverged, 0, sys.maxRelGap(), "G2 off: curvature gaps left as they are"};
  if (!sys.solveAll(&why)) {  // every path above leaves the pieces solved; this guards the invariant
    out.report = {SolveStatus::kInfeasible, out.report.iterations, INFINITY, why};
    return out;
  }
  for (const SegmentSolve& s : sys.solves()) out.segments.push_back(*s.segment);
  for (std::size_t j = chain.closed ? 0 : 1; j < chain.size(); ++j) out.gaps.push_back(sys.relGap(j));
  out.max_gap = out.gaps.empty() ? 0.0 : *std::max_element(out.gaps.begin(), out.gaps.end());
  return out;
}

}  // namespace la
