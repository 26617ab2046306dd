#include "fitting/quality.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "fitting/g2_joints.h"

namespace la {
namespace {

// Cell size of the edge grid, in median polyline edge lengths: a cell holds about this
// many edges of a curve passing through it once, and a point within the tolerance of
// the curve finds its foot in the first ring or two of cells.
constexpr double kEdgesPerCell = 4.0;
// Edges either side of the previous point's nearest edge that give each point its first
// bound (consecutive points are about one polyline edge apart).
constexpr int kNeighbourEdges = 3;
// Samples are placed to this fraction of the measure's resolution (their quadrature
// needs no more: near a cusp it took seconds a measure to place them to 1e-10 of the
// segment's length).
constexpr double kSamplePrecision = 0.01;
// The relative tolerance of a segment's samples that places them within kSamplePrecision
// of `precision` (world units).
double sampleTolerance(const LaSegment& segment, double precision) {
  return std::max(kDefaultRelativeTolerance, kSamplePrecision * precision / segment.length());
}
// Cells per axis at most (memory stays below a few MB for any curve).
constexpr int kMaxCellsPerAxis = 512;

// The polyline's edges bucketed in a uniform grid (compressed rows: cell c holds
// edges[start[c] .. start[c+1])), for exact nearest-edge queries: rings of cells around
// the query point are searched until the ring is further than the best edge found.
// (Following the previous foot along the curve instead locks onto the wrong passage
// where the curve comes back near itself: at a closed curve's seam, across a self-
// intersection, on both sides of a thin trailing edge.)
class EdgeGrid {
 public:
  /// The grid covers the polyline's bounding box, or only `region` (lo, hi) where the
  /// queries are known to lie there: a curve that runs far from the points (a fit gone
  /// astray) must not coarsen the cells where the points are. Edges wholly outside the
  /// region are kept aside and searched only by a query the grid cannot answer.
  explicit EdgeGrid(const std::vector<Vec2>& poly, std::optional<std::pair<Vec2, Vec2>> region = std::nullopt)
      : poly_(poly) {
    const int edges = static_cast<int>(poly.size()) - 1;
    direction_.resize(edges);
    inverse_length2_.resize(edges);
    for (int e = 0; e < edges; ++e) {
      direction_[e] = poly[e + 1] - poly[e];
      const double l2 = direction_[e].squaredNorm();
      inverse_length2_[e] = l2 > 0.0 ? 1.0 / l2 : 0.0;
    }
    lo_ = hi_ = poly.front();
    for (const Vec2& q : poly) lo_ = lo_.cwiseMin(q), hi_ = hi_.cwiseMax(q);
    auto outside = [&](int e) {
      const Vec2 a = poly[e].cwiseMin(poly[e + 1]), b = poly[e].cwiseMax(poly[e + 1]);
      return (b.array() < lo_.array()).any() || (a.array() > hi_.array()).any();
    };
    if (region) {
      lo_ = lo_.cwiseMax(region->first), hi_ = hi_.cwiseMin(region->second);
      if ((lo_.array() > hi_.array()).any()) lo_ = hi_ = region->first;  // no edge there
    }
    // (the median edge, not the mean: a curve run away has a few edges as long as the
    // box, which would make one cell of it)
    std::vector<double> lengths;
    for (int e = 0; e < edges; ++e) {
      if (region && outside(e)) {
        far_.push_back(e);
        continue;
      }
      lengths.push_back(direction_[e].norm());
    }
    const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
    if (!lengths.empty()) std::nth_element(lengths.begin(), middle, lengths.end());
    const double typical = lengths.empty() ? 0.0 : *middle;
    const Vec2 extent = hi_ - lo_;
    cell_ = std::max({kEdgesPerCell * typical, extent.maxCoeff() / kMaxCellsPerAxis, 1e-300});
    nx_ = std::clamp(static_cast<int>(extent.x() / cell_) + 1, 1, kMaxCellsPerAxis + 1);
    ny_ = std::clamp(static_cast<int>(extent.y() / cell_) + 1, 1, kMaxCellsPerAxis + 1);
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    auto cover = [&](int e, auto&& visit) {  // the cells the edge's bounding box touches
      if (region && outside(e)) return;
      const Vec2 a = poly[e].cwiseMin(poly[e + 1]), b = poly[e].cwiseMax(poly[e + 1]);
      const int x0 = cellX(a.x()), x1 = cellX(b.x()), y0 = cellY(a.y()), y1 = cellY(b.y());
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) visit(static_cast<std::size_t>(y) * nx_ + x);
    };
    for (int e = 0; e < edges; ++e) cover(e, [&](std::size_t c) { ++start_[c + 1]; });
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    edges_.resize(start_.back());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int e = 0; e < edges; ++e) cover(e, [&](std::size_t c) { edges_[fill[c]++] = e; });
  }
  int edges() const { return static_cast<int>(direction_.size()); }  // (the polyline's points less one)

