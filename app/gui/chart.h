#pragma once
// What the two chart docks (curvature plot, LCG plot) share: the white page with the
// axis labels around the plotting area.

#include <QPainter>
#include <QString>
#include <QWidget>

namespace la::gui {

/// Clears the widget, writes the x label under `area` and the y label (turned) left of
/// it; leaves the pen black.
inline void drawChartPage(QPainter& p, const QWidget& w, const QRectF& area, const QString& x_label,
                          const QString& y_label) {
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(w.rect(), Qt::white);
  p.setPen(Qt::black);
  p.drawText(QRectF(0, w.height() - 18, w.width(), 16), Qt::AlignCenter, x_label);
  p.save();
  p.translate(12, area.center().y());
  p.rotate(-90);
  p.drawText(QRectF(-80, -10, 160, 16), Qt::AlignCenter, y_label);
  p.restore();
}

}  // namespace la::gui
