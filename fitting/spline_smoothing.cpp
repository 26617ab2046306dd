#include "fitting/spline_smoothing.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <optional>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace la {
namespace {

// A span holding this many points is split whenever one of them is out of tolerance.
// A sparser span (sparse strokes: $1 gestures have 30-80 points) is split only where
// the miss is shared: a point out of tolerance whose neighbour lies on the same side of
// the spline. A lone outlier pulls the spline towards itself and so its neighbours to
// the other side: that one is not chased (a knot per point is not fairing). Spans of
// fewer than 2 points are never split.
constexpr int kMinPointsToSplit = 6;
constexpr int kMinPointsToSplitShared = 2;
// Up to this many control points the normal equations are solved dense (faster than
// the sparse factorization's set-up); above, sparse LDLT.
constexpr int kDenseLimit = 48;
// Solves at fixed knots after the last knot round, while the rms residual still falls by
// more than kSettled (relative): the foot points and the spline settle together.
constexpr int kSettleSolves = 3;
constexpr double kSettled = 0.01;

// Chord-length parameters in [0, 1]; for a closed stroke the closing chord counts too
// and 1 is the start again.
std::vector<double> chordParameters(const std::vector<Vec2>& pts, bool closed) {
  std::vector<double> t(pts.size(), 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) t[i] = t[i - 1] + (pts[i] - pts[i - 1]).norm();
  double total = t.back();
  if (closed) total += (pts.front() - pts.back()).norm();
  for (double& v : t) v /= total;
  return t;
}

CubicBSpline makeSpline(const std::vector<double>& breaks, std::vector<Vec2> control, bool closed) {
  return closed ? CubicBSpline::periodic(breaks, control) : CubicBSpline::clamped(breaks, std::move(control));
}

int controlCount(const std::vector<double>& breaks, bool closed) {
  const int spans = static_cast<int>(breaks.size()) - 1;
  return closed ? spans : spans + 3;
}

// The four nonzero basis functions of every span as cubics in (t - knot_i), and a span
// lookup that walks from the previous point's span: points come in order along the
// stroke, so evaluating the basis at each costs a few multiplications instead of de
// Boor's recursion and a binary search (the hot loop of every solve).
class BasisTable {
 public:
  explicit BasisTable(const CubicBSpline& shape) : shape_(shape) {
    const auto& knots = shape.knots();
    const int first = CubicBSpline::kDegree, last = static_cast<int>(shape.control().size()) - 1;
    coefficients_.resize(last + 1);
    double ders[4][4];
    for (int i = first; i <= last; ++i) {
      if (!(knots[i + 1] > knots[i])) continue;
      shape.basis(i, knots[i], ders, 3);
      for (int a = 0; a < 4; ++a)
        coefficients_[i][a] = {ders[0][a], ders[1][a], ders[2][a] / 2.0, ders[3][a] / 6.0};
    }
  }
  // Span of t (wrapped) starting from `hint`, and the four basis values there.
  int evaluate(double t, int hint, double value[4]) const {
    t = shape_.wrap(t);
    const int i = shape_.spanFrom(t, hint);
    const double u = t - shape_.knots()[i];
    for (int a = 0; a < 4; ++a) {
      const auto& c = coefficients_[i][a];
      value[a] = c[0] + u * (c[1] + u * (c[2] + u * c[3]));
    }
    return i;
  }

 private:
  const CubicBSpline& shape_;
  std::vector<std::array<std::array<double, 4>, 4>> coefficients_;
};

// The data part of the normal equations, B^T B and B^T X, for points at parameters t:
// each point touches only its span's four control points, so the products are summed
// per span (one triangle) and handed to add(row, column, value) and rhs once per span.
// Each point's control indices and basis values are kept if asked for.
template <typename Add>
void accumulateData(const CubicBSpline& shape, const std::vector<Vec2>& pts, const std::vector<double>& t,
                    Eigen::MatrixXd& rhs, Add&& add, std::vector<std::array<int, 4>>* indices = nullptr,
                    std::vector<std::array<double, 4>>* values = nullptr) {
  const BasisTable table(shape);
  double block[4][4] = {}, bx[4] = {}, by[4] = {};
  int open_span = -1;
  auto flush = [&] {
    if (open_span < 0) return;
    for (int a = 0; a < 4; ++a) {
      const int ia = shape.controlIndex(open_span - 3 + a);
      rhs(ia, 0) += bx[a];
      rhs(ia, 1) += by[a];
      bx[a] = by[a] = 0.0;
      for (int b = a; b < 4; ++b) {
        const int ib = shape.controlIndex(open_span - 3 + b);
        add(ia, ib, block[a][b]);
        if (b != a) add(ib, ia, block[a][b]);
        block[a][b] = 0.0;
      }
    }
  };
  if (indices) indices->resize(pts.size());
  if (values) values->resize(pts.size());
  int sp = CubicBSpline::kDegree;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double v[4];
    sp = table.evaluate(t[i], sp, v);
    if (sp != open_span) {
      flush();
      open_span = sp;
    }
    for (int a = 0; a < 4; ++a) {
      bx[a] += v[a] * pts[i].x();
      by[a] += v[a] * pts[i].y();
      for (int b = a; b < 4; ++b) block[a][b] += v[a] * v[b];
      if (indices) (*indices)[i][a] = shape.controlIndex(sp - 3 + a);
      if (values) (*values)[i][a] = v[a];
    }
  }
  flush();
}