  // The distance from p to the nearest edge, for queries in order along a curve: the
  // `neighbours` edges either side of the previous query's nearest (`edge`, which
  // becomes this one's) give a first bound, which the grid search confirms or beats.
  double distanceAlong(const Vec2& p, int neighbours, int& edge) const {
    double bound2 = INFINITY;
    const int from = std::max(0, edge - neighbours), to = std::min(edges() - 1, edge + neighbours);
    for (int e = from; e <= to; ++e) {
      const double d2 = distance2(p, e);
      if (d2 < bound2) bound2 = d2, edge = e;
    }
    return distance(p, bound2, edge);
  }

  // How far p lies outside the box the grid covers (0 inside).
  double outsideBox(const Vec2& p) const { return (lo_ - p).cwiseMax(p - hi_).cwiseMax(Vec2::Zero()).norm(); }

  // Squared distance from p to edge e (a point edge: to its start).
  // (in scalars: the instrumented fuzzing build runs small Eigen expressions slowly, and
  // a hostile stroke's measures spent 40% of its fit here)
  double distance2(const Vec2& p, int e) const {
    const double ax = p.x() - poly_[e].x(), ay = p.y() - poly_[e].y();
    const double dx = direction_[e].x(), dy = direction_[e].y();
    const double t = std::clamp((ax * dx + ay * dy) * inverse_length2_[e], 0.0, 1.0);
    const double rx = ax - t * dx, ry = ay - t * dy;
    return rx * rx + ry * ry;
  }

  // Distance from p to the nearest edge, which is written to `edge`. `bound2` is the
  // squared distance to some edge already known (`edge` that one), which lets the search
  // stop early: after each ring of cells, once nothing unsearched can be closer.
  double distance(const Vec2& p, double bound2, int& edge) const {
    // The point's cell (possibly outside the grid) and its Chebyshev distance to the grid.
    constexpr double kFar = 1e9;  // cells; keeps the integer arithmetic in range
    const double fx = (p.x() - lo_.x()) / cell_, fy = (p.y() - lo_.y()) / cell_;
    const int px = static_cast<int>(std::clamp(std::floor(fx), -kFar, kFar));
    const int py = static_cast<int>(std::clamp(std::floor(fy), -kFar, kFar));
    const int outside = std::max({0, -px, px - (nx_ - 1), -py, py - (ny_ - 1)});
    double best2 = bound2;
    auto visit = [&](int x, int y) {
      const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
      for (int k = start_[c]; k < start_[c + 1]; ++k) {
        const double d2 = distance2(p, edges_[k]);
        if (d2 < best2) best2 = d2, edge = edges_[k];
      }
    };
    for (int r = outside;; ++r) {
      // Ring r: the cells at Chebyshev distance r (those inside the grid).
      const int x0 = std::max(0, px - r), x1 = std::min(nx_ - 1, px + r);
      const int y0 = std::max(0, py - r + 1), y1 = std::min(ny_ - 1, py + r - 1);
      for (int y : {py - r, py + r}) {
        if (y < 0 || y >= ny_) continue;
        for (int x = x0; x <= x1; ++x) visit(x, y);
        if (r == 0) break;
      }
      for (int x : {px - r, px + r}) {
        if (r == 0 || x < 0 || x >= nx_) continue;
        for (int y = y0; y <= y1; ++y) visit(x, y);
      }
      // Everything not searched lies outside the square of rings 0..r around p's cell.
      const double margin = cell_ * std::min({fx - (px - r), px + r + 1 - fx, fy - (py - r), py + r + 1 - fy});
      if (best2 <= margin * margin || r > outside + nx_ + ny_) break;
    }
    // The edges outside the grid's box are no nearer than its border.
    const double border = std::max(0.0, -(lo_ - p).cwiseMax(p - hi_).maxCoeff());
    if (!far_.empty() && best2 > border * border)
      for (int e : far_) {
        const double d2 = distance2(p, e);
        if (d2 < best2) best2 = d2, edge = e;
      }
    return std::sqrt(best2);
  }

