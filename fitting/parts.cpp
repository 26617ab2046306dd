#include "fitting/parts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fitting/quality.h"

namespace la {
namespace {

// A step longer than this many median steps is a gap the fit fills (fillGaps).
constexpr double kGapSteps = 10.0;
// Resolution of maxDeviationOf (relative to the diagonal; 500 times below the default
// tolerance; the reported figures use 1e-6).
constexpr double kDeviationResolution = 1e-5;

// Points along every step of `p` (and the closing step of a closed part) longer than
// kGapSteps times `spacing`, that far apart. A long step is a straight edge the data
// do not sample (a font outline's closing stem, a polygon's side) or samples the
// digitizer lost: the points' own polyline is the best guess there, and without points
// along it a fit may loop through the gap. Fits use these; quality is measured on the
// data alone.
std::vector<Vec2> fillGaps(const std::vector<Vec2>& p, bool closed, double spacing) {
  std::vector<Vec2> out;
  const std::size_t steps = closed ? p.size() : p.size() - 1;
  for (std::size_t i = 0; i < p.size(); ++i) {
    out.push_back(p[i]);
    if (i >= steps) continue;
    const Vec2 a = p[i], b = p[(i + 1) % p.size()];
    const double length = (b - a).norm();
    if (!(length > kGapSteps * spacing)) continue;
    // (at most as many points as the part has: a gap of 1e11 steps, one coordinate
    // mistyped, is filled more coarsely, not with 1e11 points)
    const double most = std::max(kGapSteps, static_cast<double>(p.size()));
    const int pieces = ceilWithin(std::min(length / spacing, most), 1, std::numeric_limits<int>::max());
    for (int k = 1; k < pieces; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / pieces));
  }
  return out;
}

}  // namespace

std::vector<Part> splitAtCorners(const CleanStroke& c) {
  const auto& p = c.points;
  const double spacing = medianStep(p);
  if (c.corners.empty()) return {Part{fillGaps(p, c.closed, spacing), c.closed, false}};
  std::vector<std::size_t> cuts = c.corners;
  if (!c.closed) {
    cuts.insert(cuts.begin(), 0);
    cuts.push_back(p.size() - 1);
  } else {
    cuts.push_back(p.size());  // back to the start (a corner at index 0)
  }
  std::vector<Part> parts;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    Part part;
    for (std::size_t i = cuts[k]; i <= cuts[k + 1]; ++i) part.points.push_back(p[i % p.size()]);
    part.points = fillGaps(part.points, false, spacing);
    part.starts_at_corner = c.closed || k > 0;
    part.ends_at_corner = c.closed || k + 2 < cuts.size();
    parts.push_back(std::move(part));
  }
  return parts;
}

bool withinChord(const std::vector<Vec2>& pts, double tol) {
  const Vec2 a = pts.front(), b = pts.back();
  const Vec2 d = b - a;
  const double len = d.norm();
  if (!(len > 0.0)) return false;
  for (const Vec2& p : pts) {
    const double along = (p - a).dot(d) / len;
    if (along < -tol || along > len + tol || std::abs(cross(d, p - a)) / len > tol) return false;
  }
  return true;
}

std::vector<std::size_t> turnsAlongLine(const std::vector<Vec2>& points, double tolerance) {
  // Positions along the line through the two points furthest apart along x or y.
  auto by = [](int axis) { return [axis](const Vec2& a, const Vec2& b) { return a[axis] < b[axis]; }; };
  const auto [lo_x, hi_x] = std::minmax_element(points.begin(), points.end(), by(0));
  const auto [lo_y, hi_y] = std::minmax_element(points.begin(), points.end(), by(1));
  const Vec2 span = (*hi_x - *lo_x).norm() >= (*hi_y - *lo_y).norm() ? Vec2(*hi_x - *lo_x) : Vec2(*hi_y - *lo_y);
  const Vec2 direction = span.normalized();
  auto along = [&](std::size_t i) { return direction.dot(points[i] - points.front()); };
  // The furthest point of each run in one direction, once the stroke has come back from
  // it by more than the tolerance.
  std::vector<std::size_t> turns = {0};
  std::size_t extreme = 0;
  double heading = 0.0;  // +1 or -1 along `direction` once known
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double step = along(i) - along(extreme);
    if (heading == 0.0) {
      if (std::abs(step) > tolerance) heading = step > 0.0 ? 1.0 : -1.0, extreme = i;
    } else if (step * heading > 0.0) {
      extreme = i;
    } else if (-step * heading > tolerance) {
      turns.push_back(extreme);
      heading = -heading;
      extreme = i;
    }
  }
  if (turns.back() != points.size() - 1) turns.push_back(points.size() - 1);
  return turns;
}

double maxDeviationOf(const std::vector<LaSegment>& segments, const std::vector<Vec2>& points, double diag) {
  double worst = 0.0;
  for (double d : distancesToCurve(curveOf(segments), points, diag, kDeviationResolution)) worst = std::max(worst, d);
  return worst;
}

}  // namespace la