// The jerk Gram matrix (times scale): C''' is constant on each span, so the integral of
// |C'''|^2 is the sum over spans of width * |C'''|^2.
template <typename Add>
void accumulateJerk(const CubicBSpline& shape, const std::vector<double>& breaks, double scale, Add&& add) {
  double ders[4][4];
  for (std::size_t j = 0; j + 1 < breaks.size(); ++j) {
    const double width = breaks[j + 1] - breaks[j];
    const double mid = 0.5 * (breaks[j] + breaks[j + 1]);
    const int sp = shape.span(mid);
    shape.basis(sp, mid, ders);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        add(shape.controlIndex(sp - 3 + a), shape.controlIndex(sp - 3 + b), scale * width * ders[3][a] * ders[3][b]);
  }
}

std::vector<Vec2> controlOf(const Eigen::MatrixXd& x) {
  std::vector<Vec2> control(x.rows());
  for (Eigen::Index k = 0; k < x.rows(); ++k) control[k] = Vec2(x(k, 0), x(k, 1));
  return control;
}

// An open spline through its end points (`through_ends`): a clamped spline's first and
// last control points are its ends, held at the first and last points, their columns of
// the normal equations (dense or sparse) moved to the right-hand side.
template <typename Matrix>
void holdEnds(Matrix& a, Eigen::MatrixXd& rhs, const std::vector<Vec2>& pts) {
  const Eigen::Index last = a.rows() - 1;
  for (const auto& end : {std::pair{Eigen::Index{0}, pts.front()}, std::pair{last, pts.back()}}) {
    const Eigen::Index k = end.first;  // (no structured binding: clang 14 cannot capture one)
    const Vec2& p = end.second;
    rhs -= Eigen::VectorXd(a.col(k)) * p.transpose();
    if constexpr (std::is_same_v<Matrix, Eigen::SparseMatrix<double>>) {
      a.prune([k](Eigen::Index r, Eigen::Index c, double) { return r != k && c != k; });
    } else {
      a.row(k).setZero();
      a.col(k).setZero();
    }
    a.coeffRef(k, k) = 1.0;
    rhs.row(k) = p.transpose();
  }
}

// Solves the penalized least squares for fixed breaks and parameters.
bool solveControl(const std::vector<Vec2>& pts, const std::vector<double>& t, const std::vector<double>& breaks,
                  bool closed, bool through_ends, double weight, std::vector<Vec2>& control) {
  const int n = controlCount(breaks, closed);
  // A template spline (zero control) gives the knot vector and basis functions.
  const CubicBSpline shape = makeSpline(breaks, std::vector<Vec2>(n, Vec2::Zero()), closed);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
  const double scale = weight * static_cast<double>(pts.size());
  Eigen::MatrixXd x;
  // The normal equations are banded (the periodic case wraps around): dense when small,
  // else sparse.
  if (n <= kDenseLimit) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    auto add = [&](int r, int c, double v) { a(r, c) += v; };
    accumulateData(shape, pts, t, rhs, add);
    accumulateJerk(shape, breaks, scale, add);
    if (through_ends) holdEnds(a, rhs, pts);
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(a);
    if (ldlt.info() != Eigen::Success) return false;
    x = ldlt.solve(rhs);
  } else {
    std::vector<Eigen::Triplet<double>> triplets;
    auto add = [&](int r, int c, double v) { triplets.emplace_back(r, c, v); };
    accumulateData(shape, pts, t, rhs, add);
    accumulateJerk(shape, breaks, scale, add);
    Eigen::SparseMatrix<double> a(n, n);
    a.setFromTriplets(triplets.begin(), triplets.end());
    if (through_ends) holdEnds(a, rhs, pts);
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
    if (ldlt.info() != Eigen::Success) return false;
    x = ldlt.solve(rhs);
  }
  if (!x.allFinite()) return false;
  control = controlOf(x);
  return true;
}