 private:
  int cellX(double x) const { return std::clamp(static_cast<int>((x - lo_.x()) / cell_), 0, nx_ - 1); }
  int cellY(double y) const { return std::clamp(static_cast<int>((y - lo_.y()) / cell_), 0, ny_ - 1); }

  const std::vector<Vec2>& poly_;
  Vec2 lo_, hi_;
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_, edges_;
  std::vector<int> far_;  // edges wholly outside the region
  std::vector<Vec2> direction_;
  std::vector<double> inverse_length2_;
};

}  // namespace

std::vector<double> distancesToCurve(const Curve& curve, const std::vector<Vec2>& points, double diagonal,
                                     double resolution) {
  if (points.empty()) return {};  // (before the curve's sampling: measureLeftOut calls with none on most strokes)
  std::vector<Vec2> poly;
  CurveSamples smp;
  for (const CurvePiece& piece : curve.pieces) {
    const LaSegment& seg = piece.segment;
    const double kmax = seg.maxAbsKappa();
    // (a chord strays from its arc by at most kappa h^2 / 8, and by at most h / 2 whatever
    // the curvature: a cusp's samples need be no closer than 2 resolution diagonal, where
    // the sagitta alone put 100,000 on each of a hostile stroke's cusps, seconds a measure)
    const double h = std::max(std::sqrt(8.0 * resolution * diagonal / std::max(kmax, 1e-300)), 2.0 * resolution * diagonal);
    const int n = ceilWithin(seg.length() / h, 7, 99999) + 1;
    smp.clear();
    seg.sample(n, smp, 0.0, sampleTolerance(seg, resolution * diagonal));
    poly.insert(poly.end(), smp.point.begin(), smp.point.end());
  }
  std::vector<double> out(points.size(), INFINITY);
  if (poly.size() < 2) {
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = poly.empty() ? INFINITY : (points[i] - poly[0]).norm();
    return out;
  }
  // (the grid where the points are, a margin of a tenth of the diagonal round them)
  Vec2 lo = points.front(), hi = points.front();
  for (const Vec2& q : points) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const Vec2 margin = Vec2::Constant(0.1 * diagonal);
  const EdgeGrid grid(poly, std::pair(lo - margin, hi + margin));
  // (points come in order along the stroke)
  int edge = 0;
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = grid.distanceAlong(points[i], kNeighbourEdges, edge);
  return out;
}

// (a segment that runs away between two points is far from every point's foot, so
// max_dev, measured from the points, cannot see it)
constexpr double kStrayStep = 2e-3;

