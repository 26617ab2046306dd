#pragma once
// A curve: a chain of LA segments (DESIGN.md section 5).
//
// Segment i + 1 starts where segment i ends. Every joint is G2 (position, tangent
// angle and curvature continuous) unless the later segment is marked `corner`, in
// which case the joint is a deliberate G0 corner: only the positions meet. In a
// closed curve the joint from the last segment back to the first is a joint like
// any other (G2, or a corner when pieces[0] is marked). The flag of pieces[0] of an
// open curve has no joint to describe and is kept only so that it round-trips.
//
// These are plain data: nothing here checks the joints. Readers of the shared JSON
// format (core/curve_json.h) check each segment, not the continuity between them;
// measure the gaps with the curve analysis code or the independent checker
// (shared/tools/lacheck.py).

#include <vector>

#include "core/la_segment.h"

namespace la {

struct CurvePiece {
  LaSegment segment;
  bool corner = false;  // starts at a deliberate G0 corner
};

struct Curve {
  std::vector<CurvePiece> pieces;
  bool closed = false;  // the last segment's end joins the first segment's start
};

/// The chain of `segments` as a curve without corners.
inline Curve curveOf(const std::vector<LaSegment>& segments, bool closed = false) {
  Curve c;
  c.closed = closed;
  for (const LaSegment& s : segments) c.pieces.push_back({s, false});
  return c;
}

}  // namespace la
