#pragma once
// A pen stroke as recorded, and the clean-up before fitting (DESIGN.md section 3,
// stage 1): NaNs, duplicate and resampled points out, pen-down / pen-up hooks trimmed,
// deliberate corners found, closed strokes recognised. The raw stroke is never modified.
//
// The steps, in order (fitting/stroke.cpp explains each one and its constants):
//  1. drop non-finite samples, then consecutive duplicates (distance <= 1e-9 of the
//     bounding-box diagonal; the first of a run is kept), then, unless the points are
//     all on one line, the points a resampler put evenly between the samples
//     (fitting/subdivision.h: a stroke subdivided 2-, 3- or 4-fold is cleaned and fitted
//     as drawn);
//  2. nothing else is dropped at the ends for its length alone: a long first or last
//     step is a segment of the stroke (a digitizer's jump to where the drawing starts
//     is drawn as such);
//  3. closed? (detect_closed): the end comes back within close_fraction * diagonal of
//     the start; or the last quarter of the stroke passes within that distance of the
//     start, or crosses the start's normal line within twice that distance (a circle
//     drawn past its start), and everything after the point nearest the start (the
//     crossing) is cut. At the seam, first points that repeat the last one or form a
//     pen-down slip are dropped, and a kinked seam of a stroke drawn past its start is
//     moved within the doubly drawn part to where the closing step turns least, if that
//     step turns less than a corner (else the seam is a corner drawn past, and stays).
//     assume_closed skips the test (glyph contours, SVG paths with Z): the stroke is
//     closed whatever its gap;
//  4. hooks (open strokes only): a short straight end piece (a hook's worth: at most 6
//     median steps or 4 tolerances long, whichever is longer, and <= hook_max_samples
//     samples; longer than the sampling noise) that meets the rest at a sharp turn of
//     more than hook_min_angle is cut. Directions are chords over an arc-length window,
//     so 1-px quantization does not trigger it, and a smooth end curl is not a hook. 70%
//     of the length and 3 points always remain. If a hook was cut, step 3 is tried again;
//  5. throws StrokeError if fewer than 2 distinct points remain (a dot: no direction);
//     points all on one line, two distinct points too (a short dash), are a straight
//     stroke, returned after step 1 (no trimming step removes points if that would leave
//     the rest collinear);
//  6. corners (detect_corners): see the options.
//
// Closed strokes: `points` do not repeat the first point at the end (the closing step
// runs from points.back() to points.front()). A closed stroke that has corners is
// rotated so that the corner nearest its start is at index 0 (corners.front() == 0);
// `source` is rotated with it. Without corners the start is kept.

#include <cstddef>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/geometry.h"