namespace {

// The dense measure (strayFromPoints) against the grid of the stroke's polyline.
double denseStray(const Curve& curve, const EdgeGrid& grid, double diagonal) {
  std::vector<Vec2> samples;
  CurveSamples smp;
  for (const CurvePiece& piece : curve.pieces) {
    const int n = ceilWithin(piece.segment.length() / (kStrayStep * diagonal), 1, 99999) + 1;
    smp.clear();
    piece.segment.sample(n, smp, 0.0, sampleTolerance(piece.segment, kStrayStep * diagonal));
    samples.insert(samples.end(), smp.point.begin(), smp.point.end());
  }
  // (the first bound from as many edges either side as the points have per sample step)
  const int neighbours = kNeighbourEdges + 2 * grid.edges() / static_cast<int>(samples.size());
  double worst = 0.0;
  int edge = 0;
  for (const Vec2& q : samples) {
    // A sample more than a diagonal outside the points' box (the grid's) counts by its
    // distance to the box (a lower bound, and a curve run away): an exact search from
    // there visits every cell of the grid.
    const double outside = grid.outsideBox(q);
    worst = std::max(worst, outside > diagonal ? outside : grid.distanceAlong(q, neighbours, edge));
  }
  return worst;
}

// strayWithin against the same grid (limit > 0).
bool coarselyWithin(const Curve& curve, const EdgeGrid& grid, double diagonal, double limit) {
  // (both samplings place their samples within kSamplePrecision of kStrayStep: their
  // distances are off by at most that much each)
  const double slack = 5.0 * 2.0 * kSamplePrecision * kStrayStep * diagonal;
  int total = 0;
  for (const CurvePiece& piece : curve.pieces) total += ceilWithin(piece.segment.length() / limit, 1, 99999) + 1;
  const int neighbours = kNeighbourEdges + 2 * grid.edges() / total;
  CurveSamples smp;
  int edge = 0;
  for (const CurvePiece& piece : curve.pieces) {
    const LaSegment& seg = piece.segment;
    const int n = ceilWithin(seg.length() / limit, 1, 99999) + 1;
    const double h = seg.length() / (n - 1);
    smp.clear();
    seg.sample(n, smp, 0.0, sampleTolerance(seg, kStrayStep * diagonal));
    double before = 0.0;
    for (std::size_t i = 0; i < smp.size(); ++i) {
      if (grid.outsideBox(smp.point[i]) > limit) return false;
      const double d = grid.distanceAlong(smp.point[i], neighbours, edge);
      // (a point of the curve between two samples h apart along it lies within a / 2 + b / 2
      // of one of them, a + b = h: no further from the polyline than the mean of theirs
      // and h / 2)
      const double bound = i == 0 ? d : 0.5 * (before + d + h);
      if (bound + slack > limit) return false;
      before = d;
    }
  }
  return true;
}

}  // namespace

double strayFromPoints(const Curve& curve, std::vector<Vec2> points, double diagonal) {
  if (points.size() < 2 || curve.pieces.empty()) return 0.0;
  if (curve.closed) points.push_back(points.front());
  const EdgeGrid grid(points);
  return denseStray(curve, grid, diagonal);
}

bool strayWithin(const Curve& curve, std::vector<Vec2> points, double diagonal, double limit) {
  if (!(limit > 0.0)) return false;
  if (points.size() < 2 || curve.pieces.empty()) return true;
  if (curve.closed) points.push_back(points.front());
  const EdgeGrid grid(points);
  return coarselyWithin(curve, grid, diagonal, limit);
}

double strayBeyond(const Curve& curve, std::vector<Vec2> points, double diagonal, double limit) {
  if (points.size() < 2 || curve.pieces.empty()) return 0.0;
  if (curve.closed) points.push_back(points.front());
  const EdgeGrid grid(points);  // (one grid for both passes)
  if (limit > 0.0 && coarselyWithin(curve, grid, diagonal, limit)) return 0.0;
  const double stray = denseStray(curve, grid, diagonal);
  return stray > limit ? stray : 0.0;
}

namespace {

// A curvature change smaller than this (times 1 / diagonal) is no change: lacheck.py's
// extrema_dense threshold. (Its diagonal is the rebuilt curve's, ours the points'; the
// two differ by about the tolerance, which moves the threshold by a fraction of that.)
constexpr double kSmallestCurvatureChange = 1e-6;
// lacheck.py rebuilds every segment at this many equal steps of arc length.
constexpr int kCheckerSteps = 2000;
// A segment whose curvature changes by less than this fraction of its larger end value
// (or of 1 / diagonal, near zero) is an arc or a line: it has no trend. lacheck.py's
// value; its floor is 1 where ours is 1 / diagonal (a floor of 1 depends on the units).
constexpr double kFlatTrend = 1e-12;


// Walks the curvature in curve order as lacheck.py's extrema_dense does: a sample that
// differs from the anchor (the last sample that changed) by more than `eps` changes in
// that direction and becomes the anchor; a change against the one before is a reversal.
class ReversalCounter {
 public:
  explicit ReversalCounter(double eps) : eps_(eps) {}

  void add(double kappa) {
    if (!started_) {
      anchor_ = kappa, started_ = true;
      return;
    }
    if (std::abs(kappa - anchor_) <= eps_) return;
    const int direction = kappa > anchor_ ? 1 : -1;
    anchor_ = kappa;
    if (first_ == 0) first_ = direction;
    else if (direction != last_) ++reversals_;
    last_ = direction;
  }

