// Stroke clean-up (DESIGN.md section 3, stage 1).
//
// Everything here works on chords over arc-length windows rather than on single
// steps: tablet and mouse data are quantized to whole pixels, so the direction of one
// 2-px step is only known to within 45 degrees, while the chord over a window of a few
// steps is good to a few degrees. The window w is corner_window of the stroke length,
// but at least kWindowNoise times the sampling noise (half the pixel grid on quantized
// input), and at least 2 samples.
//
// The turn at point i over window w:
//     a = the point at least w of arc (and at least 2 samples) before i,
//     b = the point at least w of arc (and at least 2 samples) after i,
//     turn_w(i) = |angle between P_i - P_a and P_b - P_i|.
// On a circular arc of radius rho, turn_w = w / rho (the chords' directions are the
// tangents at s - w/2 and s + w/2). A hand-drawn corner and a tight smooth bend both
// turn a lot over one window; what tells them apart is how the turn grows with the
// window. Over three windows (chords [a2, a], [a, i], [i, b], [b, b2], the turns between
// them summed) an arc turns 3 turn_w, a corner between straight legs turn_w. A point is
// sharp when that wide turn is at most kWideRatio * turn_w; near the ends of an open
// stroke, where three windows do not fit, when the turn over half the window is at
// least kSharpRatio * turn_w (an arc keeps half of it, a corner all).
//
// A corner is a sharp point turning more than corner_min_angle, one index per corner
// (non-maximum suppression). A hook is a short straight end piece meeting the rest at a
// sharp turn of more than hook_min_angle. Both tests keep a small loop, a question mark's
// top or a brace's curl from being taken for a corner or a hook.

#include "fitting/stroke.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "fitting/subdivision.h"

namespace la {
namespace {

/// Two finite points closer than this fraction of the bounding-box diagonal are one.
constexpr double kDuplicateTolerance = 1e-9;
/// Points within this fraction of the diagonal of their best line are collinear.
constexpr double kCollinearTolerance = 1e-9;
/// Hook trimming keeps at least this fraction of the drawn length (the brief: ~70%).
constexpr double kMinKeptFraction = 0.7;
/// A hook's worth: an end cut spans at most this many of the stroke's median steps or
/// this many tolerances, whichever is longer (a slip takes 1-5 samples, fast ones a few
/// median steps each; a slip within a few tolerances of the curve is all it could hide).
constexpr double kHookReachSteps = 6.0;
constexpr double kHookReachTolerances = 4.0;
/// The tolerance a hook's worth is tied to when the caller gives none: FitOptions'
/// default, 0.5% of the diagonal.
constexpr double kDefaultToleranceFraction = 0.005;
/// Distances (relative to the diagonal) and turns (radians) closer than this are equal
/// where the seam is chosen (findSeam).
constexpr double kTie = 1e-9;
/// The overlap of a closed stroke is searched in this last fraction of its length only:
/// longer overlaps are not overshoots but strokes that pass their start and go on (a
/// "9" drawn from the crossing), and the first points are always near the start.
constexpr double kMaxOverlapFraction = 0.25;
/// A tail crossing the start's normal line forwards closes the stroke if it passes within
/// this many close distances of the start. The slow $1 circle #0 overshoots its start
/// 7.3% of the diagonal outside it (close_fraction is 6%); open gestures never cross
/// their start line near the start.
constexpr double kCrossReach = 2.0;
/// A kinked seam may be moved to a closing step this many close distances long: bridging
/// a sideways miss gently takes a step several times as long as the miss (on a circle of
/// radius r, a miss d is bridged best by a step of about sqrt(2 r d)).
constexpr double kSeamReach = 4.0;
/// A closed curve has at least this many points (stage 2's periodic cubic spline needs
/// them; three points closed up are a triangle, not a curve).
constexpr std::size_t kMinClosedPoints = 4;
/// Coordinates larger than this are refused: squared distances between them overflow.
constexpr double kLargestCoordinate = 1e150;
/// The seam search tries at most about this many points of each region (it is
/// quadratic, and a stroke drawn round and round has all its points there).
constexpr std::size_t kMaxSeamCandidates = 256;
/// The end of a stroke run past its start is beside its head if their directions differ
/// by less than this.
constexpr double kSeamParallel = std::numbers::pi / 4.0;
/// A seam is kinked if the closing step turns by more than this fraction of
/// corner_min_angle at either end.
constexpr double kSeamSmoothFraction = 0.5;
/// A closed stroke's first points within this many median steps of its last point are
/// dropped (they repeat it, and a very short closing step is noise).
constexpr double kSeamMergeSteps = 0.5;
/// Sharpness (see the top of the file). Over three windows an arc turns 3 times as much
/// as over one, a corner as much. In the $1 data the corners of rectangles, stars,
/// triangles, carets, v's, arrows and x's have wide ratios of 0.7-1.7 (rounded corners of
/// fast strokes the most), the smooth loop tops of the pigtails 1.9-2.4.
constexpr double kWideRatio = 1.75;
/// Over half the window a corner keeps its turn, an arc half of it; used where three
/// windows do not fit. Hand-drawn corners keep 0.7-1.3 of it.
constexpr double kSharpRatio = 0.7;
/// A corner's leg is straight if its points bulge from its chord by at most this fraction
/// of the chord on average (an arc turning 55 degrees bulges 0.08; noise averages out).
constexpr double kLegStraightness = 0.08;
/// Fewer points between a leg's ends cannot tell a bulge from noise: not straight.
constexpr std::ptrdiff_t kMinLegPoints = 3;
/// A hook is nearly straight: no point of it is farther than this fraction of its chord
/// from the chord (a circular arc turning 90 degrees has 0.21, one turning 60 degrees 0.13).
constexpr double kHookStraightness = 0.15;
/// A hook's chord is at least this many noise levels long (3 px on pixel-quantized
/// input); anything shorter is within the sampling noise and harmless to the fit,
/// unless it doubles back by more than kBackStepTurn: a pen-down back step (the fast $1
/// x starts 2.2 px back against its stroke) sits beside the curve's end, which the fit
/// pins to the first point, and no curve through both follows it.
constexpr double kHookMinNoise = 6.0;
constexpr double kBackStepTurn = 2.5;
/// Coordinates are on a grid if this share of the step components are multiples of the
/// smallest one, to within this tolerance (CSV files round to 6 decimals).
constexpr double kGridShare = 0.95;
constexpr double kGridTolerance = 1e-3;
/// Windows are at least this many noise levels long: over such a chord, noise moves
/// the direction by about 1/8 rad.
constexpr double kWindowNoise = 8.0;

std::vector<double> arcLengths(const std::vector<Vec2>& p) {
  std::vector<double> s(p.size(), 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
  return s;
}

double unsignedAngle(const Vec2& a, const Vec2& b) { return std::abs(signedAngle(a, b)); }

/// Distance from q to the segment [a, b].
double segmentDistance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double d2 = d.squaredNorm();
  const double u = d2 > 0.0 ? std::clamp((q - a).dot(d) / d2, 0.0, 1.0) : 0.0;
  return (q - (a + u * d)).norm();
}

/// Distance from q to the line through a and b (to a if they coincide).
double lineDistance(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len = d.norm();
  return len > 0.0 ? std::abs(cross(d, q - a)) / len : (q - a).norm();
}

/// The cleaned points with the raw index of each.
struct Points {
  std::vector<Vec2> p;
  std::vector<std::size_t> src;
  std::vector<LeftOutPoint>* left_out = nullptr;  // where what is cut off is listed