namespace la {

struct StrokeSample {
  Vec2 p = Vec2::Zero();
  double t = std::numeric_limits<double>::quiet_NaN();         // time stamp (ms), NaN if unknown
  double pressure = std::numeric_limits<double>::quiet_NaN();  // 0..1 or device units, NaN if unknown
  double tilt_x = std::numeric_limits<double>::quiet_NaN();    // pen tilt in degrees (tablets), NaN if unknown
  double tilt_y = std::numeric_limits<double>::quiet_NaN();
};

struct Stroke {
  std::vector<StrokeSample> samples;
  /// A profile (read from an airfoil .dat: from the trailing edge round the leading
  /// edge and back): the clean-up keeps corners only within one corner window of its
  /// first or last point. A round leading edge sampled a few points across turns like a
  /// corner over the window.
  bool profile = false;
};

struct StrokeError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct CleanupOptions {
  /// Hooks: an end piece no longer than a hook's worth (6 median steps or 4 tolerances,
  /// whichever is longer) and made of at most hook_max_samples samples, that turns by
  /// more than hook_min_angle against the rest, is cut off. A hook is the pen slipping
  /// as it lands or lifts, which takes a few samples at 60-120 Hz (1-5 in the $1 and MMG
  /// stylus data); a deliberate short leg takes longer (10-22 samples in the Omniglot
  /// and MMG star strokes). Raise hook_max_samples for devices that sample much faster.
  double hook_min_angle = 1.2;  // radians (~70 degrees)
  std::size_t hook_max_samples = 6;
  /// Corners: a point where the stroke turns by more than corner_min_angle within a
  /// short window (corner_window of the stroke length, at least 2 samples a side, and
  /// on open strokes the whole window inside the stroke) is a deliberate corner; the
  /// stroke is faired piecewise between corners. The turn must be sharp: over three
  /// windows it must not grow much (a circular arc turns 3 times as much, a corner as
  /// much), so a small circle, a pigtail's loop or a question mark's top is not a corner.
  /// One corner gives one index (the point farthest from the chord across the window);
  /// corners closer than one window are one. The window is never shorter than 8 times
  /// the sampling noise (half a pixel on pixel-quantized input).
  bool detect_corners = true;
  double corner_min_angle = 1.0;  // radians (~57 degrees)
  double corner_window = 0.03;
  /// Closed: the end comes back within this fraction of the bounding-box diagonal of
  /// the start (or runs past it within that distance, or crosses its normal line within
  /// twice that distance); the overlap is cut and the curve closes.
  bool detect_closed = true;
  double close_fraction = 0.06;
  /// The input is known to be a closed contour (a font outline, an SVG path ending in Z):
  /// closed whatever the gap between its ends; no outlier or hook trimming.
  bool assume_closed = false;
};

/// Why the clean-up left a raw sample out of the points to fit.
enum class LeftOutReason { kNonFinite, kDuplicate, kResampled, kStartHook, kEndHook, kOverlap };
const char* toString(LeftOutReason reason);
/// A duplicate or a resampler's point: it lies on the polyline of the points kept.
bool liesOnKeptPoints(LeftOutReason reason);

struct LeftOutPoint {
  std::size_t sample = 0;  // index in the raw stroke
  LeftOutReason why = LeftOutReason::kDuplicate;
};

struct CleanStroke {
  std::vector<Vec2> points;          // the points to fit, in order
  std::vector<std::size_t> source;   // index of each point in the raw stroke
  /// Indices into `points` of deliberate corners, increasing. Open stroke: interior
  /// points only (at least 2 samples and one corner window from either end). Closed
  /// stroke: if there is any corner, corners.front() == 0 (the points are rotated so).
  std::vector<std::size_t> corners;
  bool closed = false;
  /// All points lie on one straight line (within 1e-9 of the diagonal): the curve is
  /// that line, or lines where the stroke turns back along it; no other clean-up step
  /// ran (no closure, hooks or corners).
  bool straight = false;
  std::size_t trimmed_start = 0;     // raw samples removed as a pen-down hook
  std::size_t trimmed_end = 0;       // raw samples removed as a pen-up hook
  std::size_t removed_overlap = 0;   // raw samples cut where a closed stroke overlaps its start
  std::size_t removed_invalid = 0;   // NaN / infinite samples dropped
  std::size_t removed_duplicates = 0;
  /// Points a resampler put between the samples (fitting/subdivision.h); like duplicates,
  /// they lie on the kept points' polyline.
  std::size_t removed_resampled = 0;
  /// Every raw sample left out, in raw order, with why.
  std::vector<LeftOutPoint> left_out;
  /// The fraction of the drawn length (the raw stroke's finite polyline) that the steps
  /// touching a left-out sample span (a duplicate spans nothing): what the curve does not
  /// claim to follow.
  double left_out_fraction = 0.0;
  double diagonal = 0.0;             // bounding-box diagonal of `points`
  // Every raw sample is accounted for exactly once:
  // samples = points + trimmed_start + trimmed_end + removed_overlap + removed_invalid
  //           + removed_duplicates + removed_resampled.
};

/// Throws StrokeError if fewer than 2 distinct finite points remain (a dot: nothing to
/// fair); the message gives the counts. Points all on one line (two distinct points
/// among them) come back `straight`.
/// `tolerance` is the fit's (absolute), which a hook's worth is tied to; 0: 0.5% of the
/// points' bounding-box diagonal, FitOptions' default.
CleanStroke cleanStroke(const Stroke& raw, const CleanupOptions& options = {}, double tolerance = 0.0);

/// Whether points[index] can be a corner: two points or more from every corner and
/// (open stroke) from either end.
bool canBeCorner(const CleanStroke& stroke, std::size_t index);

/// Makes points[index] a corner where it can be one (canBeCorner), and says whether it
/// did. A closed stroke's points (and sources) are rotated so that its first corner stays
/// at index 0.
bool addCorner(CleanStroke& stroke, std::size_t index);

}  // namespace la