  // The segment's curvature as lacheck.py's dense rebuild samples it, at kCheckerSteps + 1
  // points. The curvature of an LA segment is monotone and so is the step between samples
  // (|d kappa/ds| is a power of a linear function), so when both end steps exceed eps every
  // sample changes, and the two ends alone give the same directions and leave the same
  // anchor. Only a nearly flat segment is walked, and there only the samples that change
  // the direction or the anchor's value across a run matter: after a sample within eps of
  // the anchor, the next that changes is the first beyond it in the direction the
  // curvature runs; after one that changed, those whose step from the one before exceeds
  // eps all change the same way, the last of them leaving the anchor. Each is found by
  // steps doubling and bisection (the steps are monotone too).
  void addSegment(const LaSegment& seg) {
    const double step = seg.length() / kCheckerSteps;
    const double k0 = seg.kappaStart(), k1 = seg.kappaEnd();
    if (seg.isCircular() ||
        (std::abs(seg.kappa(step) - k0) > eps_ && std::abs(k1 - seg.kappa(seg.length() - step)) > eps_)) {
      add(k0);
      add(k1);
      return;
    }
    auto sample = [&](int i) { return seg.kappa(i * step); };
    const double direction = k1 > k0 ? 1.0 : -1.0;  // (equal ends: a circular segment, above)
    // The first sample from `from` on where `holds` (which, once true, stays true), or
    // kCheckerSteps.
    auto first = [&](int from, auto&& holds) {
      int no = from - 1, ahead = 1;
      while (no + ahead < kCheckerSteps && !holds(no + ahead)) no += ahead, ahead *= 2;
      int yes = std::min(no + ahead, kCheckerSteps);
      while (yes - no > 1) {
        const int middle = no + (yes - no) / 2;
        (holds(middle) ? yes : no) = middle;
      }
      return yes;
    };
    auto changes = [&](int i) { return direction * (sample(i) - anchor_) > eps_; };
    auto flat = [&](int i) { return std::abs(sample(i) - sample(i - 1)) <= eps_; };
    for (int i = 0; i < kCheckerSteps;) {
      const double kappa = sample(i);
      if (started_ && std::abs(kappa - anchor_) <= eps_) {
        i = first(i + 1, changes);
        continue;
      }
      add(kappa);
      const int run_end = first(i + 1, flat) - 1;  // (i: no run)
      if (run_end > i) add(sample(run_end));
      i = run_end + 1;
    }
    add(k1);
  }

  // The caller adds a closed curve's first sample again at the end; the change back to
  // the first direction counts too.
  int reversals(bool closed) const { return reversals_ + (closed && first_ != 0 && last_ != first_ ? 1 : 0); }

 private:
  double eps_;
  double anchor_ = 0.0;
  bool started_ = false;
  int first_ = 0, last_ = 0;  // directions of the first and the latest change
  int reversals_ = 0;
};

}  // namespace

int curvatureReversals(const Curve& curve, double diagonal) {
  ReversalCounter reversals(kSmallestCurvatureChange / diagonal);
  for (const CurvePiece& piece : curve.pieces) reversals.addSegment(piece.segment);
  if (curve.closed && !curve.pieces.empty()) reversals.add(curve.pieces[0].segment.kappaStart());
  return reversals.reversals(curve.closed);
}

int curvatureTrend(const LaSegment& s, double diagonal) {
  const double a = s.kappaStart(), b = s.kappaEnd();
  if (std::abs(b - a) < kFlatTrend * std::max({std::abs(a), std::abs(b), 1.0 / diagonal})) return 0;
  return b > a ? 1 : -1;
}

