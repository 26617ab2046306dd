#pragma once
// The strokes the user selected (the Select tool, Edit > Select all), and finding strokes
// under the cursor or inside a rubber band, in widget pixels. The selection holds stroke
// ids, not indices: it survives strokes being added, removed and put back by undo. It is
// view state, not part of the document (selecting is not an undo step).

#include <QPointF>
#include <QRectF>
#include <QTransform>
#include <cstdint>
#include <set>
#include <vector>

#include "app/gui/document.h"

namespace la::gui {

/// How far from a stroke's curve or points a click still picks it, in pixels (a
/// "few pixels", as Inkscape's default grab sensitivity).
inline constexpr double kPickReachPixels = 6.0;

class Selection {
 public:
  /// The selected strokes' indices in `document`, increasing (ids no longer there skipped).
  std::vector<std::size_t> indices(const Document& document) const;
  bool contains(const DocumentStroke& stroke) const { return m_ids.count(stroke.id) > 0; }
  bool empty() const { return m_ids.empty(); }
  void clear() { m_ids.clear(); }
  void add(const DocumentStroke& stroke) { m_ids.insert(stroke.id); }
  void toggle(const DocumentStroke& stroke);
  /// Exactly these strokes of `document`.
  void set(const Document& document, const std::vector<std::size_t>& indices);

 private:
  std::set<std::uint64_t> m_ids;
};

/// The stroke nearest `at` (widget pixels) within `reach` pixels of its fitted curve or of
/// its raw points, with the segment of that curve nearest it (-1 if it has no fit or the
/// raw points were nearer); stroke -1 if none is in reach. `view` maps world to widget.
struct StrokeHit {
  int stroke = -1;
  int piece = -1;
};
StrokeHit strokeAt(const Document& document, const QTransform& view, const QPointF& at, double reach = kPickReachPixels);

/// The strokes wholly inside `band` (widget pixels), curve and points, as Inkscape's
/// rubber band selects.
std::vector<std::size_t> strokesInside(const Document& document, const QTransform& view, const QRectF& band);

/// A stroke's outline for picking and for drawing its selection: the fitted curve's
/// samples (or the raw points where it has no fit), in world coordinates.
std::vector<Vec2> strokeOutline(const DocumentStroke& stroke);

}  // namespace la::gui