// The normal equations at fixed parameters t, kept apart: the data part B^T B and B^T X,
// the jerk Gram matrix, and each point's four basis values. The fairness search solves
// them for many weights without touching the points again (dense systems only).
struct FixedParameterSystem {
  Eigen::MatrixXd data, gram, rhs;
  std::vector<std::array<int, 4>> index;
  std::vector<std::array<double, 4>> basis;
  bool through_ends = false;

  FixedParameterSystem(const std::vector<Vec2>& pts, const std::vector<double>& t, const std::vector<double>& breaks,
                       bool closed, bool through_ends) : through_ends(through_ends) {
    const int n = controlCount(breaks, closed);
    const CubicBSpline shape = makeSpline(breaks, std::vector<Vec2>(n, Vec2::Zero()), closed);
    data = gram = Eigen::MatrixXd::Zero(n, n);
    rhs = Eigen::MatrixXd::Zero(n, 2);
    accumulateData(shape, pts, t, rhs, [&](int r, int c, double v) { data(r, c) += v; }, &index, &basis);
    accumulateJerk(shape, breaks, 1.0, [&](int r, int c, double v) { gram(r, c) += v; });
  }
  // Control points for jerk weight w (the same scaling as solveControl) and the distances
  // of the points from their (unmoved) parameters on that spline; false if singular.
  bool solve(double weight, const std::vector<Vec2>& pts, std::vector<Vec2>& control, std::vector<double>& dist) const {
    // (factored in place, and the right-hand side copied only to hold the ends: the
    // fairness search solves this for every weight it tries)
    Eigen::MatrixXd a = data + weight * static_cast<double>(pts.size()) * gram, held_rhs;
    if (through_ends) {
      held_rhs = rhs;
      holdEnds(a, held_rhs, pts);
    }
    const Eigen::LDLT<Eigen::Ref<Eigen::MatrixXd>> ldlt(a);
    if (ldlt.info() != Eigen::Success) return false;
    const Eigen::MatrixXd x = ldlt.solve(through_ends ? held_rhs : rhs);
    if (!x.allFinite()) return false;
    control = controlOf(x);
    dist.resize(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      Vec2 c = Vec2::Zero();
      for (int a = 0; a < 4; ++a) c += basis[i][a] * control[index[i][a]];
      dist[i] = (c - pts[i]).norm();
    }
    return true;
  }
};

// Newton steps towards the foot point of each X_i; returns per-point distances. The
// spline is evaluated from its per-span polynomials (Horner), the hot loop of smoothing.
void correctParameters(const CubicBSpline& spline, const std::vector<Vec2>& pts, int steps,
                       std::vector<double>& t, std::vector<double>& dist) {
  const int first = CubicBSpline::kDegree, last = static_cast<int>(spline.control().size()) - 1;
  std::vector<std::array<Vec2, 4>> poly(last - first + 1);
  for (int i = first; i <= last; ++i) poly[i - first] = spline.spanPolynomial(i);
  const auto& knots = spline.knots();
  int span = first;  // walks along with the points (they come in order)
  auto eval = [&](double ti, Vec2& c0, Vec2& c1, Vec2& c2) {
    ti = spline.wrap(ti);
    const int i = span = spline.spanFrom(ti, span);
    const double u = ti - knots[i];
    const auto& c = poly[i - first];
    c0 = c[0] + u * (c[1] + u * (c[2] + u * c[3]));
    c1 = c[1] + u * (2.0 * c[2] + 3.0 * u * c[3]);
    c2 = 2.0 * c[2] + 6.0 * u * c[3];
  };
  dist.resize(pts.size());
  Vec2 c0, c1, c2;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double ti = t[i];
    for (int k = 0; k < steps; ++k) {
      eval(ti, c0, c1, c2);
      const Vec2 r = c0 - pts[i];
      const double g = r.dot(c1), h = c1.squaredNorm() + r.dot(c2);
      if (!(h > 0.0)) break;
      ti = spline.isPeriodic() ? ti - g / h : std::clamp(ti - g / h, spline.tMin(), spline.tMax());
    }
    t[i] = ti;
    eval(ti, c0, c1, c2);
    dist[i] = (c0 - pts[i]).norm();
  }
}

double rmsOf(const std::vector<double>& d) {
  double sum = 0.0;
  for (double v : d) sum += v * v;
  return d.empty() ? 0.0 : std::sqrt(sum / d.size());
}

