#include "app/gui/import_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace la::gui {

std::optional<WorldBox> boundsOf(const std::vector<Stroke>& strokes) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  WorldBox box{Vec2(inf, inf), Vec2(-inf, -inf)};
  for (const Stroke& s : strokes)
    for (const StrokeSample& q : s.samples) {
      if (!std::isfinite(q.p.x()) || !std::isfinite(q.p.y())) continue;  // (the clean-up drops them too)
      box.lo = box.lo.cwiseMin(q.p);
      box.hi = box.hi.cwiseMax(q.p);
    }
  if (!(box.lo.x() <= box.hi.x())) return std::nullopt;
  return box;
}

std::optional<Similarity> fitToView(const std::vector<Stroke>& strokes, const WorldBox& view) {
  const std::optional<WorldBox> box = boundsOf(strokes);
  const Vec2 room = view.size();
  if (!box || !(room.x() > 0.0) || !(room.y() > 0.0)) return std::nullopt;
  const Vec2 size = box->size();
  // the tighter of the two directions, ignoring one in which the points have no extent
  double scale = std::numeric_limits<double>::infinity();
  if (size.x() > 0.0) scale = std::min(scale, kFitToViewFill * room.x() / size.x());
  if (size.y() > 0.0) scale = std::min(scale, kFitToViewFill * room.y() / size.y());
  if (!std::isfinite(scale)) scale = 1.0;  // one point: nothing to scale
  Similarity t;
  t.scale = scale;
  t.offset = view.center() - scale * box->center();
  return t;
}

void applySimilarity(std::vector<Stroke>& strokes, const Similarity& t) {
  for (Stroke& s : strokes)
    for (StrokeSample& q : s.samples) q.p = t.apply(q.p);
}

}  // namespace la::gui
