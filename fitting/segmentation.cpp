#include "fitting/segmentation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/polynomial.h"

namespace la {
namespace {

constexpr int kTurningSamples = 64;  // per piece, for measuring and cutting its turning
// A piece is cut into at most this many by its turning (a spline gone wild turns 1e12 rad).
constexpr int kMaxPartsPerPiece = kTurningSamples;
constexpr int kRelocateSamples = 10; // per side, for the parabola through an extremum

struct Critical {
  double t;
  double kappa;
};

// Removes noise extrema from `ext` (in parameter order). For an open curve the ends
// bound the sequence, and an extremum next to an end may go alone; for a closed curve
// the sequence is cyclic and extrema go in pairs.
void simplify(std::vector<Critical>& ext, bool closed, double end0, double end1, double threshold, int cap) {
  while (!ext.empty()) {
    const int n = static_cast<int>(ext.size());
    double best = INFINITY;
    int best_i = -1;
    bool single = false;
    const int pairs = closed ? (n >= 2 ? n : 0) : n - 1;
    for (int i = 0; i < pairs; ++i) {
      const double d = std::abs(ext[i].kappa - ext[(i + 1) % n].kappa);
      if (d < best) best = d, best_i = i, single = false;
    }
    if (!closed) {
      const double d0 = std::abs(ext.front().kappa - end0), d1 = std::abs(ext.back().kappa - end1);
      if (d0 < best) best = d0, best_i = 0, single = true;
      if (d1 < best) best = d1, best_i = n - 1, single = true;
    }
    const bool over_cap = cap >= 0 && n > cap;
    if (best_i < 0 || (best >= threshold && !over_cap)) break;
    if (single) {
      ext.erase(ext.begin() + best_i);
    } else if (best_i + 1 < n) {
      ext.erase(ext.begin() + best_i, ext.begin() + best_i + 2);
    } else {  // the pair wraps: last and first
      ext.pop_back();
      ext.erase(ext.begin());
    }
  }
}

// A cubic spline's curvature has a kink at every knot, so its extrema tend to sit on
// knots rather than where the stroke's curvature peaks. Each kept extremum is moved to
// the vertex of the least-squares parabola through the curvature sampled over a window
// reaching a third of the way to its neighbours (kept inside the window).
void relocateExtrema(const CubicBSpline& s, std::vector<Critical>& ext, bool closed, double t_begin, double t_end) {
  const double period = s.tMax() - s.tMin();
  const std::size_t n = ext.size();
  std::vector<Critical> moved = ext;
  for (std::size_t i = 0; i < n; ++i) {
    double left = (i > 0) ? ext[i].t - ext[i - 1].t : (closed && n > 1 ? ext[i].t - ext[n - 1].t + period : ext[i].t - t_begin);
    double right = (i + 1 < n) ? ext[i + 1].t - ext[i].t : (closed && n > 1 ? ext[0].t + period - ext[i].t : t_end - ext[i].t);
    if (closed && n == 1) left = right = 0.5 * period;
    const double half = std::min(left, right) / 3.0;
    if (!(half > 0.0)) continue;
    // least squares kappa ~ c0 + c1 x + c2 x^2, x in [-1, 1]
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    Eigen::Vector3d atb = Eigen::Vector3d::Zero();
    for (int k = -kRelocateSamples; k <= kRelocateSamples; ++k) {
      const double x = static_cast<double>(k) / kRelocateSamples;
      const Eigen::Vector3d row(1.0, x, x * x);
      ata += row * row.transpose();
      atb += row * s.curvature(s.wrap(ext[i].t + x * half));
    }
    const Eigen::Vector3d c = ata.ldlt().solve(atb);
    if (!(std::abs(c[2]) > 0.0)) continue;
    const double x = std::clamp(-c[1] / (2.0 * c[2]), -1.0, 1.0);
    moved[i].t = s.wrap(ext[i].t + x * half);
    moved[i].kappa = s.curvature(moved[i].t);
  }
  ext = std::move(moved);
  if (closed) std::sort(ext.begin(), ext.end(), [](const Critical& a, const Critical& b) { return a.t < b.t; });
}

// Turning of the spline between t0 < t1, from sampled tangent angles.
std::vector<double> cumulativeTurning(const CubicBSpline& s, double t0, double t1, std::vector<double>& ts) {
  ts.resize(kTurningSamples + 1);
  std::vector<double> turn(kTurningSamples + 1, 0.0);
  double prev = splineTangentAngle(s, t0);
  for (int k = 0; k <= kTurningSamples; ++k) {
    ts[k] = t0 + (t1 - t0) * k / kTurningSamples;
    const double a = splineTangentAngle(s, ts[k]);
    if (k > 0) turn[k] = turn[k - 1] + wrapAngle(a - prev);
    prev = a;
  }
  return turn;
}

}  // namespace

const char* toString(SplitKind kind) {
  switch (kind) {
    case SplitKind::kEnd: return "end";
    case SplitKind::kInflection: return "inflection";
    case SplitKind::kExtremum: return "extremum";
    case SplitKind::kTurning: return "turning";
  }
  return "unknown";
}

double splineTangentAngle(const CubicBSpline& spline, double t) { return angleOf(spline.evaluate(t, 1)); }

Segmentation segmentSpline(const CubicBSpline& spline, const SegmentationOptions& options) {
  return segmentSpline(spline, spline.tMin(), spline.tMax(), options);
}

Segmentation segmentSpline(const CubicBSpline& spline, double t_begin, double t_end, const SegmentationOptions& options) {
  Segmentation out;
  out.closed = spline.isPeriodic();
  if (out.closed) {
    t_begin = spline.tMin();
    t_end = spline.tMax();
  }
  const double period = spline.tMax() - spline.tMin();
  const auto& knots = spline.knots();
  std::vector<Critical> extrema;
  std::vector<double> zeros;
  double g_end_prev = NAN;  // d kappa/dt numerator at the end of the previous span
  const int first_span = CubicBSpline::kDegree, last_span = static_cast<int>(spline.control().size()) - 1;
  double g_first_start = NAN;
  for (int i = first_span; i <= last_span; ++i) {
    const double h = knots[i + 1] - knots[i];
    if (!(h > 0.0)) continue;
    const auto c = spline.spanPolynomial(i);
    const Polynomial x{c[0].x(), c[1].x(), c[2].x(), c[3].x()}, y{c[0].y(), c[1].y(), c[2].y(), c[3].y()};
    const Polynomial xp = derivative(x), yp = derivative(y), xpp = derivative(xp), ypp = derivative(yp);
    const Polynomial xppp = derivative(xpp), yppp = derivative(ypp);
    const Polynomial cr = xp * ypp + (-1.0) * (yp * xpp);
    const Polynomial crp = xp * yppp + (-1.0) * (yp * xppp);
    const Polynomial g = crp * (xp * xp + yp * yp) + (-3.0) * (cr * (xp * xpp + yp * ypp));
    for (double r : realRoots(cr, 0.0, h)) zeros.push_back(knots[i] + r);
    for (double r : realRoots(g, 0.0, h)) extrema.push_back({knots[i] + r, 0.0});
    // an extremum on the knot at the start of this span: d kappa/dt changes sign across it
    const double g0 = evaluate(g, 0.0);
    if (std::isnan(g_first_start)) g_first_start = g0;
    if (!std::isnan(g_end_prev) && g0 != 0.0 && (g0 < 0.0) != (g_end_prev < 0.0)) extrema.push_back({knots[i], 0.0});
    g_end_prev = evaluate(g, h);
  }
  if (out.closed && g_first_start != 0.0 && (g_first_start < 0.0) != (g_end_prev < 0.0))
    extrema.push_back({spline.tMin(), 0.0});
  std::sort(extrema.begin(), extrema.end(), [](const Critical& a, const Critical& b) { return a.t < b.t; });
  extrema.erase(std::unique(extrema.begin(), extrema.end(),
                            [&](const Critical& a, const Critical& b) { return b.t - a.t <= 1e-12 * period; }),
                extrema.end());
  std::sort(zeros.begin(), zeros.end());
  if (!out.closed) {  // only what lies strictly inside the fitted range
    std::erase_if(extrema, [&](const Critical& c) { return c.t <= t_begin || c.t >= t_end; });
    std::erase_if(zeros, [&](double z) { return z <= t_begin || z >= t_end; });
  }
  double kappa_max = 0.0;
  for (Critical& e : extrema) {
    e.kappa = spline.curvature(e.t);
    kappa_max = std::max(kappa_max, std::abs(e.kappa));
  }
  const double end0 = spline.curvature(t_begin), end1 = spline.curvature(t_end);
  kappa_max = std::max({kappa_max, std::abs(end0), std::abs(end1)});

  simplify(extrema, out.closed, end0, end1, options.significance * kappa_max, options.max_extrema);
  relocateExtrema(spline, extrema, out.closed, t_begin, t_end);

  // Boundaries of monotone stretches, then one inflection between two of opposite sign.
  std::vector<Critical> bounds;
  if (!out.closed) bounds.push_back({t_begin, end0});
  bounds.insert(bounds.end(), extrema.begin(), extrema.end());
  if (!out.closed) bounds.push_back({t_end, end1});
  std::vector<SplitPoint> splits;
  if (!out.closed) splits.push_back({t_begin, SplitKind::kEnd, end0});
  const std::size_t stretches = out.closed ? bounds.size() : bounds.size() - 1;
  for (std::size_t j = 0; j < stretches; ++j) {
    const Critical& a = bounds[j];
    const Critical& b = bounds[(j + 1) % bounds.size()];
    if (out.closed || j > 0) splits.push_back({a.t, SplitKind::kExtremum, a.kappa});
    if ((a.kappa < 0.0) == (b.kappa < 0.0)) continue;
    std::vector<double> between;
    for (double z : zeros) {
      const bool inside = (b.t > a.t) ? (z > a.t && z < b.t) : (z > a.t || z < b.t);  // wraps when closed
      if (inside) between.push_back(z);
    }
    if (b.t <= a.t) std::stable_partition(between.begin(), between.end(), [&](double z) { return z > a.t; });
    if (!between.empty()) splits.push_back({between[between.size() / 2], SplitKind::kInflection, 0.0});
  }
  if (!out.closed) splits.push_back({t_end, SplitKind::kEnd, end1});
  if (out.closed && splits.empty()) splits.push_back({spline.tMin(), SplitKind::kTurning, spline.curvature(spline.tMin())});

  // Cut pieces that turn too much into equal-turning parts.
  std::vector<SplitPoint> result;
  const std::size_t pieces = out.closed ? splits.size() : splits.size() - 1;
  std::vector<double> ts;
  for (std::size_t j = 0; j < pieces; ++j) {
    const SplitPoint& a = splits[j];
    const SplitPoint& b = splits[(j + 1) % splits.size()];
    result.push_back(a);
    const double t1 = (b.t > a.t) ? b.t : b.t + period;  // closed: through the seam
    const std::vector<double> turn = cumulativeTurning(spline, a.t, t1, ts);
    const int parts = ceilWithin(std::abs(turn.back()) / options.max_piece_turning, 0, kMaxPartsPerPiece);
    for (int k = 1; k < parts; ++k) {
      const double want = turn.back() * k / parts;
      int m = 1;
      while (m < kTurningSamples && std::abs(turn[m]) < std::abs(want)) ++m;
      const double f = (want - turn[m - 1]) / (turn[m] - turn[m - 1]);
      const double t = spline.wrap(ts[m - 1] + f * (ts[m] - ts[m - 1]));
      result.push_back({t, SplitKind::kTurning, spline.curvature(t)});
    }
  }
  if (!out.closed) result.push_back(splits.back());
  out.splits = std::move(result);
  return out;
}

}  // namespace la
