#pragma once
// What the two chart docks (curvature plot, LCG plot) share: the white page with the
// axis labels around the plotting area.

#include <QPainter>
#include <QString>
#include <QWidget>
#include <cmath>
#include <vector>

namespace la::gui {

/// A round tick step for a range: 1, 2 or 5 times a power of ten, about 5 ticks.
inline double tickStep(double range) {
  const double raw = range / 5.0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (raw <= m * p) return m * p;
  return 10.0 * p;
}

/// The round values in [lo, hi] a tick step apart (multiples of tickStep(hi - lo)).
inline std::vector<double> roundTicks(double lo, double hi) {
  std::vector<double> out;
  if (!(hi > lo)) return out;
  const double step = tickStep(hi - lo);
  for (double k = std::ceil(lo / step); k * step <= hi + 1e-9 * step; ++k) out.push_back(k * step);
  return out;
}

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