  std::size_t size() const { return p.size(); }
  void dropFront(std::size_t k, LeftOutReason why) {
    for (std::size_t i = 0; i < k; ++i) left_out->push_back({src[i], why});
    p.erase(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(k));
    src.erase(src.begin(), src.begin() + static_cast<std::ptrdiff_t>(k));
  }
  void keepFront(std::size_t k, LeftOutReason why) {
    for (std::size_t i = k; i < src.size(); ++i) left_out->push_back({src[i], why});
    p.resize(k);
    src.resize(k);
  }
  /// Keeps the points `keep` flags; returns how many went.
  std::size_t keepOnly(const std::vector<bool>& keep, LeftOutReason why) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!keep[i]) {
        left_out->push_back({src[i], why});
        continue;
      }
      p[kept] = p[i];
      src[kept++] = src[i];
    }
    const std::size_t gone = p.size() - kept;
    p.resize(kept);
    src.resize(kept);
    return gone;
  }
};

// The fraction of the drawn length (the finite samples' polyline) spanned by the steps
// that touch a left-out sample (not a duplicate: it lies on a kept point). A resampler's
// points lie on the step between the samples either side, which is walked in one.
double leftOutFraction(const Stroke& raw, const std::vector<LeftOutPoint>& left_out) {
  std::vector<bool> out(raw.samples.size(), false), resampled(raw.samples.size(), false);
  for (const LeftOutPoint& l : left_out) {
    out[l.sample] = !liesOnKeptPoints(l.why);
    resampled[l.sample] = l.why == LeftOutReason::kResampled;
  }
  double drawn = 0.0, dropped = 0.0;
  std::size_t prev = raw.samples.size();
  for (std::size_t i = 0; i < raw.samples.size(); ++i) {
    if (!allFinite(raw.samples[i].p) || resampled[i]) continue;
    if (prev < raw.samples.size()) {
      const double step = (raw.samples[i].p - raw.samples[prev].p).norm();
      drawn += step;
      if (out[i] || out[prev]) dropped += step;
    }
    prev = i;
  }
  return drawn > 0.0 ? dropped / drawn : 0.0;
}

/// Length scales of a stroke, measured once after the outlier test.
struct Scales {
  double median_step = 0.0;
  /// Sampling noise: the median distance of a point from the chord of its two
  /// neighbours (the sagitta of one step on a smooth exact curve), but at least half
  /// the spacing of the grid the coordinates are rounded to.
  double noise = 0.0;
  /// The corner window: corner_window of the length, but at least kWindowNoise noise
  /// levels, so that a window's chord direction is good to a few degrees.
  double window = 0.0;
  /// A hook's worth: the longest an end cut may be (kHookReachSteps, kHookReachTolerances).
  double hook_reach = 0.0;
};

/// The spacing of the grid the coordinates were rounded to (pixels, or the Omniglot
/// canvas's 0.84 units), 0 if there is none: the smallest nonzero step component, if
/// nearly all step components are multiples of it.
double gridSpacing(const std::vector<Vec2>& p) {
  std::vector<double> components;
  for (std::size_t i = 1; i < p.size(); ++i) {
    for (const double c : {std::abs(p[i].x() - p[i - 1].x()), std::abs(p[i].y() - p[i - 1].y())}) {
      if (c > 0.0) components.push_back(c);
    }
  }
  if (components.empty()) return 0.0;
  const double q = *std::min_element(components.begin(), components.end());
  const auto on_grid = std::count_if(components.begin(), components.end(), [q](double c) {
    return std::abs(c / q - std::round(c / q)) < kGridTolerance;
  });
  return static_cast<double>(on_grid) >= kGridShare * static_cast<double>(components.size()) ? q : 0.0;
}

