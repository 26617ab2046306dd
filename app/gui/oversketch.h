#pragma once
// Oversketch: a stroke drawn starting and/or ending near an existing stroke replaces the
// part of it between those points (Illustrator's pencil "edit selected paths", Inkscape's
// pencil, Cornucopia). As Cornucopia and Inkscape do it, the raw samples are spliced, not
// the curves: old samples before the first join + the new samples + old samples after the
// second join make one raw stroke, which is then fitted like any stroke. The fitter makes
// the result G2 where the new stroke runs on smoothly and finds a corner where it meets
// the old one at an angle, so no joining math is needed here.
//
// A join is the point of the old stroke's raw polyline nearest the new stroke's end point,
// taken when that end point is within `reach` of the stroke (its fitted curve or its raw
// polyline). The cases:
//  - both ends join (open stroke): the middle between the joins is replaced; a new stroke
//    running against the old one's direction is reversed first. Joins at opposite ends
//    close the stroke instead (old + new);
//  - one end joins: from that join to the nearer end of the old stroke is replaced (at the
//    end itself: an extension);
//  - closed stroke, both ends join: the shorter arc between the joins is replaced, the
//    loop keeping its direction (the new stroke reversed where it runs against it);
//    a closed stroke with one join is not oversketched (there is no "nearer end").
// No Qt widgets here: the window converts its pixel reach to world units.

#include <cstddef>
#include <optional>
#include <vector>

#include "app/gui/document.h"

namespace la::gui {

/// How far (pixels) from a stroke a new stroke's end still joins it, unless the user sets
/// another (Edit > Oversketch reach): a few pixels, as Inkscape's pencil snaps.
inline constexpr double kDefaultOversketchReachPixels = 8.0;

/// Where one end of the new stroke meets the old stroke's polyline.
struct OversketchJoin {
  double s = 0.0;         // arc length along the old polyline (loop order for a closed stroke)
  double distance = 0.0;  // from the new stroke's end to the old stroke (world units)
};

struct Oversketch {
  Stroke raw;  // the stroke to fit in place of the old one
  std::optional<OversketchJoin> start, end;  // the new stroke's joins (start and end as drawn)
  bool reversed = false;  // the new samples were put in reversed to run with the old stroke
  bool closes = false;    // the new stroke joined an open stroke's two ends: the result is closed
  /// Which old samples were kept (indices into the old polyline: raw samples for an open
  /// stroke, `loop` order for a closed one): [0, kept_before) before the new samples and
  /// [kept_after, n) after them (open); for a closed stroke the kept arc is the range
  /// kept_after .. kept_before going forward, wrapping.
  std::size_t kept_before = 0, kept_after = 0;
};

/// The old stroke's samples in loop order for a closed fit (the raw samples the clean-up
/// kept, as it ordered them), or the raw samples for an open one.
std::vector<StrokeSample> oversketchPolyline(const DocumentStroke& old);

/// The splice of `drawn` into `old`, or nothing if neither end of `drawn` is within
/// `reach` (world units) of it, or `drawn` has fewer than 2 samples.
std::optional<Oversketch> oversketch(const DocumentStroke& old, const Stroke& drawn, double reach);

/// The stroke of `document` that `drawn` oversketches (the one whose joins are nearest;
/// two joins before one), with the splice; nothing if none is in reach.
struct OversketchTarget {
  std::size_t stroke = 0;
  Oversketch splice;
};
std::optional<OversketchTarget> findOversketch(const Document& document, const Stroke& drawn, double reach);

}  // namespace la::gui
