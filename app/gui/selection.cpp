#include "app/gui/selection.h"

#include <algorithm>
#include <cmath>

namespace la::gui {
namespace {

constexpr int kSamplesPerSegment = 48;  // a polyline close enough to pick within a pixel or two

double distanceToSegment(const QPointF& p, const QPointF& a, const QPointF& b) {
  const QPointF ab = b - a, ap = p - a;
  const double len2 = QPointF::dotProduct(ab, ab);
  const double t = len2 > 0 ? std::clamp(QPointF::dotProduct(ap, ab) / len2, 0.0, 1.0) : 0.0;
  const QPointF q = a + t * ab - p;
  return std::hypot(q.x(), q.y());
}

QPointF map(const QTransform& view, const Vec2& q) { return view.map(QPointF(q.x(), q.y())); }

}  // namespace

std::vector<std::size_t> Selection::indices(const Document& document) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < document.strokes().size(); ++i)
    if (contains(document.strokes()[i])) out.push_back(i);
  return out;
}

void Selection::toggle(const DocumentStroke& stroke) {
  if (!m_ids.erase(stroke.id)) m_ids.insert(stroke.id);
}

void Selection::set(const Document& document, const std::vector<std::size_t>& indices) {
  m_ids.clear();
  for (std::size_t i : indices)
    if (i < document.strokes().size()) m_ids.insert(document.strokes()[i].id);
}

std::vector<Vec2> strokeOutline(const DocumentStroke& stroke) {
  std::vector<Vec2> out;
  if (!stroke.fit) {
    for (const StrokeSample& s : stroke.raw.samples) out.push_back(s.p);
    return out;
  }
  for (const CurvePiece& piece : stroke.fit->curve.pieces) {
    const CurveSamples smp = piece.segment.sample(kSamplesPerSegment);
    out.insert(out.end(), smp.point.begin(), smp.point.end());
  }
  return out;
}

StrokeHit strokeAt(const Document& document, const QTransform& view, const QPointF& at, double reach) {
  StrokeHit hit;
  double best = reach;
  for (std::size_t k = 0; k < document.strokes().size(); ++k) {
    const DocumentStroke& s = document.strokes()[k];
    if (s.fit) {  // the curve, segment by segment, as a polyline
      for (std::size_t i = 0; i < s.fit->curve.pieces.size(); ++i) {
        const CurveSamples smp = s.fit->curve.pieces[i].segment.sample(kSamplesPerSegment);
        for (std::size_t j = 1; j < smp.size(); ++j) {
          const double d = distanceToSegment(at, map(view, smp.point[j - 1]), map(view, smp.point[j]));
          if (d <= best) best = d, hit = {static_cast<int>(k), static_cast<int>(i)};
        }
      }
    }
    for (const StrokeSample& q : s.raw.samples) {  // and the points (what the user drew)
      const QPointF w = map(view, q.p);
      const double d = std::hypot(w.x() - at.x(), w.y() - at.y());
      if (d < best) best = d, hit = {static_cast<int>(k), -1};
    }
  }
  // a hit on the raw points still names the segment nearest, for the panels that follow it
  if (hit.stroke >= 0 && hit.piece < 0 && document.strokes()[hit.stroke].fit) {
    double nearest = INFINITY;
    const auto& pieces = document.strokes()[hit.stroke].fit->curve.pieces;
    for (std::size_t i = 0; i < pieces.size(); ++i)
      for (const Vec2& q : pieces[i].segment.sample(kSamplesPerSegment).point) {
        const QPointF w = map(view, q);
        const double d = std::hypot(w.x() - at.x(), w.y() - at.y());
        if (d < nearest) nearest = d, hit.piece = static_cast<int>(i);
      }
  }
  return hit;
}

std::vector<std::size_t> strokesInside(const Document& document, const QTransform& view, const QRectF& band) {
  std::vector<std::size_t> out;
  const QRectF r = band.normalized();
  for (std::size_t k = 0; k < document.strokes().size(); ++k) {
    const DocumentStroke& s = document.strokes()[k];
    auto inside = [&](const Vec2& q) { return r.contains(map(view, q)); };
    bool all = !s.raw.samples.empty();
    for (const StrokeSample& q : s.raw.samples) all = all && inside(q.p);
    for (const Vec2& q : strokeOutline(s)) all = all && inside(q);
    if (all) out.push_back(k);
  }
  return out;
}

}  // namespace la::gui