/// The corner window of points p with noise level `noise` (Scales::window).
double cornerWindow(const std::vector<Vec2>& p, bool closed, double noise, const CleanupOptions& options) {
  double length = arcLengths(p).back();
  if (closed && p.size() > 1) length += (p.front() - p.back()).norm();
  return std::max(options.corner_window * length, kWindowNoise * noise);
}

Scales measureScales(const std::vector<Vec2>& p, bool closed, const CleanupOptions& options, double tolerance) {
  Scales scales;
  scales.median_step = medianStep(p);
  scales.hook_reach = std::max(kHookReachSteps * scales.median_step, kHookReachTolerances * tolerance);
  std::vector<double> deviations;
  for (std::size_t i = 1; i + 1 < p.size(); ++i) deviations.push_back(lineDistance(p[i], p[i - 1], p[i + 1]));
  if (!deviations.empty()) {
    auto mid = deviations.begin() + static_cast<std::ptrdiff_t>(deviations.size() / 2);
    std::nth_element(deviations.begin(), mid, deviations.end());
    scales.noise = *mid;
  }
  // On a pixel grid most steps of a slanted line are exactly straight runs, so the
  // median above sees no noise; the quantization is half a grid step.
  scales.noise = std::max(scales.noise, 0.5 * gridSpacing(p));
  scales.window = cornerWindow(p, closed, scales.noise, options);
  return scales;
}

/// A polyline seen through arc-length windows; indices wrap around when closed.
class Polyline {
 public:
  Polyline(const std::vector<Vec2>& p, bool closed) : m_p(p), m_closed(closed) {
    m_n = static_cast<std::ptrdiff_t>(p.size());
    m_s = arcLengths(p);
    m_length = m_s.empty() ? 0.0 : m_s.back();
    if (closed && m_n > 1) m_length += (p.front() - p.back()).norm();
    if (closed) {  // arc length at unwrapped indices -n .. 2n-1
      m_shift = m_n;
      for (std::ptrdiff_t k = -m_n; k < 2 * m_n; ++k) {
        const double laps = std::floor(static_cast<double>(k) / static_cast<double>(m_n));
        m_cumulative.push_back(m_s[static_cast<std::size_t>(wrap(k))] + laps * m_length);
      }
    } else {
      m_cumulative = m_s;
    }
    // Running sums of the points (about point 0, to keep them small) at the same
    // unwrapped indices, so a leg's bulge is O(1) however many points a window holds.
    const std::ptrdiff_t lo = closed ? -m_n : 0, hi = closed ? 2 * m_n : m_n;
    m_sums.reserve(static_cast<std::size_t>(hi - lo + 1));
    m_sums.push_back(Vec2::Zero());
    for (std::ptrdiff_t k = lo; k < hi; ++k) m_sums.push_back(m_sums.back() + (at(k) - p.front()));
  }

  double length() const { return m_length; }
  std::ptrdiff_t size() const { return m_n; }
  /// Arc length at each point from point 0.
  const std::vector<double>& pointArcLengths() const { return m_s; }
  std::ptrdiff_t wrap(std::ptrdiff_t i) const { return m_closed ? ((i % m_n) + m_n) % m_n : i; }
  const Vec2& at(std::ptrdiff_t i) const { return m_p[static_cast<std::size_t>(wrap(i))]; }

  /// Arc length from i to j along the curve (the shorter way round when closed).
  double distance(std::ptrdiff_t i, std::ptrdiff_t j) const {
    const double d = std::abs(m_s[static_cast<std::size_t>(wrap(i))] - m_s[static_cast<std::size_t>(wrap(j))]);
    return m_closed ? std::min(d, m_length - d) : d;
  }

  /// The sum of the points at unwrapped indices from..to-1 (from <= to).
  Vec2 sum(std::ptrdiff_t from, std::ptrdiff_t to) const {
    return m_sums[static_cast<std::size_t>(to + m_shift)] - m_sums[static_cast<std::size_t>(from + m_shift)] +
           static_cast<double>(to - from) * m_p.front();
  }

