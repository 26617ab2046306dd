#include "fitting/model_selection.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>

#include "fitting/quality.h"

namespace la {
namespace {

// A segment as the edits see it: its law, its signed turning and, where it starts at a
// corner, the tangent's turn there (NaN elsewhere). A chain is rebuilt from its start pose
// and these (LaSegment positions), so an edit changes only what it names.
struct Piece {
  double alpha, kappa0, kappa1, turning;
  double corner_turn = NAN;
  double line_length = NAN;  // a straight line's (it has no turning to set it)
  bool atCorner() const { return !std::isnan(corner_turn); }
  bool line() const { return !std::isnan(line_length); }
};

// Alpha for a segment that gets a zero-curvature end (DESIGN.md section 2: alpha < 0).
constexpr double kZeroEndAlpha = -1.0;
// An edited piece's new free end or joint starts at this fraction of its neighbour's
// curvature (the fit moves it).
constexpr double kNewKappaFraction = 0.5;
// A split cuts at the worst point's foot, kept this far from the segment's ends (or
// SelectionOptions::split_margin, where less).
constexpr double kSplitMargin = 0.15;
// A segment beside a corner shorter than this fraction of its neighbour in its part is a
// collapse candidate (a hook).
constexpr double kHookRatio = 0.2;
// A split is kept if it brings the worst point within the tolerance or this factor closer.
constexpr double kMarkedGain = 0.99;
// A trial simplification whose fit stops at its iteration limit further than this many
// times the distance it must keep is not given the patience of longer fits.
constexpr double kHopelessTrial = 2.0;
// ... nor more than kAbandonAfter steps where its points are still further than
// kAbandonedTrial times that distance then (ChainFitOptions::abandon; a window's
// fit in refitNearby too). Of the shared data's 443 trial fits, the 68 so far off after
// 3 steps took 8% of the trials' time, and one of them ended within its bound; after 2
// steps, or at 10 times, more did (data_benchmark: 2 and 4 curves changed, the latter
// with 6 extrema more, where this changes one, a $1 star's: 11 -> 10 segments).
constexpr double kAbandonedTrial = 20.0;
constexpr int kAbandonAfter = 3;
// ... and one whose segments near the edit, fitted alone (selectChain's refitNearby),
// stay further than this many times that distance is not fitted whole (at 2 a drawn
// star's model selection took another path and missed its tolerance 1.8 times: a
// window's fit stops at its own iteration limit, short of its optimum).
constexpr double kHopelessWindow = 4.0;

// A segment is tried as a circular arc (selectChain) only where, levelled alone, it would
// move no further off than this many tolerances (|kappa1 - kappa0| L^2 / 8) between two
// extrema, or this many at its part's end, which the fit across corners lets slide. Of
// the 200 tried on the shared data without this screen, 117 were further, and 3 of them
// were kept; the 83 nearer gave 16 arcs.
constexpr double kArcStrayBetween = 1.0, kArcStrayAtEnd = 4.0;

// Segments merged for the cap on extrema may turn this much (radians): a spiral's
// monotone curvature is one LA segment however far it turns.
constexpr double kCapMaxTurning = 8.0 * std::numbers::pi;

// The points whose feet are on segments i .. i + count - 1.
std::vector<Vec2> pointsOn(const std::vector<Vec2>& points, const std::vector<ChainFoot>& feet, std::size_t i,
                           std::size_t count) {
  std::vector<Vec2> on;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (feet[k].segment >= i && feet[k].segment < i + count) on.push_back(points[k]);
  return on;
}

// The largest distance of the points whose feet are on segments i and i + 1 from those
// points' least-squares line (lineDeviation). A bump (selectChain) whose points stray
// further than the tolerance is what they need: its line's trial would hardly keep the
// tolerance, and such trials fail at a cost.
double spreadAboutLine(const std::vector<Vec2>& points, const std::vector<ChainFoot>& feet, std::size_t i) {
  return lineDeviation(pointsOn(points, feet, i, 2));
}

// Whether corner c is at either end of the segments i .. i + count - 1 of a chain of n.
bool endsSide(const ChainCorner& c, std::size_t i, std::size_t count, std::size_t n) {
  return c.joint == i || c.joint == (i + count) % n;
}

// Whether side i .. i + count - 1 (straightenSide) may be a line: its points lie within
// the tolerance of their least-squares line, and that line meets the tangent of the
// segment beyond each corner within the tolerance of the corner's own point. (A straight
// side's corner runs on past a rounded tip; where the trials were left to find out, half
// of them failed so, each a fit of the whole chain. And a corner that wanders along the
// stroke leaves the points of one part beside the curve of the next.)
bool sideLineFits(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points,
                  const std::vector<ChainFoot>& feet, const std::vector<ChainCorner>& corners, std::size_t i,
                  std::size_t count, double tolerance) {
  const std::vector<Vec2> own = pointsOn(points, feet, i, count);
  if (own.size() < 2) return false;
  const FittedLine line = leastSquaresLine(own);
  if (line.deviation > tolerance) return false;
  const std::size_t n = chain.size();
  for (const ChainCorner& c : corners) {
    if (!endsSide(c, i, count, n)) continue;
    // (the corner where the line crosses the other side's tangent line there)
    const LaSegment& other = c.joint == i ? chain[(i + n - 1) % n] : chain[c.joint];
    const Vec2 at = chain[c.joint].start(), along = unitVector(c.joint == i ? other.theta(other.length()) : other.theta0());
    const double sine = cross(line.direction, along);
    if (std::abs(sine) < 1e-9) return false;
    const Vec2 corner = line.point + line.direction * (cross(at - line.point, along) / sine);
    if ((corner - points[c.point]).norm() > tolerance) return false;
  }
  return true;
}

// A side's line keeps its corners within the tolerance of their own points (as above, of
// the fitted chain).
bool sideCornersHold(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points,
                     const std::vector<ChainCorner>& corners, std::size_t line, double tolerance) {
  for (const ChainCorner& c : corners)
    if (endsSide(c, line, 1, chain.size()) && (chain[c.joint].start() - points[c.point]).norm() > tolerance)
      return false;
  return true;
}

// The chain as a curve, its corners marked.
Curve curveOf(const std::vector<LaSegment>& chain, const std::vector<ChainCorner>& corners, bool closed) {
  Curve c = curveOf(chain, closed);
  for (const ChainCorner& k : corners) c.pieces[k.joint].corner = true;
  return c;
}

std::vector<Piece> piecesOf(const std::vector<LaSegment>& chain, const std::vector<ChainCorner>& corners) {
  std::vector<Piece> out;
  for (const LaSegment& s : chain) {
    out.push_back({std::isfinite(s.alpha()) ? s.alpha() : kZeroEndAlpha, s.kappaStart(), s.kappaEnd(), s.turning()});
    if (s.isStraight()) out.back().line_length = s.length();
  }
  for (const ChainCorner& c : corners)
    out[c.joint].corner_turn = c.joint == 0 ? 0.0 : turnBetween(chain[c.joint - 1], chain[c.joint]);
  return out;
}

// The corners of `pieces` (in order, as `corners` had them, at the pieces now starting there).
std::vector<ChainCorner> cornersOf(const std::vector<Piece>& pieces, const std::vector<ChainCorner>& corners) {
  std::vector<ChainCorner> out;
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (pieces[i].atCorner()) out.push_back({i, corners[out.size()].point});
  return out;
}

double signOf(const Piece& p) { return p.turning < 0.0 ? -1.0 : 1.0; }

// A piece with a zero-curvature end needs alpha < 0: at most kZeroEndAlpha then.
void fixZeroEnd(Piece& p) {
  if (p.kappa0 == 0.0 || p.kappa1 == 0.0) p.alpha = std::min(p.alpha, kZeroEndAlpha);
}

// The chain from a start pose and pieces; nullopt if a piece is not an LA segment
// (curvatures of opposite signs, a zero end with alpha >= 0, no turning).
std::optional<std::vector<LaSegment>> rebuild(Vec2 start, double theta, const std::vector<Piece>& pieces) {
  std::vector<LaSegment> chain;
  try {
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const Piece& p = pieces[i];
      if (i > 0 && p.atCorner()) theta += p.corner_turn;
      chain.push_back(p.line() ? LaSegment::arc(p.line_length, start, theta, 0.0)
                               : LaSegment::withTurning(p.alpha, p.turning, start, theta, p.kappa0, p.kappa1));
      start = chain.back().end();
      theta = chain.back().theta(chain.back().length());
    }
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
  return chain;
}

// A chain edit: the new pieces, the start pose they hang from, and where the old feet go.
struct Edit {
  std::vector<Piece> pieces;
  Vec2 start;
  double theta;
  std::vector<ChainFoot> feet;
};

// The chain as it is, to be edited.
Edit unedited(const std::vector<LaSegment>& chain, const std::vector<ChainFoot>& feet,
              const std::vector<ChainCorner>& corners) {
  return {piecesOf(chain, corners), chain.front().start(), chain.front().theta0(), feet};
}

// The feet of a segment i cut at fraction u onto its two parts (and those after, one on).
void splitFeet(std::vector<ChainFoot>& feet, std::size_t i, double u) {
  for (ChainFoot& f : feet) {
    if (f.segment > i) ++f.segment;
    else if (f.segment == i && f.u >= u) f = {i + 1, (f.u - u) / (1.0 - u)};
    else if (f.segment == i) f.u /= u;
  }
}

// Bends line i by curvature `bend` (towards the points it misses): into one arc where
// its tangent is free at both ends (a chain's end, a corner), else into two parts
// meeting at that curvature at fraction u (a line's neighbours meet it at zero
// curvature, and an LA segment has at most one zero end). The bent line starts turned
// back by half its turning where it can, so that it ends near the line's end.
std::optional<Edit> bendLine(const std::vector<LaSegment>& chain, const std::vector<ChainFoot>& feet,
                             const std::vector<ChainCorner>& corners, std::size_t i, double u, double bend,
                             bool closed) {
  if (bend == 0.0) return std::nullopt;
  Edit e = unedited(chain, feet, corners);
  const std::size_t n = chain.size();
  const double length = chain[i].length(), half = 0.5 * bend * length;
  const bool free_start = e.pieces[i].atCorner() || (i == 0 && !closed);
  const bool free_end = i + 1 < n ? e.pieces[i + 1].atCorner() : !closed;
  if (free_start) (i == 0 ? e.theta : e.pieces[i].corner_turn) -= half;
  if (i + 1 < n && free_end) e.pieces[i + 1].corner_turn -= half;
  if (free_start && free_end) {
    e.pieces[i] = {kZeroEndAlpha, bend, bend, bend * length, e.pieces[i].corner_turn};
    return e;
  }
  e.pieces[i] = {kZeroEndAlpha, bend, bend, bend * u * length, e.pieces[i].corner_turn};
  e.pieces.insert(e.pieces.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                  Piece{kZeroEndAlpha, bend, bend, bend * (1.0 - u) * length});
  splitFeet(e.feet, i, u);
  return e;
}

// Pieces i .. i + count - 1 of `e` (those of `chain`) become one line of `length`, which
// keeps piece i's corner turn; their feet go onto it in proportion to the arc length.
void replaceByLine(Edit& e, const std::vector<LaSegment>& chain, std::size_t i, std::size_t count, double length) {
  std::vector<double> offset = {0.0};  // of each replaced segment along them
  for (std::size_t k = i; k < i + count; ++k) offset.push_back(offset.back() + chain[k].length());
  e.pieces[i] = {kZeroEndAlpha, 0.0, 0.0, 0.0, e.pieces[i].corner_turn, length};
  e.pieces.erase(e.pieces.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                 e.pieces.begin() + static_cast<std::ptrdiff_t>(i + count));
  for (ChainFoot& f : e.feet) {
    if (f.segment >= i + count) f.segment -= count - 1;
    else if (f.segment >= i) f = {i, (offset[f.segment - i] + f.u * chain[f.segment].length()) / offset.back()};
  }
}

// Replaces segments i .. i + count - 1 (nearly straight, between zero-curvature joints
// or the chain's ends) by one line of their length, along the first one's start
// tangent. Nullopt across a corner.
std::optional<Edit> straighten(const std::vector<LaSegment>& chain, const std::vector<ChainFoot>& feet,
                               const std::vector<ChainCorner>& corners, std::size_t i, std::size_t count) {
  Edit e = unedited(chain, feet, corners);
  double length = 0.0;
  for (std::size_t k = i; k < i + count; ++k) {
    if (k > i && e.pieces[k].atCorner()) return std::nullopt;
    length += chain[k].length();
  }
  replaceByLine(e, chain, i, count, length);
  return e;
}

// Replaces a side (segments i .. i + count - 1 between two corners, or a corner and the
// open chain's end) by one line along its chord. The corners take the change of tangent,
// so the rest of the chain stays where it is (straighten's line along the first
// segment's tangent swings the rest of the chain by the side's turning: a side turning
// tenths of a radian came back from its refit tolerances off).
std::optional<Edit> straightenSide(const std::vector<LaSegment>& chain, const std::vector<ChainFoot>& feet,
                                   const std::vector<ChainCorner>& corners, std::size_t i, std::size_t count) {
  Edit e = unedited(chain, feet, corners);
  const std::size_t j = i + count;
  const LaSegment& last = chain[j - 1];
  const Vec2 from = chain[i].start(), to = last.end();
  if (!((to - from).norm() > 0.0)) return std::nullopt;
  const double chord = angleOf(to - from);
  const double onto = wrapAngle(chord - chain[i].theta0());
  if (i == 0) e.theta += onto;
  else e.pieces[i].corner_turn = wrapAngle(e.pieces[i].corner_turn + onto);
  if (j < chain.size()) e.pieces[j].corner_turn = wrapAngle(e.pieces[j].corner_turn + last.theta(last.length()) - chord);
  replaceByLine(e, chain, i, count, (to - from).norm());
  return e;
}

// Cuts segment i at fraction u (its two parts: the same law).
Edit split(const std::vector<LaSegment>& chain, const std::vector<ChainFoot>& feet,
           const std::vector<ChainCorner>& corners, std::size_t i, double u) {
  Edit e = unedited(chain, feet, corners);
  const LaSegment& s = chain[i];
  const double at = u * s.length(), kappa = s.kappa(at), turn = s.theta(at) - s.theta0();
  const Piece old = e.pieces[i];
  e.pieces[i] = {old.alpha, old.kappa0, kappa, turn, old.corner_turn};
  e.pieces.insert(e.pieces.begin() + static_cast<std::ptrdiff_t>(i) + 1, Piece{old.alpha, kappa, old.kappa1, old.turning - turn});
  splitFeet(e.feet, i, u);
  return e;
}

// Merges the segments before and after joint j (1 <= j < n; a closed chain's joint 0 is
// not merged, its seam stays, nor is a corner). Nullopt if they cannot be one LA segment.
std::optional<Edit> merge(const std::vector<LaSegment>& chain, const std::vector<ChainFoot>& feet,
                          const std::vector<ChainCorner>& corners, std::size_t j, double max_turning) {
  Edit e = unedited(chain, feet, corners);
  const Piece a = e.pieces[j - 1], b = e.pieces[j];
  if (b.atCorner()) return std::nullopt;
  if (signOf(a) != signOf(b) || a.kappa1 == 0.0) return std::nullopt;  // an inflection: no single law
  if (std::abs(a.turning + b.turning) > max_turning) return std::nullopt;
  const double la = chain[j - 1].length(), lb = chain[j].length();
  e.pieces[j - 1] = {(la * a.alpha + lb * b.alpha) / (la + lb), a.kappa0, b.kappa1, a.turning + b.turning, a.corner_turn};
  fixZeroEnd(e.pieces[j - 1]);
  e.pieces.erase(e.pieces.begin() + static_cast<std::ptrdiff_t>(j));
  for (ChainFoot& f : e.feet) {
    if (f.segment == j - 1) f.u = f.u * la / (la + lb);
    else if (f.segment == j) f = {j - 1, (la + f.u * lb) / (la + lb)};
    else if (f.segment > j) --f.segment;
  }
  return e;
}

// Removes segment i: its neighbours meet at one joint, an inflection if they turn
// opposite ways, else a curvature extremum; at an open end its neighbour reaches the end.
// Beside a corner (a hook left where a part was pinned to a corner sample on the other
// side's stroke), the corner takes its turning and its neighbour in its part reaches the
// corner; the only segment of a part stays.
// With count 2, segments i and i + 1 go together, between their neighbours (a spike:
// two stubs between inflections, 0 -> kappa -> 0, of which neither can go alone, for
// the other would be left with two zero ends).
std::optional<Edit> collapse(const std::vector<LaSegment>& chain, const std::vector<ChainFoot>& feet,
                             const std::vector<ChainCorner>& corners, std::size_t i, bool closed,
                             std::size_t count = 1) {
  const std::size_t n = chain.size();
  if (n < (closed ? 4u : 2u) + count - 1) return std::nullopt;
  Edit e = unedited(chain, feet, corners);
  Piece gone = e.pieces[i];
  if (count == 2) {
    if (i == 0 || i + 2 >= n || gone.atCorner() || e.pieces[i + 1].atCorner() || e.pieces[i + 2].atCorner())
      return std::nullopt;  // (interior only)
    gone.kappa1 = e.pieces[i + 1].kappa1;
    gone.turning += e.pieces[i + 1].turning;
  }
  const bool open_end = !closed && (i == 0 || i + 1 == n);
  const bool corner_before = gone.atCorner();
  const bool corner_after = i + 1 < n ? e.pieces[i + 1].atCorner() : closed && e.pieces[0].atCorner();
  if (corner_before || corner_after) {
    if ((corner_before && corner_after) || open_end) return std::nullopt;  // (a part's only segment)
    // The neighbour in its part grows by the hook's length (at its curvature there), so
    // that it reaches the corner; the corner turns by the rest of the hook's turning.
    Piece& next = e.pieces[(i + 1) % n];
    Piece& neighbour = corner_before ? next : e.pieces[i - 1];
    const double grown = (corner_before ? neighbour.kappa0 : neighbour.kappa1) * chain[i].length();
    neighbour.turning += grown;
    next.corner_turn = (corner_before ? gone.corner_turn : next.corner_turn) + gone.turning - grown;
  } else if (open_end) {
    // An end sliver: the neighbour takes its place up to the stroke's end.
    Piece& p = e.pieces[i == 0 ? 1 : n - 2];
    double& free_end = i == 0 ? p.kappa0 : p.kappa1;
    if (free_end == 0.0 || (free_end < 0.0) != (signOf(p) < 0.0))
      free_end = signOf(p) * kNewKappaFraction * std::abs(i == 0 ? p.kappa1 : p.kappa0);
    if (signOf(gone) == signOf(p)) p.turning += gone.turning;
  } else {
    const std::size_t before = (i + n - 1) % n, after = (i + count) % n;
    Piece& a = e.pieces[before];
    Piece& b = e.pieces[after];
    double kappa = 0.0;
    if (signOf(a) == signOf(b)) {
      // (the sliver's own curvature where it has one of its neighbours' sign: the joint
      // may be a maximum as well as a minimum)
      const double ka = std::abs(a.kappa0), kb = std::abs(b.kappa1);
      const double own = std::sqrt(std::abs(gone.kappa0 * gone.kappa1));
      kappa = signOf(a) * (own > 0.0 && signOf(gone) == signOf(a) ? own
                           : kNewKappaFraction * (ka > 0.0 && kb > 0.0 ? std::min(ka, kb) : std::max(ka, kb)));
    }
    a.kappa1 = b.kappa0 = kappa;
    a.turning += 0.5 * gone.turning;
    b.turning += 0.5 * gone.turning;
  }
  if (i == 0) {  // the chain now starts at the old segment 1
    e.start = chain[1].start();
    e.theta = chain[1].theta0();
  }
  e.pieces.erase(e.pieces.begin() + static_cast<std::ptrdiff_t>(i), e.pieces.begin() + static_cast<std::ptrdiff_t>(i + count));
  for (Piece& p : e.pieces) fixZeroEnd(p);
  for (ChainFoot& f : e.feet) {
    if (f.segment >= i && f.segment < i + count) {  // onto the end of the segment before or the start of the one after
      const double along = (static_cast<double>(f.segment - i) + f.u) / static_cast<double>(count);
      const bool to_before = corner_before || corner_after ? corner_after
                             : closed ? along < 0.5
                                      : (i + 1 == n || (i > 0 && along < 0.5));
      f = to_before ? ChainFoot{(i + n - 1) % n, 1.0} : ChainFoot{(i + count) % n, 0.0};
    }
    if (f.segment >= i + count) f.segment -= count;  // the erase renumbers those after
  }
  return e;
}

}  // namespace

std::optional<LaSegment> closestCircle(const std::vector<Vec2>& points) {
  Eigen::MatrixXd a(points.size(), 3);
  Eigen::VectorXd b(points.size());
  const Vec2 origin = points.front();
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec2 p = points[k] - origin;
    a.row(static_cast<Eigen::Index>(k)) << p.x(), p.y(), 1.0;
    b[static_cast<Eigen::Index>(k)] = -p.squaredNorm();
  }
  const Eigen::Vector3d s = a.colPivHouseholderQr().solve(b);
  const Vec2 centre = origin - 0.5 * Vec2(s[0], s[1]);
  const double r2 = 0.25 * (s[0] * s[0] + s[1] * s[1]) - s[2];
  if (!std::isfinite(r2) || !(r2 > 0.0)) return std::nullopt;
  const double r = std::sqrt(r2);
  // (turning the way the points go round)
  double area = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) area += cross(points[k] - centre, points[(k + 1) % points.size()] - centre);
  const double sign = area < 0.0 ? -1.0 : 1.0;
  const Vec2 radial = (points.front() - centre).normalized();
  const Vec2 start = centre + r * radial;
  return LaSegment::arc(2.0 * std::numbers::pi * r, start, angleOf(Vec2(-radial.y(), radial.x()) * sign), sign / r);
}