struct Attempt {
  std::vector<Vec2> control;
  std::vector<double> t, dist;
  double max_error = INFINITY;
};

// One fit at fixed breaks and weight, with foot-point correction.
bool attempt(const std::vector<Vec2>& pts, const std::vector<double>& breaks, bool closed, bool through_ends,
             double weight, int steps, Attempt& a) {
  if (!solveControl(pts, a.t, breaks, closed, through_ends, weight, a.control)) return false;
  const CubicBSpline spline = makeSpline(breaks, a.control, closed);
  correctParameters(spline, pts, steps, a.t, a.dist);
  a.max_error = *std::max_element(a.dist.begin(), a.dist.end());
  return true;
}

// The smoothing with the ends free, or with an open spline through its end points.
SmoothingResult smoothOnce(const std::vector<Vec2>& points, bool closed, bool through_ends,
                           const SmoothingOptions& options) {
  if (points.size() < 4) throw std::invalid_argument("B-spline smoothing needs at least 4 points");
  // Fitted about the points' centre, then moved back (a B-spline moves with its control
  // points): the normal equations of points a million units from the origin lose the
  // digits that tell their shape apart.
  const Vec2 centre = boundingBoxOf(points).centre();
  std::vector<Vec2> pts;
  pts.reserve(points.size());
  for (const Vec2& q : points) pts.push_back(q - centre);
  if (!(options.tolerance > 0.0)) throw std::invalid_argument("B-spline smoothing needs a positive tolerance");
  const int min_spans = closed ? 4 : 1;
  std::vector<double> breaks;
  const int spans0 = std::max(min_spans, options.initial_spans);
  for (int j = 0; j <= spans0; ++j) breaks.push_back(static_cast<double>(j) / spans0);

  Attempt current;
  current.t = chordParameters(pts, closed);
  double weight = options.fairness;
  SmoothingResult result{makeSpline(breaks, std::vector<Vec2>(controlCount(breaks, closed), Vec2::Zero()), closed),
                         {}, 0, 0, 0, 0, {}};
  int round = 0;
  for (; round < options.max_rounds; ++round) {
    if (!attempt(pts, breaks, closed, through_ends, weight, options.foot_point_steps, current)) {
      result.report = {SolveStatus::kBadInput, round, INFINITY, "B-spline least squares is singular"};
      return result;
    }
    if (current.max_error <= options.tolerance || round + 1 == options.max_rounds) break;
    // Split every span holding a point out of tolerance (if it holds enough points, or
    // the miss is shared, see kMinPointsToSplit).
    const CubicBSpline spline = makeSpline(breaks, current.control, closed);
    const int spans = static_cast<int>(breaks.size()) - 1;
    std::vector<int> bad(spans, 0), shared(spans, 0), count(spans, 0);
    std::vector<int> span_of(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const int j = span_of[i] = std::clamp(spline.span(current.t[i]) - 3, 0, spans - 1);
      ++count[j];
      if (current.dist[i] > options.tolerance) bad[j] = 1;
    }
    // In sparse spans: is a miss shared by a neighbour on the same side of the spline
    // (signed distance along the normal)?
    auto side = [&](std::size_t i) {
      const Vec2 d1 = spline.evaluate(current.t[i], 1);
      return cross(d1, pts[i] - spline.point(current.t[i]));
    };
    const std::size_t n = pts.size();
    for (std::size_t i = 0; i < n; ++i) {
      const int j = span_of[i];
      if (!bad[j] || count[j] >= kMinPointsToSplit || shared[j] || current.dist[i] <= options.tolerance) continue;
      const double mine = side(i);
      if ((closed || i > 0) && side((i + n - 1) % n) * mine > 0.0) shared[j] = 1;
      if ((closed || i + 1 < n) && side((i + 1) % n) * mine > 0.0) shared[j] = 1;
    }
    std::vector<double> next{breaks.front()};
    int added = 0;  // (the spans of this round count against max_spans too)
    for (int j = 0; j < spans; ++j) {
      const bool worth = count[j] >= kMinPointsToSplit || (shared[j] && count[j] >= kMinPointsToSplitShared);
      if (bad[j] && worth && spans + added + 1 <= options.max_spans) {
        next.push_back(0.5 * (breaks[j] + breaks[j + 1]));
        ++added;
      }
      next.push_back(breaks[j + 1]);
    }
    if (added == 0) break;
    breaks = std::move(next);
  }
  result.rounds = round + 1;
  // The last solve used the parameters from before its own foot-point correction: solve
  // again until the residuals settle (the knots stay).
  for (int k = 0; k < kSettleSolves && current.max_error <= options.tolerance; ++k) {
    Attempt again = current;
    if (!attempt(pts, breaks, closed, through_ends, weight, options.foot_point_steps, again)) break;
    const double before = rmsOf(current.dist), after = rmsOf(again.dist);
    if (again.max_error > options.tolerance) break;
    current = std::move(again);
    if (before - after < kSettled * before) break;
  }

  // Raise the fairness weight as far as the tolerance allows and the noise justifies:
  // the residuals may grow to the noise level (Morozov's discrepancy principle: rms
  // distance of 2D noise sigma is sigma sqrt(2)), never past the tolerance margin.
  const double limit = options.fairness_margin * options.tolerance;
  const double rms_limit = std::sqrt(2.0) * options.noise_sigma;
  auto acceptable = [&](const Attempt& a) { return a.max_error <= limit && rmsOf(a.dist) <= rms_limit; };
  if (current.max_error <= options.tolerance && options.fairness_steps > 0 && options.noise_sigma > 0.0) {
    double lo = std::log(weight), hi = std::log(options.max_fairness);
    const bool dense = controlCount(breaks, closed) <= kDenseLimit;
    // A trial weight: at the parameters held (distances from them are upper bounds of the
    // foot distances, so a weight found acceptable is), cheap for a dense system; else a
    // full attempt with its own foot correction.
    std::optional<FixedParameterSystem> fixed;
    if (dense) fixed.emplace(pts, current.t, breaks, closed, through_ends);
    auto trialAt = [&](double w, Attempt& a) {
      a = current;
      if (!fixed) return attempt(pts, breaks, closed, through_ends, w, options.foot_point_steps, a);
      if (!fixed->solve(w, pts, a.control, a.dist)) return false;
      a.max_error = *std::max_element(a.dist.begin(), a.dist.end());
      return true;
    };
    const double start_weight = weight;
    Attempt probe;
    if (trialAt(options.max_fairness, probe) && acceptable(probe)) {
      current = probe;
      weight = options.max_fairness;
    } else {
      for (int k = 0; k < options.fairness_steps; ++k) {
        const double mid = 0.5 * (lo + hi);
        Attempt trial;
        if (trialAt(std::exp(mid), trial) && acceptable(trial)) {
          current = std::move(trial);
          lo = mid;
          weight = std::exp(mid);
        } else {
          hi = mid;
        }
      }
    }
    // The chosen weight once more with the foot points corrected.
    if (dense && weight != start_weight) {
      Attempt final_fit = current;
      if (attempt(pts, breaks, closed, through_ends, weight, options.foot_point_steps, final_fit) &&
          final_fit.max_error <= options.tolerance)
        current = std::move(final_fit);
    }
  }

  for (Vec2& c : current.control) c += centre;
  result.spline = makeSpline(breaks, current.control, closed);
  result.parameters = current.t;
  result.max_error = current.max_error;
  result.rms_error = rmsOf(current.dist);
  result.fairness = weight;
  const bool ok = current.max_error <= options.tolerance;
  result.report = {ok ? SolveStatus::kConverged : SolveStatus::kIterationLimit, result.rounds, current.max_error,
                   ok ? "within tolerance with " + std::to_string(breaks.size() - 1) + " spans"
                      : "tolerance not reached with " + std::to_string(breaks.size() - 1) + " spans (max error " +
                            std::to_string(current.max_error) + ")"};
  return result;
}

}  // namespace

SmoothingResult smoothWithBSpline(const std::vector<Vec2>& points, bool closed, const SmoothingOptions& options) {
  SmoothingResult free_ends = smoothOnce(points, closed, false, options);
  if (closed || free_ends.report.status != SolveStatus::kIterationLimit ||
      !(free_ends.max_error > options.through_ends_beyond * options.tolerance))
    return free_ends;
  // Out of tolerance with its ends free: again through the end points, kept where that
  // keeps the tolerance. A clamped end can fall short of its point along the tangent (the
  // point's foot held at the end, its neighbours' feet sliding along), which halving the
  // end span cannot cure, and dense exact points emptied the end spans until the spline's
  // start ran away (6,400 samples of a sine: 16 off with 400 spans; through its ends,
  // within 0.03 with 14). Not the first try: a noisy end point held exactly added 62
  // segments and 37 extrema on the shared data.
  SmoothingResult through_ends = smoothOnce(points, closed, true, options);
  return through_ends.max_error <= options.tolerance ? through_ends : free_ends;
}

}  // namespace la