  /// Walks from i in direction dir (+1 / -1) until at least `length` of arc and
  /// `min_steps` steps are covered. An open polyline stops at its end, a closed one after
  /// half a loop; nullopt if fewer than min_steps steps were possible, or (`whole`) if
  /// the open end came before `length`. The result is not wrapped (on a closed polyline
  /// it may be negative or >= size()). Binary search on the arc length: O(log n).
  std::optional<std::ptrdiff_t> walk(std::ptrdiff_t i, int dir, double length, int min_steps,
                                     bool whole = false) const {
    const std::ptrdiff_t base = wrap(i);
    const std::ptrdiff_t max_steps = m_closed ? (m_n - 1) / 2 : (dir > 0 ? m_n - 1 - base : base);
    if (max_steps < min_steps) return std::nullopt;
    const double start = arcAt(base);
    auto covered = [&](std::ptrdiff_t k) { return dir > 0 ? arcAt(base + k) - start : start - arcAt(base - k); };
    if (covered(max_steps) < length) {
      if (whole && !m_closed) return std::nullopt;
      return i + dir * max_steps;
    }
    std::ptrdiff_t lo = min_steps, hi = max_steps;  // the fewest steps covering `length`
    while (lo < hi) {
      const std::ptrdiff_t mid = lo + (hi - lo) / 2;
      if (covered(mid) >= length) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
    return i + dir * lo;
  }

  /// turn_w(i) of the file comment, with the window ends.
  struct Turn {
    double angle = 0.0;
    std::ptrdiff_t a = 0, b = 0;
  };
  std::optional<Turn> turn(std::ptrdiff_t i, double w, int min_steps, bool whole = false) const {
    const auto a = walk(i, -1, w, min_steps, whole);
    const auto b = walk(i, +1, w, min_steps, whole);
    if (!a || !b) return std::nullopt;
    return Turn{unsignedAngle(at(i) - at(*a), at(*b) - at(i)), *a, *b};
  }

  /// Turning over three windows: the signed turns from chord [a2, a] to [a, i] to
  /// [i, b] to [b, b2], each chord at least w long, summed (so a small loop does not
  /// wrap round). A circular arc turns 3 turn_w(i) over it, a corner between straight
  /// legs turn_w(i).
  std::optional<double> wideTurn(std::ptrdiff_t i, double w, int min_steps) const {
    const auto a = walk(i, -1, w, min_steps, true);
    const auto b = walk(i, +1, w, min_steps, true);
    if (!a || !b) return std::nullopt;
    const auto a2 = walk(*a, -1, w, min_steps, true);
    const auto b2 = walk(*b, +1, w, min_steps, true);
    if (!a2 || !b2) return std::nullopt;
    const Vec2 c0 = at(*a) - at(*a2), c1 = at(i) - at(*a), c2 = at(*b) - at(i), c3 = at(*b2) - at(*b);
    return std::abs(signedAngle(c0, c1) + signedAngle(c1, c2) + signedAngle(c2, c3));
  }

 private:
  double arcAt(std::ptrdiff_t k) const { return m_cumulative[static_cast<std::size_t>(k + m_shift)]; }

  const std::vector<Vec2>& m_p;
  bool m_closed = false;
  std::ptrdiff_t m_n = 0;
  std::vector<double> m_s;          // arc length at each point from point 0
  std::vector<double> m_cumulative; // the same at unwrapped indices (closed: -n .. 2n-1)
  std::vector<Vec2> m_sums;         // m_sums[k + shift] = sum of (points - point 0) before unwrapped index k
  std::ptrdiff_t m_shift = 0;
  double m_length = 0.0;
};

/// Whether the legs of a window (from its ends to its centre i) are straight: the points
/// between bulge from the chord by at most kLegStraightness of its length on average
/// (signed, so that noise averages out and an arc's bulge does not). A leg whose first
/// step from i is a window (w) long is that step, straight: a font outline's straight
/// edge is one step, and the window's two samples a side reach past its far corner.
bool straightLegs(const Polyline& line, std::ptrdiff_t i, const Polyline::Turn& turn, double w) {
  auto oneStep = [&](std::ptrdiff_t next) { return (line.at(next) - line.at(i)).norm() >= w; };
  auto straight = [&](std::ptrdiff_t from, std::ptrdiff_t to) {
    const Vec2 chord = line.at(to) - line.at(from);
    const double length = chord.norm();
    const double bulge =
        cross(chord, line.sum(from + 1, to) - static_cast<double>(to - from - 1) * line.at(from)) / length;
    return to - from - 1 >= kMinLegPoints && std::abs(bulge) / static_cast<double>(to - from - 1) <= kLegStraightness * length;
  };
  return (oneStep(i - 1) || straight(turn.a, i)) && (oneStep(i + 1) || straight(i, turn.b));
}

/// Deliberate corners: turn over the window above corner_min_angle, sharp, then
/// non-maximum suppression (strongest first) and each placed on the point farthest from
/// the chord (segment) across its window. With `ends_only` (a profile), only those
/// within one window of the first or last point are kept.
std::vector<std::size_t> findCorners(const std::vector<Vec2>& p, bool closed, double w,
                                     const CleanupOptions& options, bool ends_only) {
  const Polyline line(p, closed);
  const std::ptrdiff_t n = line.size();
  constexpr int kMinSideSamples = 2;  // the brief: at least 2 samples a side

  struct Candidate {
    std::ptrdiff_t i;
    Polyline::Turn turn;
  };
  std::vector<Candidate> candidates;
  const std::ptrdiff_t first = closed ? 0 : kMinSideSamples;
  const std::ptrdiff_t last = closed ? n - 1 : n - 1 - kMinSideSamples;
  for (std::ptrdiff_t i = first; i <= last; ++i) {
    const auto full = line.turn(i, w, kMinSideSamples, true);
    if (!full || full->angle <= options.corner_min_angle) continue;
    const auto half = line.turn(i, 0.5 * w, 1, true);
    const auto wide = line.wideTurn(i, w, kMinSideSamples);
    // Two corners closer than two windows (the short edge at a glyph's stem end) each
    // see the other in their wide turn: there the half-window test decides, if both
    // legs are straight (a small loop inside the window has no straight legs).
    const bool keeps_half = half && half->angle >= kSharpRatio * full->angle;
    const bool sharp = wide ? *wide <= kWideRatio * full->angle || (keeps_half && straightLegs(line, i, *full, w))
                            : keeps_half;
    if (!sharp) continue;
    candidates.push_back({i, *full});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& x, const Candidate& y) { return x.turn.angle > y.turn.angle; });

