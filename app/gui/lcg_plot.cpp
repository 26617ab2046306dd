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
constexpr double kTitleHeight = 18;
constexpr double kLegendRowHeight = 15;
constexpr double kTopMargin = kTitleHeight + 2 * kLegendRowHeight + 6;  // title, two legend rows
const QColor kDataColor(150, 150, 150);
const QColor kSegmentColor(21, 101, 192);

}  // namespace

LcgPlot::LcgPlot(QWidget* parent) : QWidget(parent) { setMinimumSize(240, 180); }

QRectF LcgPlot::plotArea() const { return QRectF(52, kTopMargin, width() - 64, height() - kTopMargin - 36); }

// (from the left edge: the dock is narrow and the rows hold numbers)
QRectF LcgPlot::legendRect() const { return QRectF(6, kTitleHeight, width() - 12, 2 * kLegendRowHeight); }

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
  const QRectF area = plotArea();
  drawChartPage(p, *this, area, "log ρ", "log(ρ |ds/dρ|)");
  p.drawRect(area);
  if (m_segment.empty()) {
    p.drawText(area, Qt::AlignCenter, "click a segment to see its LCG");
    return;
  }
  p.drawText(QRectF(0, 1, width(), kTitleHeight), Qt::AlignCenter, m_title);
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
  p.save();
  p.setClipRect(area);
  p.setPen(Qt::NoPen);
  p.setBrush(kDataColor);
  for (const QPointF& q : m_data) p.drawEllipse(map(q.x(), q.y()), 2.2, 2.2);
  if (std::isfinite(m_fit_alpha)) {
    p.setPen(QPen(QColor(120, 120, 120), 1.0, Qt::DashLine));
    p.drawLine(map(x0, m_fit_intercept + m_fit_alpha * x0), map(x1, m_fit_intercept + m_fit_alpha * x1));
  }
  QPolygonF line;
  for (const QPointF& q : m_segment) line << map(q.x(), q.y());
  p.setPen(QPen(kSegmentColor, 2.0));
  p.drawPolyline(line);
  p.restore();
  // the legend, one row per series, in the margin above the data
  const QRectF legend = legendRect();
  const QRectF row1(legend.left(), legend.top(), legend.width(), kLegendRowHeight);
  const QRectF row2 = row1.translated(0, kLegendRowHeight);
  p.setPen(Qt::NoPen);
  p.setBrush(kDataColor);
  p.drawEllipse(QPointF(row1.left() + 7, row1.center().y()), 2.2, 2.2);
  p.setPen(QPen(QColor(120, 120, 120), 1.0, Qt::DashLine));
  p.drawLine(QPointF(row1.left() + 11, row1.center().y()), QPointF(row1.left() + 18, row1.center().y()));
  p.setPen(Qt::black);
  const QString stroke_text = std::isfinite(m_fit_alpha)
                                  ? QString("stroke: slope %1, R² %2 (dashed)").arg(m_fit_alpha, 0, 'g', 3).arg(m_r2, 0, 'f', 3)
                                  : QString("stroke (too few points for a line)");
  p.drawText(row1.adjusted(22, 0, 0, 0), Qt::AlignVCenter | Qt::AlignLeft, stroke_text);
  p.setPen(QPen(kSegmentColor, 2.0));
  p.drawLine(QPointF(row2.left() + 2, row2.center().y()), QPointF(row2.left() + 18, row2.center().y()));
  p.setPen(Qt::black);
  p.drawText(row2.adjusted(22, 0, 0, 0), Qt::AlignVCenter | Qt::AlignLeft, QString("LA segment: alpha %1").arg(m_alpha, 0, 'g', 3));
}

}  // namespace la::gui
