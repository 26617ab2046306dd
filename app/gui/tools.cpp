#include "app/gui/tools.h"

#include <QPainter>
#include <QPainterPath>
#include <QPixmap>
#include <tuple>

namespace la::gui {

QIcon toolIcon(std::optional<Tool> tool) {
  constexpr int kSize = 32;  // drawn at twice the toolbar's usual size: crisp on high-dpi screens
  QPixmap pixmap(kSize, kSize);
  pixmap.fill(Qt::transparent);
  QPainter p(&pixmap);
  p.setRenderHint(QPainter::Antialiasing);
  p.setPen(QPen(QColor(40, 40, 40), 2.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  if (!tool) {  // a control triangle with the curve through it
    p.drawPolyline(QPolygonF({QPointF(4, 26), QPointF(16, 6), QPointF(28, 26)}));
    QPainterPath curve(QPointF(4, 26));
    curve.quadTo(QPointF(16, 6), QPointF(28, 26));
    p.setPen(QPen(QColor(27, 94, 32), 2.5));
    p.drawPath(curve);
  } else if (*tool == Tool::kDraw) {  // a pen nib over a stroke
    QPainterPath stroke(QPointF(3, 28));
    stroke.cubicTo(QPointF(8, 18), QPointF(14, 30), QPointF(18, 20));
    p.drawPath(stroke);
    p.setBrush(QColor(21, 101, 192));
    p.drawPolygon(QPolygonF({QPointF(18, 20), QPointF(21, 12), QPointF(29, 4), QPointF(31, 6), QPointF(23, 14)}));
  } else if (*tool == Tool::kSelect) {  // an arrow
    p.setBrush(Qt::white);
    p.drawPolygon(QPolygonF({QPointF(8, 3), QPointF(8, 26), QPointF(13, 21), QPointF(17, 30), QPointF(21, 28),
                             QPointF(17, 19), QPointF(24, 19)}));
  } else {  // four arrows
    p.drawLine(QPointF(16, 3), QPointF(16, 29));
    p.drawLine(QPointF(3, 16), QPointF(29, 16));
    for (const auto& [tip, a, b] : {std::tuple{QPointF(16, 3), QPointF(12, 7), QPointF(20, 7)},
                                    std::tuple{QPointF(16, 29), QPointF(12, 25), QPointF(20, 25)},
                                    std::tuple{QPointF(3, 16), QPointF(7, 12), QPointF(7, 20)},
                                    std::tuple{QPointF(29, 16), QPointF(25, 12), QPointF(25, 20)}})
      p.drawPolyline(QPolygonF({a, tip, b}));
  }
  p.end();
  return QIcon(pixmap);
}

}  // namespace la::gui