  std::vector<std::ptrdiff_t> accepted;
  // A candidate within one window of an accepted corner is that corner seen off-centre.
  auto nearAccepted = [&](std::ptrdiff_t i) {
    return std::any_of(accepted.begin(), accepted.end(), [&](std::ptrdiff_t v) { return line.distance(v, i) < w; });
  };
  for (const Candidate& c : candidates) {
    if (nearAccepted(c.i)) continue;  // before the vertex search: on a long zigzag most are
    // The vertex: the point of the window farthest from the chord P_a P_b (the segment,
    // not its line: at a hairpin the chord is short and across the legs, and points far
    // along a leg are further from its line than the tip is).
    std::ptrdiff_t vertex = c.i;
    double farthest = -1.0;
    for (std::ptrdiff_t j = c.turn.a + 1; j < c.turn.b; ++j) {
      const double d = distanceToSegment(line.at(j), line.at(c.turn.a), line.at(c.turn.b));
      if (d > farthest) {
        farthest = d;
        vertex = line.wrap(j);
      }
    }
    if (!closed && (vertex < kMinSideSamples || vertex > n - 1 - kMinSideSamples)) vertex = c.i;
    if (!nearAccepted(vertex)) accepted.push_back(vertex);
  }
  if (ends_only)
    std::erase_if(accepted, [&](std::ptrdiff_t v) { return std::min(line.distance(v, 0), line.distance(v, n - 1)) >= w; });
  std::vector<std::size_t> corners(accepted.begin(), accepted.end());
  std::sort(corners.begin(), corners.end());
  return corners;
}

/// Length budget shared by the two hooks.
struct HookLimits {
  double max_length = 0.0;      // arc length the cut may remove
  std::size_t max_points = 0;   // points the cut may remove
};

/// Number of leading points of p that form a hook (0 if none). A candidate junction k
/// is accepted when
///  - the piece P_0..P_k is short (a hook's worth, Scales::hook_reach, at most
///    hook_max_samples points, and within the limits), nearly straight, and longer than
///    kHookMinNoise noise levels;
///  - its chord P_0 P_k turns by more than hook_min_angle against the chord from P_k
///    over the next window w;
///  - the turn at P_k is sharp (the corner test, with the hook side of the window cut
///    short at P_0).
/// Of several candidates the one with the largest turn is the junction.
std::size_t startHook(const std::vector<Vec2>& p, const Scales& scales, const HookLimits& limits,
                      const CleanupOptions& options) {
  const Polyline line(p, false);
  const std::vector<double>& s = line.pointArcLengths();
  const double max_length = std::min(scales.hook_reach, limits.max_length);
  const double w = scales.window;
  std::size_t best = 0;
  double best_turn = options.hook_min_angle;
  const std::size_t max_points = std::min(limits.max_points, options.hook_max_samples);
  for (std::size_t k = 1; k <= max_points && k < p.size() && s[k] <= max_length; ++k) {
    const Vec2 chord = p[k] - p[0];
    const bool short_chord = chord.norm() < kHookMinNoise * scales.noise;
    double deviation = 0.0;
    for (std::size_t j = 1; j < k; ++j) deviation = std::max(deviation, lineDistance(p[j], p[0], p[k]));
    if (deviation > kHookStraightness * chord.norm()) continue;
    const auto ki = static_cast<std::ptrdiff_t>(k);
    const auto b = line.walk(ki, +1, w, 2);
    if (!b) continue;
    const double turn = unsignedAngle(chord, line.at(*b) - p[k]);
    if (turn <= best_turn || (short_chord && turn <= kBackStepTurn)) continue;
    const auto full = line.turn(ki, w, 1);
    const auto half = line.turn(ki, 0.5 * w, 1);
    if (!full || !half) continue;
    if (half->angle < kSharpRatio * full->angle) continue;
    best = k;
    best_turn = turn;
  }
  return best;
}

/// Where a closed stroke is cut: points [first, end) are kept.
struct Seam {
  std::size_t first = 0;
  std::size_t end = 0;
};