// Parts run from one corner to the next (an open curve's first part from its start); a
// closed curve without corners is one part whose seam counts too. Within a part, arcs
// and lines are skipped, so a plateau between a rise and a fall counts once; the joint
// named is the one after the last segment before the reversal that has a trend.
std::vector<std::vector<std::size_t>> extremumJoints(const Curve& curve, double diagonal) {
  const std::size_t n = curve.pieces.size();
  if (n == 0) return {};
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < n; ++i)
    if (curve.pieces[i].corner) starts.push_back(i);
  const bool seam = curve.closed && starts.empty();
  if (starts.empty() || (!curve.closed && starts.front() != 0)) starts.insert(starts.begin(), 0);
  std::vector<std::vector<std::size_t>> parts;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const std::size_t end = k + 1 < starts.size() ? starts[k + 1] : (curve.closed ? starts[0] + n : n);
    std::vector<std::size_t>& joints = parts.emplace_back();
    int first = 0, last = 0;
    std::size_t last_at = 0;
    for (std::size_t i = starts[k]; i < end; ++i) {
      const int t = curvatureTrend(curve.pieces[i % n].segment, diagonal);
      if (t == 0) continue;
      if (first == 0) first = t;
      else if (t != last) joints.push_back((last_at + 1) % n);
      last = t, last_at = i;
    }
    if (seam && first != 0 && last != first) joints.push_back(0);
  }
  return parts;
}

bool overExtremaCap(const Curve& curve, double diagonal, int cap) {
  if (cap < 0) return false;
  for (const std::vector<std::size_t>& joints : extremumJoints(curve, diagonal))
    if (joints.size() > static_cast<std::size_t>(cap)) return true;
  return false;
}

QualityFigures measureQuality(const Curve& curve, const std::vector<Vec2>& points) {
  QualityFigures q;
  q.diagonal = boundingBoxDiagonal(points);
  const double diag = q.diagonal > 0.0 ? q.diagonal : 1.0;
  q.segments = static_cast<int>(curve.pieces.size());
  const std::vector<double> d = distancesToCurve(curve, points, diag);
  double sum = 0.0;
  for (double v : d) {
    q.max_dev = std::max(q.max_dev, v);
    sum += v * v;
  }
  q.rms_dev = d.empty() ? 0.0 : std::sqrt(sum / d.size());

  const std::size_t n = curve.pieces.size();
  std::vector<int> trend;
  for (const CurvePiece& piece : curve.pieces) trend.push_back(curvatureTrend(piece.segment, diag));
  for (std::size_t j = 0; j < n; ++j) {
    if (curve.pieces[j].corner) ++q.corners;
    const bool has_joint_before = j > 0 || (curve.closed && n > 1);
    if (!has_joint_before) continue;
    const LaSegment& a = curve.pieces[(j + n - 1) % n].segment;
    const LaSegment& b = curve.pieces[j].segment;
    q.g0_gap = std::max(q.g0_gap, (a.end() - b.start()).norm() / diag);  // corners too: a corner is no break
    if (curve.pieces[j].corner) continue;
    q.g1_gap = std::max(q.g1_gap, std::abs(turnBetween(a, b)));
    q.g2_gap = std::max(q.g2_gap, relativeGap(a.kappaEnd(), b.kappaStart(), diag));
    const int ta = trend[(j + n - 1) % n], tb = trend[j];
    if (ta != 0 && tb != 0 && ta != tb) ++q.extrema;
  }
  for (const std::vector<std::size_t>& joints : extremumJoints(curve, diag))
    q.extrema_per_part.push_back(static_cast<int>(joints.size()));
  for (int count : q.extrema_per_part) q.max_extrema_per_part = std::max(q.max_extrema_per_part, count);

  for (const CurvePiece& piece : curve.pieces) q.max_abs_kappa = std::max(q.max_abs_kappa, piece.segment.maxAbsKappa());
  q.extrema_dense = curvatureReversals(curve, diag);
  q.min_radius = q.max_abs_kappa > 0.0 ? 1.0 / q.max_abs_kappa : INFINITY;
  // inflections: sign changes of curvature, also across corners (the shape inflects there too)
  auto sign = [](double k) { return k > 0 ? 1 : (k < 0 ? -1 : 0); };
  int last = 0;
  for (std::size_t j = 0; j < n; ++j) {
    for (double k : {curve.pieces[j].segment.kappaStart(), curve.pieces[j].segment.kappaEnd()}) {
      const int s = sign(k);
      if (s != 0 && last != 0 && s != last) ++q.inflections;
      if (s != 0) last = s;
    }
  }
  return q;
}

}  // namespace la
