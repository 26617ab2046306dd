#include "app/gui/lcg_plot.h"

#include "app/gui/chart.h"

#include <QPainter>
#include <algorithm>
#include <cmath>

#include "core/lcg.h"
#include "fitting/paper_stages.h"

namespace la::gui {
namespace {

constexpr int kSamples = 80;

}  // namespace

LcgPlot::LcgPlot(QWidget* parent) : QWidget(parent) { setMinimumSize(240, 160); }

void LcgPlot::setSegment(const FitResult* fit, int piece) {
  m_data.clear();
  m_segment.clear();
  m_alpha = m_fit_alpha = m_fit_intercept = m_r2 = NAN;
  m_title.clear();
  if (fit && piece >= 0 && piece < static_cast<int>(fit->curve.pieces.size())) {
    const LaSegment& seg = fit->curve.pieces[piece].segment;
    m_alpha = seg.alpha();
    for (const LcgPoint& p : lcgOfSegment(seg, kSamples)) m_segment.emplace_back(p.log_rho, p.log_rho_ds_drho);
    const PieceReport& rep = fit->pieces[piece];
    if (rep.spline >= 0) {  // the smoothed stroke over the same piece, as the fit read it
      const std::vector<LcgPoint> pts = lcgPointsOfPiece(fit->splines[rep.spline], rep.t0, rep.t1);
      for (const LcgPoint& p : pts) m_data.emplace_back(p.log_rho, p.log_rho_ds_drho);
      const LcgFit lf = fitLcg(pts);
      if (lf.report.usable()) m_fit_alpha = lf.alpha, m_fit_intercept = lf.intercept, m_r2 = lf.r2;
    }
    m_title = QString("segment %1: alpha %2").arg(piece + 1).arg(m_alpha, 0, 'g', 3);
  }
  update();
}

void LcgPlot::paintEvent(QPaintEvent*) {
  QPainter p(this);
  const QRectF area(52, 22, width() - 64, height() - 58);
  drawChartPage(p, *this, area, "log ρ", "log(ρ |ds/dρ|)");
  p.drawRect(area);
  if (m_segment.empty()) {
    p.drawText(area, Qt::AlignCenter, "click a segment to see its LCG");
    return;
  }
  p.drawText(QRectF(0, 2, width(), 18), Qt::AlignCenter, m_title);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const auto* set : {&m_data, &m_segment})
    for (const QPointF& q : *set) x0 = std::min(x0, q.x()), x1 = std::max(x1, q.x()), y0 = std::min(y0, q.y()), y1 = std::max(y1, q.y());
  const double px = std::max(0.05 * (x1 - x0), 1e-3), py = std::max(0.05 * (y1 - y0), 1e-3);
  x0 -= px, x1 += px, y0 -= py, y1 += py;
  auto map = [&](double x, double y) {
    return QPointF(area.left() + area.width() * (x - x0) / (x1 - x0), area.bottom() - area.height() * (y - y0) / (y1 - y0));
  };
  QFont small = font();
  small.setPointSizeF(small.pointSizeF() * 0.8);
  p.setFont(small);
  // (ticks at round values: quarters of the range read 2.38, 2.6, 2.82)
  for (double x : roundTicks(x0, x1))
    p.drawText(QRectF(map(x, y0).x() - 30, area.bottom() + 2, 60, 14), Qt::AlignCenter, QString::number(x, 'g', 3));
  for (double y : roundTicks(y0, y1))
    p.drawText(QRectF(area.left() - 50, map(x0, y).y() - 7, 46, 14), Qt::AlignRight | Qt::AlignVCenter, QString::number(y, 'g', 3));
  p.setPen(Qt::NoPen);
  p.setBrush(QColor(150, 150, 150));
  for (const QPointF& q : m_data) p.drawEllipse(map(q.x(), q.y()), 2.2, 2.2);
  if (std::isfinite(m_fit_alpha)) {
    p.setPen(QPen(QColor(120, 120, 120), 1.0, Qt::DashLine));
    p.drawLine(map(x0, m_fit_intercept + m_fit_alpha * x0), map(x1, m_fit_intercept + m_fit_alpha * x1));
    p.drawText(QPointF(area.left() + 6, area.top() + 14),
               QString("stroke: slope %1, R² %2").arg(m_fit_alpha, 0, 'g', 3).arg(m_r2, 0, 'f', 3));
  }
  QPolygonF line;
  for (const QPointF& q : m_segment) line << map(q.x(), q.y());
  p.setPen(QPen(QColor(21, 101, 192), 2.0));
  p.drawPolyline(line);
  p.drawText(QPointF(area.left() + 6, area.top() + 28), QString("LA segment: alpha %1").arg(m_alpha, 0, 'g', 3));
}

}  // namespace la::gui