/// Closure of an open point sequence, nullopt if it is open. With `reach` =
/// close_fraction * diagonal, the stroke is closed when, in its last
/// kMaxOverlapFraction of length,
///  - overlap: a segment passes within reach of the start; everything after the point
///    of that part nearest the start is cut;
///  - crossing: it crosses the line through the start normal to the start direction,
///    forwards, within kCrossReach * reach of the start (a circle drawn past its start
///    a little outside it); everything after the crossing is cut;
///  - gap: the end stops within reach of the start.
/// Then the seam: leading points within half a median step of the new end are dropped
/// (they repeat it), and so is a pen-down slip at the start (a spike: a piece that
/// would be a hook, turning sharply against the closing step too). If the closing step
/// then meets the stroke at a kink and the stroke ran on past its start (overlap or
/// crossing), the seam moves to the smoothest closing step within the doubly drawn
/// region (at most kSeamReach * reach long), unless that step still turns like a corner:
/// then the seam is a corner (a tip drawn past) and stays. A real corner at the seam
/// stays a corner (the stroke keeps it on one side of the step). A stroke closed by its gap keeps its
/// seam: there is nothing drawn twice to choose from.
std::optional<Seam> findSeam(const std::vector<Vec2>& p, const Scales& scales, const CleanupOptions& options) {
  const std::size_t n = p.size();
  if (n < 4) return std::nullopt;
  const Polyline line(p, false);
  const std::vector<double>& s = line.pointArcLengths();
  const double length = s.back();
  const double reach = options.close_fraction * boundingBoxDiagonal(p);
  const double tail_start = (1.0 - kMaxOverlapFraction) * length;

  // (on a pixel grid many distances and turns are equal, or exactly at a bound: a
  // comparison that rounding can tip picked another seam for the stroke moved, scaled or
  // turned, and a corner came and went with it. So the first of equal ones wins, and a
  // turn at a bound is beyond it, up to kTie of their scale)
  const double tie = kTie * boundingBoxDiagonal(p);
  double nearest_segment = std::numeric_limits<double>::infinity();
  std::size_t nearest_point = n - 1;
  double nearest_distance = (p[n - 1] - p[0]).norm();
  for (std::size_t j = 1; j < n; ++j) {
    if (s[j - 1] < tail_start) continue;
    nearest_segment = std::min(nearest_segment, segmentDistance(p[0], p[j - 1], p[j]));
    const double d = (p[j] - p[0]).norm();
    if (d < nearest_distance - tie) nearest_point = j, nearest_distance = d;
  }
  std::optional<std::size_t> last;
  if (nearest_segment <= reach) last = nearest_point;
  if (!last) {
    const auto ahead = line.walk(0, +1, scales.window, 2);
    const Vec2 d0 = ahead ? (line.at(*ahead) - p[0]).normalized() : Vec2::Zero();
    for (std::size_t j = 1; j < n && !last; ++j) {
      if (s[j - 1] < tail_start) continue;
      const double u0 = (p[j - 1] - p[0]).dot(d0), u1 = (p[j] - p[0]).dot(d0);
      if (!(u0 < 0.0 && u1 >= 0.0)) continue;
      const Vec2 crossing = p[j - 1] + (u0 / (u0 - u1)) * (p[j] - p[j - 1]);
      if (std::abs(cross(d0, crossing - p[0])) <= kCrossReach * reach) last = j - 1;
    }
  }
  if (!last && (p[n - 1] - p[0]).norm() <= reach) last = n - 1;
  if (!last) return std::nullopt;

  // The seam. Leading points that repeat the new end are dropped.
  const std::size_t m = *last;
  const double merge = kSeamMergeSteps * scales.median_step;
  std::size_t first = 0;
  while (first + 3 <= m && (p[first] - p[m]).norm() < merge) ++first;
  // Directions arriving at / leaving each point, over the corner window.
  auto arrival = [&](std::size_t j) -> std::optional<Vec2> {
    const auto a = line.walk(static_cast<std::ptrdiff_t>(j), -1, scales.window, 2);
    if (!a) return std::nullopt;
    return Vec2(p[j] - line.at(*a));
  };
  auto departure = [&](std::size_t i) -> std::optional<Vec2> {
    const auto b = line.walk(static_cast<std::ptrdiff_t>(i), +1, scales.window, 2);
    if (!b) return std::nullopt;
    return Vec2(line.at(*b) - p[i]);
  };
  // The larger of the two turns where the closing step P_j -> P_i meets the stroke.
  auto seamTurn = [&](std::size_t j, const Vec2& in, std::size_t i, const Vec2& out) {
    const Vec2 closing = p[i] - p[j];
    return std::max(unsignedAngle(in, closing), unsignedAngle(closing, out));
  };
  // A pen-down slip at the seam: a short straight first piece turning sharply against
  // both the closing step and the rest of the stroke (a spike) is dropped.
  {
    std::size_t spike = 0;
    double spike_turn = options.hook_min_angle;
    for (std::size_t k = 1; k <= options.hook_max_samples && first + k + 3 <= m &&
                            s[first + k] - s[first] <= scales.hook_reach;
         ++k) {
      const std::size_t j = first + k;
      const Vec2 chord = p[j] - p[first];
      const bool short_chord = chord.norm() < kHookMinNoise * scales.noise;
      double deviation = 0.0;
      for (std::size_t i = first + 1; i < j; ++i) deviation = std::max(deviation, lineDistance(p[i], p[first], p[j]));
      if (deviation > kHookStraightness * chord.norm()) continue;
      const auto out = departure(j);
      if (!out) continue;
      // (within the noise only a back step counts, as at an open stroke's start)
      if (short_chord && unsignedAngle(chord, *out) <= kBackStepTurn) continue;
      const double turn = std::min(unsignedAngle(p[first] - p[m], chord), unsignedAngle(chord, *out));
      if (turn > spike_turn) {
        spike = k;
        spike_turn = turn;
      }
    }
    first += spike;
  }
  const auto in_m = arrival(m);
  const auto out_first = departure(first);
  const double kink = in_m && out_first ? seamTurn(m, *in_m, first, *out_first) : 0.0;
  if (m + 1 < n && kink > kSeamSmoothFraction * options.corner_min_angle) {
    // A kinked seam where the stroke ran on past its start: the tail from m on and the
    // head up to its point nearest the stroke's end were drawn twice, and the seam may be
    // anywhere in that doubled region. It moves to the pair of points there whose
    // closing step turns least, if that turns less (a circle drawn past its start beside
    // it: the step bridges the sideways miss). The doubled points dropped leave a gap for
    // the fairing to fill. If the tail's end runs along the head (within kSeamParallel),
    // the region extends by kCrossReach * reach at both ends, room for a gentle bridge; if
    // not, the start is a corner with no doubled region around it to cut.
    std::size_t head_end = first;
    double head_distance = (p[first] - p[n - 1]).norm();
    for (std::size_t i = first; i < n && s[i] <= kMaxOverlapFraction * length; ++i) {
      const double d = (p[i] - p[n - 1]).norm();
      if (d < head_distance - tie) head_end = i, head_distance = d;
    }
    const auto tail_in = arrival(n - 1);
    const auto head_out = departure(head_end);
    double head_limit = s[head_end], tail_limit = s[m];
    if (tail_in && head_out && unsignedAngle(*tail_in, *head_out) < kSeamParallel - kTie) {
      head_limit = std::min(head_limit + kCrossReach * reach, kMaxOverlapFraction * length);
      tail_limit = std::max(tail_limit - kCrossReach * reach, tail_start);
    }
    // (every stride-th point of each region is a candidate, kMaxSeamCandidates)
    std::size_t head_count = 0, tail_count = 0;
    for (std::size_t i = first; i < n && s[i] <= head_limit; ++i) ++head_count;
    for (std::size_t j = n - 1; j >= 3 && s[j] >= tail_limit; --j) ++tail_count;
    const std::size_t head_stride = 1 + head_count / kMaxSeamCandidates, tail_stride = 1 + tail_count / kMaxSeamCandidates;
    std::vector<std::optional<Vec2>> out(n);
    for (std::size_t i = first; i < n && s[i] <= head_limit; i += head_stride) out[i] = departure(i);
    // (a step is better than the kinked seam where it turns less, and no more than a
    // corner: a star's tip drawn past has no smooth step, and moved to the smoothest, the
    // seam left the overshoot as a hook beside the tip)
    double best = std::min(kink, options.corner_min_angle);
    std::optional<Seam> better;
    for (std::size_t j = n - 1; j >= 3 && s[j] >= tail_limit; j = j >= tail_stride ? j - tail_stride : 0) {
      const auto in = arrival(j);
      if (!in) continue;
      for (std::size_t i = first; s[i] <= head_limit && i + 3 <= j; i += head_stride) {
        const double gap = (p[i] - p[j]).norm();
        if (gap < merge || gap > kSeamReach * reach || !out[i]) continue;
        const double turn = seamTurn(j, *in, i, *out[i]);
        if (turn < best - kTie) {
          best = turn;
          better = Seam{i, j + 1};
        }
      }
    }
    if (better) return better;
  }
  if (m + 1 - first < kMinClosedPoints) return std::nullopt;
  return Seam{first, m + 1};
}