SelectionResult selectChain(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points,
                            const std::vector<ChainFoot>& feet, const SelectionOptions& options) {
  // (a segment shorter than the tolerance is a stub: no point places it)
  ChainFitOptions base = options.fit;
  base.min_length = options.tolerance;
  base.standard_errors = false;  // (the first fit's, or the kept fit's at the end)
  // A fit that stops at its iteration limit outside the tolerance goes on from where it
  // stopped, for `patience` times as many steps (none at 0): a long chain far from its
  // start needs them, and only such a chain pays for them. A trial simplification that
  // has to end within `keep_within` does not where it stopped further than kHopelessTrial
  // times that (the trials that fail so paid for most of stage 7's time).
  // Nor does a fit that must keep the cap on extrema (`keep_cap`: a split's) where its
  // steps broke it: going on converges further, which adds extrema rather than removes
  // them (under caps of 0, 1 and 2 on the shared data, no such fit was kept).
  // (an edit renumbers the corners' joints: each fit names the corners of its chain)
  const bool closed = options.fit.closed;
  const double diagonal = options.diagonal > 0.0 ? options.diagonal : boundingBoxDiagonal(points);
  // (some part of the chain has more curvature extrema than the cap)
  auto breaksCap = [&](const std::vector<LaSegment>& segments, const std::vector<ChainCorner>& corners) {
    return options.max_extrema >= 0 && overExtremaCap(curveOf(segments, corners, closed), diagonal, options.max_extrema);
  };
  auto fit = [&](const std::vector<LaSegment>& start, const std::vector<ChainFoot>& start_feet,
                 const std::vector<ChainCorner>& corners, double keep_within = INFINITY, bool standard_errors = false,
                 bool keep_cap = false) {
    ChainFitOptions o = base;
    o.corners = corners;
    o.standard_errors = standard_errors;
    if (std::isfinite(keep_within)) o.abandon = {kAbandonAfter, kAbandonedTrial * keep_within};
    ChainFitResult r = fitChain(start, points, start_feet, o);
    if (options.patience <= 0 || !r.improved || r.report.status != SolveStatus::kIterationLimit ||
        r.max_distance <= options.tolerance ||
        r.max_distance > kHopelessTrial * keep_within || (keep_cap && breaksCap(r.segments, corners)))
      return r;
    ChainFitOptions longer = o;
    longer.max_iterations *= options.patience;
    ChainFitResult more = fitChain(r.segments, points, r.feet, longer);
    if (!more.improved) return r;
    more.report.iterations += r.report.iterations;
    return more;
  };
  SelectionResult out;
  out.corners = options.fit.corners;
  out.fit = fit(chain, feet, out.corners, INFINITY, options.fit.standard_errors);  // (often the one kept)
  // (a start the chain fit refuses has no feet to edit by: nothing to select from; an edit
  // of it crashed the window screen on a noisy logarithmic spiral of four turns)
  if (out.fit.report.status == SolveStatus::kBadInput) return out;
  if (out.fit.max_distance > options.hopeless_start) return out;
  const double n_points = static_cast<double>(points.size());
  struct Attempt {
    ChainFitResult fit;
    std::vector<ChainCorner> corners;
  };
  // (an edit's chain, rebuilt from its pieces: given where the caller has it already)
  auto attemptRebuilt = [&](const Edit& e, const std::vector<LaSegment>& rebuilt, double keep_within,
                            bool keep_cap = false) -> std::optional<Attempt> {
    if (rebuilt.empty()) return std::nullopt;
    std::vector<ChainCorner> corners = cornersOf(e.pieces, out.corners);
    ChainFitResult r = fit(rebuilt, e.feet, corners, keep_within, /*standard_errors=*/false, keep_cap);
    if (r.report.status == SolveStatus::kBadInput) return std::nullopt;
    return Attempt{std::move(r), std::move(corners)};
  };
  auto attempt = [&](const std::optional<Edit>& e, double keep_within = INFINITY,
                     bool keep_cap = false) -> std::optional<Attempt> {
    if (!e) return std::nullopt;
    const auto rebuilt = rebuild(e->start, e->theta, e->pieces);
    if (!rebuilt) return std::nullopt;
    return attemptRebuilt(*e, *rebuilt, keep_within, keep_cap);
  };
  // The trial edits of the chain out.fit holds that were not kept (a verdict holds for
  // its chain alone). The simplification of slivers ends by trying every candidate in
  // vain, and the full one, where nothing came between, starts on the same chain with the
  // same candidates: the same fits, the same verdicts (14% of the trial fits' steps on
  // the shared data). A trial is not run again on its chain (it still counts as an edit:
  // the cap on edits cuts where it did). Nor after Lawson's rounds (reweigh), which move
  // the chain a little and keep its segments: on the shared data no curve changed for not
  // trying them again (a drawn star's fit across corners had tried three hooks three
  // times each, in vain). The caller may hand in the verdicts of another selection of the
  // same chain (SelectionOptions::not_kept).
  std::vector<TrialEdit>& not_kept = out.not_kept;
  not_kept = options.not_kept;
  auto take = [&](Attempt&& a) {
    out.fit = std::move(a.fit);
    out.corners = std::move(a.corners);
    not_kept.clear();
  };
  int edits = 0;
  auto spent = [&] {
    if (!options.budget.spent()) return false;
    out.out_of_time = true;
    return true;
  };
  // Segments lo .. hi - 1 of a chain alone: the points whose feet are on them (the feet
  // renumbered from lo) and the options of their fit: ends free, no corners, not closed,
  // unweighted, no arcs, given up where still far outside `keep_within` (as a trial).
  struct Alone {
    std::vector<LaSegment> segments;
    std::vector<Vec2> points;
    std::vector<ChainFoot> feet;
    ChainFitOptions options;
  };
  auto alone = [&](const std::vector<LaSegment>& chain, const std::vector<ChainFoot>& chain_feet, std::size_t lo,
                   std::size_t hi, double keep_within) {
    Alone a;
    a.segments.assign(chain.begin() + static_cast<std::ptrdiff_t>(lo), chain.begin() + static_cast<std::ptrdiff_t>(hi));
    for (std::size_t k = 0; k < points.size(); ++k)
      if (chain_feet[k].segment >= lo && chain_feet[k].segment < hi) {
        a.points.push_back(points[k]);
        a.feet.push_back({chain_feet[k].segment - lo, chain_feet[k].u});
      }
    ChainFitOptions& o = a.options = base;
    o.abandon = {kAbandonAfter, kAbandonedTrial * keep_within};
    o.corners.clear();
    o.closed = o.fix_start = o.fix_end = o.hold_corner_points = false;
    o.held_start.reset();
    o.weights.clear();
    o.arcs.clear();
    return a;
  };
  // A trial edit's segments near `center` (two on either side, in the edited chain),
  // fitted alone to the points whose feet are on them. Where even they stay further than
  // kHopelessWindow times `keep_within` from those points, the whole chain's fit would
  // not keep the edit, and is not run (most trial simplifications fail, and a window
  // costs a fraction of the chain). Inside the chain, the window is pinned to the
  // segments on either side where they were before the edit (ChainFitOptions::window),
  // and where its fit improves on the edit, the whole chain's fit starts from the edit
  // with that window: G2, and nearer the points than the crude edit. At an open chain's
  // end, and at a closed chain's seam, the window's ends are free (and `start` stays
  // empty). Not across a corner, nor where the window is most of the chain.
  struct Nearby {
    bool hopeless = false;
    std::vector<LaSegment> start;  // the edited chain with the window refitted
    std::vector<ChainFoot> feet;   // on it
  };
  auto refitNearby = [&](const Edit& e, const std::vector<LaSegment>& rebuilt, std::size_t center, double keep_within) {
    Nearby nearby;
    const std::size_t n = e.pieces.size(), old_n = out.fit.segments.size();
    const std::size_t lo = center >= 2 ? center - 2 : 0, hi = std::min(n, center + 2);
    if (lo >= hi || 2 * (hi - lo) > n) return nearby;
    for (std::size_t i = lo; i <= hi && i < n; ++i)
      if ((i > lo || i == 0) && e.pieces[i].atCorner()) return nearby;
    Alone window = alone(rebuilt, e.feet, lo, hi, keep_within);
    // (the segments from hi on are the chain's from hi + old_n - n on, unedited)
    const auto unedited = out.fit.segments.begin() + static_cast<std::ptrdiff_t>(hi + old_n - n);
    // (a closed chain's first segment collapsed changes its last one too: no window)
    ChainFitOptions& o = window.options;
    o.window = hi < n && !(closed && center == 0);
    if (o.window) o.window_end = {unedited->start(), unedited->theta0()};
    // (a fit that does not improve on the edit reports the edit's own distances)
    const ChainFitResult r = fitChain(window.segments, window.points, window.feet, o);
    if (r.report.status == SolveStatus::kBadInput) return nearby;
    nearby.hopeless = r.max_distance > kHopelessWindow * keep_within;
    if (!o.window || !r.improved || nearby.hopeless) return nearby;
    nearby.start.assign(rebuilt.begin(), rebuilt.begin() + static_cast<std::ptrdiff_t>(lo));
    nearby.start.insert(nearby.start.end(), r.segments.begin(), r.segments.end());
    nearby.start.insert(nearby.start.end(), unedited, out.fit.segments.end());
    nearby.feet = e.feet;
    for (std::size_t k = 0, j = 0; k < points.size(); ++k)
      if (e.feet[k].segment >= lo && e.feet[k].segment < hi) {
        nearby.feet[k] = {r.feet[j].segment + lo, r.feet[j].u};
        ++j;
      }
    return nearby;
  };
  // An edit is kept if the refitted chain is within the tolerance (or no further outside
  // it than before) and the points do not object (the F-test above); a merge at a weak
  // curvature extremum on the tolerance alone (fewer extrema come before the squares).
  auto keep = [&](const ChainFitResult& r, bool fewer_extrema) {
    if (r.max_distance > std::max(options.tolerance, out.fit.max_distance)) return false;
    if (fewer_extrema) return true;
    const double variance = out.fit.ssr / std::max(1.0, n_points - out.fit.unknowns);
    const double f = (r.ssr - out.fit.ssr) / std::max(1, out.fit.unknowns - r.unknowns) / std::max(variance, 1e-300);
    return f < options.significance;
  };
  // Which joints of the chosen chain (of n segments) are corners; joint n: the end, or a
  // closed chain's seam again.
  auto cornerJoints = [&](std::size_t n) {
    std::vector<bool> corner(n + 1, false);
    for (const ChainCorner& c : out.corners) corner[c.joint] = true;
    corner[n] = closed && corner[0];
    return corner;
  };
  // Collapses (slivers first, the thinnest first) and merges (the weakest joint first),
  // one at a time, until none is kept.
  auto simplify = [&](bool slivers_only) {
    for (bool changed = true; changed && edits < options.max_edits;) {
      changed = false;
      const std::vector<LaSegment> segs = out.fit.segments;
      const std::size_t n = segs.size();
      const std::vector<bool> corner = cornerJoints(n);
      struct Candidate {
        double weakness;  // smaller first
        EditKind kind;
        std::size_t index;
        std::size_t count = 1;  // segments collapsed or straightened together
        bool extremum = false;  // a merge at a (weak) curvature extremum
      };
      std::vector<Candidate> candidates;
      for (std::size_t i = 0; i < n; ++i) {
        const double turning = std::abs(segs[i].turning());
        const bool beside = corner[i] || corner[i + 1];
        if (beside && (corner[i] == corner[i + 1] || (!closed && (i == 0 || i + 1 == n)))) continue;  // (a part's only)
        // a hook: a short segment between a corner and the rest of its part
        const std::size_t inner = corner[i] ? i + 1 : i - 1;
        const bool hook = beside && segs[i].length() < kHookRatio * segs[inner % n].length();
        // a stub: shorter than the tolerance, so no point places it; it only turns the
        // chain abruptly (a straight piece between inflections can end as a spike of two)
        const bool stub = segs[i].length() < options.tolerance;
        const bool spike = stub && i + 1 < n && segs[i].kappaStart() == 0.0 && segs[i + 1].kappaEnd() == 0.0;
        if (spike) candidates.push_back({0.0, EditKind::kCollapse, i, 2});
        else if ((turning < options.sliver_turning && options.refine) || hook || stub)
          candidates.push_back({hook || stub ? 0.0 : turning, EditKind::kCollapse, i});
      }
      // Nearly straight runs of one or two segments between zero-curvature joints or the
      // chain's ends: an LA segment has at most one zero end, so the solver can only
      // approach a line there (a segment and a stub, or two flat ones). (Not beside a
      // corner: a line runs on past a rounded tip.)
      auto free = [&](std::size_t joint) { return !corner[joint] && !closed && (joint == 0 || joint == n); };
      for (std::size_t i = 0; i < n && options.straighten_runs; ++i)
        for (std::size_t count = 1; count <= 2 && i + count <= n; ++count) {
          const LaSegment& first = segs[i];
          const LaSegment& last = segs[i + count - 1];
          if ((count == 1 && first.isStraight()) || (count == 2 && corner[i + 1])) continue;
          if (!(first.kappaStart() == 0.0 || free(i)) || !(last.kappaEnd() == 0.0 || free(i + count))) continue;
          const double turning = std::abs(first.turning()) + (count == 2 ? std::abs(last.turning()) : 0.0);
          // A bump (zero curvature, an extremum, zero again) on a chain within the
          // tolerance, its points near a line (spreadAboutLine), however far it turns: a
          // line candidate too, kept on the tolerance alone (one extremum fewer, as a merge
          // at a weak one). The F-test kept the noise's bumps on the sides of drawn
          // polygons. (A chain outside the tolerance needs splits, not lines: tried there
          // too, Omniglot's strokes came out with 49 segments and 32 extrema more.)
          const bool bump = count == 2 && first.kappaStart() == 0.0 && first.kappaEnd() != 0.0 && last.kappaEnd() == 0.0;
          const bool bump_line = bump && out.fit.max_distance < options.tolerance &&
                                 spreadAboutLine(points, out.fit.feet, i) <= options.tolerance;
          if (turning < options.straight_turning || bump_line)
            candidates.push_back({turning, EditKind::kStraighten, i, count, bump_line});
        }
      // Sides (between two corners, or a corner and an open chain's end) whose points lie
      // near a line, on a chain within the tolerance: a line candidate kept on the
      // tolerance alone, as a bump. A side that curls into its corner, and the jump of
      // curvature there, are extrema a straight side does not have.
      if (!out.corners.empty() && out.fit.max_distance < options.tolerance) {
        // (the joints that end sides, in order; a closed chain's side across its seam, where
        // the seam is no corner, is not tried)
        std::vector<std::size_t> ends;
        for (std::size_t joint = 0; joint <= n; ++joint)
          if (corner[joint] || (!closed && (joint == 0 || joint == n))) ends.push_back(joint);
        for (std::size_t side = 0; side + 1 < ends.size(); ++side) {
          const std::size_t i = ends[side], j = ends[side + 1], count = j - i;
          if (count == 1 && segs[i].isStraight()) continue;
          double turning = 0.0;
          for (std::size_t k = i; k < j; ++k) turning += std::abs(segs[k].turning());
          if (sideLineFits(segs, points, out.fit.feet, out.corners, i, count, options.tolerance))
            candidates.push_back({turning, EditKind::kStraightenSide, i, count, true});
        }
      }
      for (std::size_t j = 1; j < n && !slivers_only; ++j) {
        if (corner[j]) continue;
        const double k0 = std::abs(segs[j - 1].kappaStart()), kj = std::abs(segs[j].kappaStart());
        const double k1 = std::abs(segs[j].kappaEnd());
        if (kj == 0.0) continue;
        const bool monotone = (k0 - kj) * (kj - k1) > 0.0;
        const double change = std::min(std::abs(kj - k0), std::abs(kj - k1)) / kj;
        if (monotone || change < options.weak_extremum)
          candidates.push_back({1.0 + (monotone ? 0.0 : change), EditKind::kMerge, j, 1, !monotone});
      }
      std::sort(candidates.begin(), candidates.end(),
                [](const Candidate& a, const Candidate& b) { return a.weakness < b.weakness; });
      for (const Candidate& c : candidates) {
        if (edits >= options.max_edits || spent()) break;
        ++edits;
        const TrialEdit tried{c.kind, c.index, c.count};
        if (std::find(not_kept.begin(), not_kept.end(), tried) != not_kept.end()) continue;
        not_kept.push_back(tried);  // (until it is kept, below)
        const std::optional<Edit> e = c.kind == EditKind::kCollapse ? collapse(segs, out.fit.feet, out.corners, c.index, closed, c.count)
                                      : c.kind == EditKind::kMerge  ? merge(segs, out.fit.feet, out.corners, c.index, options.max_turning)
                                      : c.kind == EditKind::kStraighten ? straighten(segs, out.fit.feet, out.corners, c.index, c.count)
                                                                        : straightenSide(segs, out.fit.feet, out.corners, c.index, c.count);
        const double keep_within = std::max(options.tolerance, out.fit.max_distance);  // (keep's bound)
        if (!e) continue;
        const auto rebuilt = rebuild(e->start, e->theta, e->pieces);
        if (!rebuilt) continue;
        const Nearby nearby = refitNearby(*e, *rebuilt, c.index, keep_within);
        if (nearby.hopeless) continue;
        std::optional<Attempt> r;
        if (nearby.start.empty()) {
          r = attemptRebuilt(*e, *rebuilt, keep_within);
        } else {
          Edit from_window = *e;
          from_window.feet = nearby.feet;
          r = attemptRebuilt(from_window, nearby.start, keep_within);
        }
        // (a line only within the tolerance: bent again, it is a crude start for a split)
        const bool line = c.kind == EditKind::kStraighten || c.kind == EditKind::kStraightenSide;
        if (!r || !keep(r->fit, c.extremum) || (line && r->fit.max_distance > options.tolerance)) continue;
        if (c.kind == EditKind::kStraightenSide && !sideCornersHold(r->fit.segments, points, r->corners, c.index, options.tolerance))
          continue;
        not_kept.pop_back();
        take(std::move(*r));
        ++(c.kind == EditKind::kCollapse ? out.collapses : c.kind == EditKind::kMerge ? out.merges : out.straightenings);
        changed = true;
        break;
      }
    }
  };
  // Least squares minimizes the sum of squares; a chain of the same segments that keeps
  // every point within the tolerance may still exist where it leaves a few outside.
  // Lawson's iteration looks for it: each round multiplies every point's weight by its
  // distance over the tolerance (where above 1) and fits again from the current chain,
  // kept while the largest distance falls. Tried before any segment is added. From the
  // third round (the first ones' weights are still near 1, and their gain says little),
  // the rounds stop where the rounds left, each gaining what the last one did, would
  // not bring the largest distance within the tolerance: on the shared data most rounds
  // crawled so (a few thousandths of the tolerance each) into a split all the same.
  auto reweigh = [&] {
    std::vector<double> weights(points.size(), 1.0);
    for (int round = 0; round < options.reweighing_rounds && out.fit.max_distance > options.tolerance; ++round) {
      for (std::size_t k = 0; k < weights.size(); ++k)
        weights[k] *= std::max(1.0, out.fit.distance[k] / options.tolerance);
      ChainFitOptions weighted = base;
      weighted.weights = weights;
      weighted.corners = out.corners;
      const ChainFitResult r = fitChain(out.fit.segments, points, out.fit.feet, weighted);
      if (!r.improved || !(r.max_distance < out.fit.max_distance) || breaksCap(r.segments, out.corners)) break;
      const double gain = out.fit.max_distance - r.max_distance;
      out.fit = r;
      const int rounds_left = options.reweighing_rounds - round - 1;
      if (round >= 2 && out.fit.max_distance - options.tolerance > rounds_left * gain) break;
    }
  };
  // The cap on extrema (see the header): merges at the extrema of parts over it, the
  // weakest first, then a closed part's circle.
  auto enforceCap = [&] {
    const auto cap = static_cast<std::size_t>(options.max_extrema);
    auto circle = [&] {
      const auto c = closestCircle(points);
      if (!c) return false;
      auto r = attempt(Edit{{Piece{kZeroEndAlpha, c->kappaStart(), c->kappaEnd(), c->turning()}}, c->start(), c->theta0(), {}});
      if (r) take(std::move(*r)), ++out.cap_merges;
      return r.has_value();
    };
    // (a simple closed curve that is not a circle has at least 4 extrema: the four-vertex
    // theorem)
    const bool one_closed_part = closed && out.corners.empty();
    // The merges at `joints` (all but the seam) made one after another on the unfitted
    // chain, then fitted once: where parts are many extrema over the cap, a fit per merge
    // cost a capped glyph seconds. True if two or more merged and the fit took them.
    auto mergedAtOnce = [&](std::vector<std::size_t> joints) {
      std::sort(joints.begin(), joints.end(), std::greater<>());  // (a merge renumbers only the segments after it)
      std::vector<LaSegment> chain = out.fit.segments;
      std::vector<ChainFoot> feet = out.fit.feet;
      std::vector<ChainCorner> corners = out.corners;
      std::optional<Edit> last;
      int merges = 0;
      for (std::size_t j : joints) {
        std::optional<Edit> e = merge(chain, feet, corners, j, kCapMaxTurning);
        if (!e) continue;
        std::optional<std::vector<LaSegment>> rebuilt = rebuild(e->start, e->theta, e->pieces);
        if (!rebuilt) continue;
        chain = std::move(*rebuilt);
        feet = e->feet;
        corners = cornersOf(e->pieces, corners);
        last = std::move(e);
        ++merges;
      }
      if (merges < 2) return false;
      std::optional<Attempt> r = attemptRebuilt(*last, chain, INFINITY);
      if (!r) return false;
      take(std::move(*r));
      out.cap_merges += merges;
      return true;
    };
    for (;;) {
      const std::vector<LaSegment> segs = out.fit.segments;
      const std::size_t n = segs.size();
      // The extrema of the parts over the cap, the weakest first: the smaller curvature
      // change beside the joint, relative to the curvature there.
      std::vector<std::pair<double, std::size_t>> candidates;
      std::vector<std::size_t> excess;  // per part over the cap, its weakest extrema beyond it
      for (const std::vector<std::size_t>& joints : extremumJoints(curveOf(segs, out.corners, closed), diagonal)) {
        if (joints.size() <= cap) continue;
        const std::size_t from = candidates.size();
        for (std::size_t j : joints) {
          const LaSegment& a = segs[(j + n - 1) % n];
          const LaSegment& b = segs[j];
          const double k = b.kappaStart();
          const double change = std::min(std::abs(k - a.kappaStart()), std::abs(b.kappaEnd() - k));
          candidates.push_back({change / std::max(std::abs(k), 1.0 / diagonal), j});
        }
        std::vector<std::pair<double, std::size_t>> part(candidates.begin() + static_cast<std::ptrdiff_t>(from), candidates.end());
        std::sort(part.begin(), part.end());
        for (std::size_t k = 0; k + cap < part.size(); ++k)
          if (part[k].second > 0) excess.push_back(part[k].second);
      }
      if (candidates.empty()) return;  // (no part over the cap)
      if (!one_closed_part && excess.size() >= 2 && mergedAtOnce(excess)) continue;
      if (one_closed_part && (cap < 4 || n == 1)) {
        if (!circle()) out.over_cap = true;
        return;
      }
      std::sort(candidates.begin(), candidates.end());
      bool merged = false;
      for (const auto& [weakness, j] : candidates) {
        std::optional<Attempt> r;
        if (j > 0) {
          // (two segments meeting at an extremum with a zero curvature at each far end are
          // no LA segment: then the spike goes, or one of them)
          r = attempt(merge(segs, out.fit.feet, out.corners, j, kCapMaxTurning));
          if (!r) r = attempt(collapse(segs, out.fit.feet, out.corners, j - 1, closed, 2));
          if (!r) r = attempt(collapse(segs, out.fit.feet, out.corners, j - 1, closed));
          if (!r) r = attempt(collapse(segs, out.fit.feet, out.corners, j, closed));
        } else if (one_closed_part) {
          // the seam: the closed chain started one segment later, merged at its new joint n - 1
          std::vector<LaSegment> turned(segs.begin() + 1, segs.end());
          turned.push_back(segs.front());
          std::vector<ChainFoot> feet = out.fit.feet;
          for (ChainFoot& f : feet) f.segment = (f.segment + n - 1) % n;
          r = attempt(merge(turned, feet, {}, n - 1, kCapMaxTurning));
        }
        if (!r) continue;
        take(std::move(*r));
        ++out.cap_merges;
        merged = true;
        break;
      }
      if (!merged) {
        if (!one_closed_part || !circle()) out.over_cap = true;
        return;
      }
    }
  };
  // Fewer extrema by arcs, the objective's first term, on a chain within the tolerance: a
  // segment between a curvature peak and a dip of its part (its curvature falls from one
  // to the other), or between an extremum and its part's end (a side that curls into its
  // corner or end), held as a circular arc (ChainFitOptions::arcs): the curvature levels
  // out there instead of turning back. Kept where the chain keeps the tolerance and its
  // curvature reverses less often (curvatureReversals, as lacheck counts them); the arcs
  // kept are held by the selection's fits after. Each segment is tried once, where
  // levelling it alone would not move it far (kArcStrayBetween), and screened as a trial
  // edit is (refitNearby) by a fit of the segments about it alone, its ends free (not
  // past a corner).
  auto holdArcs = [&] {
    if (!(out.fit.max_distance <= options.tolerance) || out.fit.feet.empty()) return;
    const std::size_t n = out.fit.segments.size();  // (an arc keeps the count and the corners)
    const std::vector<bool> corner = cornerJoints(n);
    std::vector<bool> tried(n, false);
    int reversals = curvatureReversals(curveOf(out.fit.segments, out.corners, closed), diagonal);
    for (bool changed = true; changed && !spent();) {
      changed = false;
      const std::vector<LaSegment> segs = out.fit.segments;
      // +1 where joint j is a smooth joint at a peak of |curvature|, -1 at a dip, else 0
      auto extremum = [&](std::size_t j) {
        if ((j == 0 && !closed) || j == n || corner[j]) return 0;
        const double before = std::abs(segs[(j + n - 1) % n].kappaStart()), at = std::abs(segs[j].kappaStart());
        const double after = std::abs(segs[j].kappaEnd());
        if (at == 0.0) return 0;
        return at > before && at > after ? 1 : at < before && at < after ? -1 : 0;
      };
      // (the segments lo..hi-1 about i, with arc i, fitted alone to the points on them)
      auto hopeless = [&](std::size_t i) {
        std::size_t lo = i, hi = i + 1;
        while (lo > 0 && i - lo < 2 && !corner[lo]) --lo;
        while (hi < n && hi - i < 3 && !corner[hi]) ++hi;
        if (2 * (hi - lo) > n) return false;
        Alone window = alone(segs, out.fit.feet, lo, hi, options.tolerance);
        for (std::size_t a : base.arcs)
          if (a >= lo && a < hi) window.options.arcs.push_back(a - lo);
        const ChainFitResult r = fitChain(window.segments, window.points, window.feet, window.options);
        return r.report.status != SolveStatus::kBadInput && r.max_distance > kHopelessWindow * options.tolerance;
      };
      for (std::size_t i = 0; i < n && !changed && !spent(); ++i) {
        const LaSegment& s = segs[i];
        if (tried[i] || s.isStraight() || s.kappaStart() == 0.0 || s.kappaEnd() == 0.0) continue;
        const int at_start = extremum(i), at_end = extremum(closed && i + 1 == n ? 0 : i + 1);
        const bool start_ends = (i == 0 && !closed) || corner[i], end_ends = (i + 1 == n && !closed) || corner[i + 1];
        const bool between = at_start != 0 && at_end != 0 && at_start != at_end;
        const bool to_end = (at_start != 0 && end_ends) || (at_end != 0 && start_ends);
        if (!between && !to_end) continue;
        // (the segment levelled alone would move about |kappa1 - kappa0| L^2 / 8 off)
        const double stray = std::abs(std::abs(s.kappaEnd()) - std::abs(s.kappaStart())) * s.length() * s.length() / 8.0;
        if (stray > (between ? kArcStrayBetween : kArcStrayAtEnd) * options.tolerance) continue;
        tried[i] = true;
        base.arcs.push_back(i);
        if (!hopeless(i)) {
          ChainFitResult r = fit(segs, out.fit.feet, out.corners, options.tolerance);
          const bool keeps = r.report.status != SolveStatus::kBadInput && r.max_distance <= options.tolerance &&
                             !breaksCap(r.segments, out.corners);
          const int after = keeps ? curvatureReversals(curveOf(r.segments, out.corners, closed), diagonal) : reversals;
          if (after < reversals) {
            take(Attempt{std::move(r), out.corners});
            reversals = after;
            ++out.arcs;
            changed = true;
            continue;
          }
        }
        base.arcs.pop_back();
      }
    }
  };
  // Under a cap on extrema, the chain keeps it from here on: merged down to it first, then
  // split towards the tolerance only where a split's refit keeps it (a split is a cut
  // that changes nothing, but the refit may add an extremum). The splits the cap would
  // merge away again cost a capped glyph most of its second. The slivers go after the
  // cap's merges: on a start far from the points (a glyph's chain of 34 segments 200
  // tolerances off), trial collapses of segments the cap merges anyway took seconds.
  if (options.max_extrema >= 0) enforceCap();
  simplify(true);
  // The split at the worst point of a fit (an edit).
  auto splitAtWorst = [&](const ChainFitResult& from) {
    const std::size_t worst = std::max_element(from.distance.begin(), from.distance.end()) - from.distance.begin();
    const ChainFoot at = from.feet[worst];
    const LaSegment& s = from.segments[at.segment];
    const double margin = std::min(kSplitMargin, options.split_margin / s.length());
    const double u = std::clamp(at.u, margin, 1.0 - margin);
    ++edits;
    if (!s.isStraight()) return attempt(split(from.segments, from.feet, out.corners, at.segment, u), INFINITY, /*keep_cap=*/true);
    // (a line bends towards the worst point: the arc through its ends with that sagitta,
    // no tighter than the fit allows: a stub line bent so had a curvature of 1e16, and
    // the quadrature of its 1e9 radians took seconds)
    const double side = cross(s.tangent(at.u * s.length()), points[worst] - s.position(at.u * s.length()));
    double bend = 8.0 * side / (s.length() * s.length());
    if (options.fit.max_curvature > 0.0) bend = std::clamp(bend, -options.fit.max_curvature, options.fit.max_curvature);
    return attempt(bendLine(from.segments, from.feet, out.corners, at.segment, u, bend, closed), INFINITY, /*keep_cap=*/true);
  };
  // (a split that barely helps is not the missing segment: the chain is stuck elsewhere)
  auto helps = [&](const std::optional<Attempt>& r) {
    return r && (r->fit.max_distance <= options.tolerance || r->fit.max_distance < kMarkedGain * out.fit.max_distance) &&
           !breaksCap(r->fit.segments, r->corners);
  };
  // Splits while some point is out of tolerance (and the split helps).
  while (options.refine && edits < options.max_edits && out.fit.max_distance > options.tolerance && !out.fit.feet.empty() &&
         !spent()) {
    const ChainFitResult unweighted = out.fit;
    reweigh();
    if (out.fit.max_distance <= options.tolerance) break;
    auto r = splitAtWorst(out.fit);
    // Lawson's rounds may have bent the chain where the segment is missing (a curvature
    // spike at a joint): the split is tried from the unweighted fit too.
    if (!helps(r) && unweighted.max_distance != out.fit.max_distance && edits < options.max_edits)
      r = splitAtWorst(unweighted);
    if (!helps(r)) break;
    take(std::move(*r));
    ++out.splits;
  }
  if (options.refine) simplify(false);
  if (options.max_extrema >= 0) enforceCap();
  if (options.level_arcs) holdArcs();
  if (options.fit.standard_errors && out.fit.improved && out.fit.alpha_standard_error.empty()) {
    ChainFitOptions o = base;
    o.corners = out.corners;
    out.fit.alpha_standard_error = alphaStandardErrorsOf(out.fit.segments, points, out.fit.feet, o);
  }
  return out;
}

}  // namespace la
