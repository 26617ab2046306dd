#include "app/gui/markers.h"

#include <set>

#include "fitting/quality.h"

namespace la::gui {
namespace {

constexpr double kMarkerRadius = 5.0;  // pixels: visible over a 2.2-pixel curve, small beside a comb tooth

}  // namespace

QString markerName(MarkerKind kind) {
  switch (kind) {
    case MarkerKind::kEnd: return "curve end";
    case MarkerKind::kJoint: return "joint (G2)";
    case MarkerKind::kInflection: return "inflection";
    case MarkerKind::kExtremum: return "curvature extremum";
    case MarkerKind::kCorner: return "corner (G0)";
  }
  return {};
}

std::vector<CurveMarker> curveMarkers(const Curve& curve, double diagonal) {
  std::vector<CurveMarker> out;
  const auto& pieces = curve.pieces;
  if (pieces.empty()) return out;
  std::set<std::size_t> extrema;
  for (const auto& part : extremumJoints(curve, diagonal)) extrema.insert(part.begin(), part.end());
  const std::size_t n = pieces.size();
  for (std::size_t i = 0; i < n; ++i) {
    const LaSegment& seg = pieces[i].segment;
    if (i == 0 && !curve.closed) {
      out.push_back({seg.start(), MarkerKind::kEnd});
      continue;
    }
    const LaSegment& before = pieces[(i + n - 1) % n].segment;
    MarkerKind kind = MarkerKind::kJoint;
    if (pieces[i].corner) kind = MarkerKind::kCorner;
    else if (seg.kappaStart() == 0.0 || before.kappaEnd() == 0.0 || seg.kappaStart() * before.kappaEnd() < 0.0)
      kind = MarkerKind::kInflection;
    else if (extrema.count(i)) kind = MarkerKind::kExtremum;
    out.push_back({seg.start(), kind});
  }
  if (!curve.closed) out.push_back({pieces.back().segment.end(), MarkerKind::kEnd});
  return out;
}

void drawMarker(QPainter& p, MarkerKind kind, const QPointF& at) {
  const double r = kMarkerRadius;
  p.save();
  p.setBrush(Qt::NoBrush);
  switch (kind) {
    case MarkerKind::kEnd:  // a filled dot
      p.setBrush(p.pen().color());
      p.drawEllipse(at, 0.7 * r, 0.7 * r);
      break;
    case MarkerKind::kJoint:  // a square
      p.drawRect(QRectF(at - QPointF(0.8 * r, 0.8 * r), QSizeF(1.6 * r, 1.6 * r)));
      break;
    case MarkerKind::kInflection:  // a circle
      p.drawEllipse(at, r, r);
      break;
    case MarkerKind::kExtremum:  // a triangle, point up
      p.drawPolygon(QPolygonF({at + QPointF(0, -1.2 * r), at + QPointF(1.1 * r, 0.8 * r), at + QPointF(-1.1 * r, 0.8 * r)}));
      break;
    case MarkerKind::kCorner:  // a cross
      p.drawLine(at + QPointF(-r, -r), at + QPointF(r, r));
      p.drawLine(at + QPointF(-r, r), at + QPointF(r, -r));
      break;
  }
  p.restore();
}

}  // namespace la::gui