[[noreturn]] void fail(const std::string& what, std::size_t samples, const CleanStroke& c) {
  std::ostringstream message;
  message << "stroke cannot be fitted: " << what << " (" << samples << " samples: " << c.removed_invalid
          << " non-finite, " << c.removed_duplicates << " duplicates";
  if (c.removed_resampled > 0) message << ", " << c.removed_resampled << " resampled";
  if (c.trimmed_start + c.trimmed_end > 0) message << ", " << c.trimmed_start + c.trimmed_end << " trimmed as hooks";
  if (c.removed_overlap > 0) message << ", " << c.removed_overlap << " cut as closing overlap";
  message << ", " << c.points.size() << " left)";
  throw StrokeError(message.str());
}

bool collinear(const std::vector<Vec2>& p) {
  return p.size() < 3 || lineDeviation(p) < kCollinearTolerance * boundingBoxDiagonal(p);
}

// A closed stroke's points (and their sources and corners) rotated to start at points[shift].
void startClosedAt(CleanStroke& stroke, std::size_t shift) {
  const std::size_t n = stroke.points.size();
  const auto offset = static_cast<std::ptrdiff_t>(shift);
  std::rotate(stroke.points.begin(), stroke.points.begin() + offset, stroke.points.end());
  std::rotate(stroke.source.begin(), stroke.source.begin() + offset, stroke.source.end());
  for (std::size_t& c : stroke.corners) c = (c + n - shift) % n;
  std::sort(stroke.corners.begin(), stroke.corners.end());
}

}  // namespace

CleanStroke cleanStroke(const Stroke& raw, const CleanupOptions& options, double tolerance) {
  CleanStroke result;
  const std::size_t samples = raw.samples.size();

  // 1. Non-finite samples, then consecutive duplicates.
  std::vector<Vec2> finite;
  std::vector<std::size_t> finite_source;
  for (std::size_t i = 0; i < samples; ++i) {
    if (!allFinite(raw.samples[i].p)) {
      ++result.removed_invalid;
      result.left_out.push_back({i, LeftOutReason::kNonFinite});
      continue;
    }
    finite.push_back(raw.samples[i].p);
    finite_source.push_back(i);
  }
  // Distances between such points overflow (squares above 1e308): every threshold
  // below would be infinite and every point a duplicate.
  for (const Vec2& q : finite)
    if (q.cwiseAbs().maxCoeff() > kLargestCoordinate) {
      result.points = finite;
      fail("coordinates beyond 1e150 (distances between them overflow)", samples, result);
    }
  const double duplicate_distance = kDuplicateTolerance * boundingBoxDiagonal(finite);
  Points pts;
  pts.left_out = &result.left_out;
  for (std::size_t i = 0; i < finite.size(); ++i) {
    if (!pts.p.empty() && (finite[i] - pts.p.back()).norm() <= duplicate_distance) {
      ++result.removed_duplicates;
      result.left_out.push_back({finite_source[i], LeftOutReason::kDuplicate});
      continue;
    }
    pts.p.push_back(finite[i]);
    pts.src.push_back(finite_source[i]);
  }
  auto publish = [&] {
    result.points = pts.p;
    result.source = pts.src;
    std::sort(result.left_out.begin(), result.left_out.end(),
              [](const LeftOutPoint& a, const LeftOutPoint& b) { return a.sample < b.sample; });
    result.left_out_fraction = leftOutFraction(raw, result.left_out);
  };
  if (pts.size() < 2) {
    publish();
    fail("fewer than 2 distinct finite points", samples, result);
  }
  if (collinear(pts.p)) {
    publish();
    result.diagonal = boundingBoxDiagonal(pts.p);
    result.straight = true;
    return result;
  }
  // From here on no step removes points if that would leave them collinear: a stroke
  // that can be fitted stays so.

  // 1b. Points a resampler put evenly on the chords between the samples say nothing the
  // samples do not (fitting/subdivision.h): left out like duplicates (a 4-fold
  // subdivision in two rounds). (Not on a straight stroke: evenly sampled, its points
  // are all midpoints, and its line is fitted to them as they are.)
  for (std::vector<bool> sample; !(sample = resamplerSamples(pts.p)).empty();)
    result.removed_resampled += pts.keepOnly(sample, LeftOutReason::kResampled);

  // 2. (A long first or last step is a segment of the stroke, drawn or not: nothing is
  // dropped for its length alone. Hooks, which turn sharply, are step 4.)

  // 3. Closed?
  auto close = [&](const Seam& seam) {
    result.closed = true;
    result.removed_overlap += seam.first + (pts.size() - seam.end);
    pts.keepFront(seam.end, LeftOutReason::kOverlap);
    pts.dropFront(seam.first, LeftOutReason::kOverlap);
  };
  const double hook_tolerance = tolerance > 0.0 ? tolerance : kDefaultToleranceFraction * boundingBoxDiagonal(pts.p);
  Scales scales = measureScales(pts.p, false, options, hook_tolerance);
  const std::size_t measured = pts.size();  // (points are only ever cut off: the same count, the same points)
  if (options.assume_closed || options.detect_closed) {
    if (const auto seam = findSeam(pts.p, scales, options)) close(*seam);
  }
  if (options.assume_closed) result.closed = true;

  // 4. Hooks at both ends of an open stroke; then closure once more.
  if (!result.closed && pts.size() > 3) {
    const double drawn_length = arcLengths(pts.p).back();
    HookLimits limits{(1.0 - kMinKeptFraction) * drawn_length, pts.size() - 3};
    std::size_t start = startHook(pts.p, scales, limits, options);
    if (start > 0 && collinear(std::vector<Vec2>(pts.p.begin() + static_cast<std::ptrdiff_t>(start), pts.p.end()))) start = 0;
    if (start > 0) {
      limits.max_length -= arcLengths(pts.p)[start];
      limits.max_points -= start;
      pts.dropFront(start, LeftOutReason::kStartHook);
      result.trimmed_start += start;
    }
    const std::vector<Vec2> reversed(pts.p.rbegin(), pts.p.rend());
    std::size_t end = startHook(reversed, scales, limits, options);
    if (end > 0 && collinear(std::vector<Vec2>(pts.p.begin(), pts.p.end() - static_cast<std::ptrdiff_t>(end)))) end = 0;
    if (end > 0) {
      pts.keepFront(pts.size() - end, LeftOutReason::kEndHook);
      result.trimmed_end += end;
    }
    if ((start > 0 || end > 0) && options.detect_closed) {
      if (const auto seam = findSeam(pts.p, scales, options)) close(*seam);
    }
  }

  // 5. Input errors (the seam of a closed stroke could leave too little).
  publish();
  result.diagonal = boundingBoxDiagonal(pts.p);
  if (pts.size() < measured && collinear(pts.p)) {  // (a closed stroke's seam cut can leave a line)
    result.straight = true;
    result.closed = false;
    return result;
  }
  if (result.closed && pts.size() < kMinClosedPoints) fail("a closed curve needs at least 4 points", samples, result);

  // 6. Corners; a closed stroke starts at its corner nearest the original start.
  if (options.detect_corners) {
    if (pts.size() < measured) scales = measureScales(pts.p, result.closed, options, hook_tolerance);
    else scales.window = cornerWindow(pts.p, result.closed, scales.noise, options);
    result.corners = findCorners(pts.p, result.closed, scales.window, options, raw.profile);
  }
  if (result.closed && !result.corners.empty()) {
    const std::size_t n = pts.size();
    std::size_t shift = result.corners.front();
    for (std::size_t c : result.corners) {
      if (std::min(c, n - c) < std::min(shift, n - shift)) shift = c;
    }
    startClosedAt(result, shift);
  }
  return result;
}

bool canBeCorner(const CleanStroke& stroke, std::size_t index) {
  const std::size_t n = stroke.points.size();
  constexpr std::size_t kApart = 2;  // (a part between two corners has 3 points or more)
  if (index >= n || (!stroke.closed && (index < kApart || index + kApart >= n))) return false;
  return std::none_of(stroke.corners.begin(), stroke.corners.end(), [&](std::size_t c) {
    const std::size_t apart = c > index ? c - index : index - c;
    return std::min(apart, stroke.closed ? n - apart : apart) < kApart;
  });
}

bool addCorner(CleanStroke& stroke, std::size_t index) {
  if (!canBeCorner(stroke, index)) return false;
  stroke.corners.insert(std::upper_bound(stroke.corners.begin(), stroke.corners.end(), index), index);
  if (stroke.closed) startClosedAt(stroke, stroke.corners.front());
  return true;
}

bool liesOnKeptPoints(LeftOutReason reason) {
  return reason == LeftOutReason::kDuplicate || reason == LeftOutReason::kResampled;
}

const char* toString(LeftOutReason reason) {
  switch (reason) {
    case LeftOutReason::kNonFinite: return "not a finite number";
    case LeftOutReason::kDuplicate: return "duplicate";
    case LeftOutReason::kResampled: return "resampled";
    case LeftOutReason::kStartHook: return "pen-down hook";
    case LeftOutReason::kEndHook: return "pen-up hook";
    case LeftOutReason::kOverlap: return "closing overlap";
  }
  return "unknown";
}

}  // namespace la
