#include "app/gui/curvature_plot.h"

#include "app/gui/chart.h"

#include <QPainter>
#include <algorithm>
#include <cmath>

namespace la::gui {
namespace {

constexpr int kSamplesPerSegment = 64;
constexpr int kSplineSamples = 400;

}  // namespace

CurvaturePlot::CurvaturePlot(QWidget* parent) : QWidget(parent) { setMinimumSize(280, 160); }

void CurvaturePlot::setFit(const FitResult* fit) {
  m_before = {};
  m_after = {};
  m_joints.clear();
  if (fit) {
    double s0 = 0.0;
    for (const CurvePiece& piece : fit->curve.pieces) {
      const CurveSamples smp = piece.segment.sample(kSamplesPerSegment);
      for (std::size_t i = 0; i < smp.size(); ++i) {
        m_after.s.push_back(s0 + smp.s[i]);
        m_after.kappa.push_back(smp.kappa[i]);
      }
      m_joints.push_back(s0);
      s0 += piece.segment.length();
    }
    // the splines, sampled uniformly in parameter, with arc length accumulated
    double s = 0.0;
    for (const CubicBSpline& spline : fit->splines) {
      Vec2 prev = spline.point(spline.tMin());
      for (int k = 0; k <= kSplineSamples; ++k) {
        const double t = spline.tMin() + (spline.tMax() - spline.tMin()) * k / kSplineSamples;
        const Vec2 q = spline.point(t);
        s += (q - prev).norm();
        prev = q;
        m_before.s.push_back(s);
        m_before.kappa.push_back(spline.curvature(t));
      }
    }
  }
  update();
}

void CurvaturePlot::setCurve(const std::vector<double>& s, const std::vector<double>& kappa,
                             const std::vector<double>& joints) {
  m_before = {};
  m_after = {s, kappa};
  m_joints = joints;
  update();
}

void CurvaturePlot::paintEvent(QPaintEvent*) {
  QPainter p(this);
  const QRectF area(56, 14, width() - 70, height() - 48);
  drawChartPage(p, *this, area, "arc length s", "curvature κ");
  if (m_after.s.empty()) {
    p.drawText(area, Qt::AlignCenter, "draw a stroke to see its curvature");
    return;
  }
  double s_max = m_after.s.back(), k_lo = 0.0, k_hi = 0.0;
  for (const Series* ser : {&m_before, &m_after})
    for (double k : ser->kappa) k_lo = std::min(k_lo, k), k_hi = std::max(k_hi, k);
  if (!m_before.s.empty()) s_max = std::max(s_max, m_before.s.back());
  const double pad = 0.08 * std::max(k_hi - k_lo, 1e-12);
  k_lo -= pad;
  k_hi += pad;
  auto map = [&](double s, double k) {
    return QPointF(area.left() + area.width() * s / s_max, area.bottom() - area.height() * (k - k_lo) / (k_hi - k_lo));
  };
  // axes and ticks
  p.setPen(QPen(Qt::black, 1.0));
  p.drawRect(area);
  QFont small = font();
  small.setPointSizeF(small.pointSizeF() * 0.8);
  p.setFont(small);
  const double ks = tickStep(k_hi - k_lo);
  for (double k = std::ceil(k_lo / ks) * ks; k <= k_hi; k += ks) {
    const QPointF a = map(0, k);
    p.setPen(QPen(QColor(225, 225, 225), 1.0));
    p.drawLine(a, map(s_max, k));
    p.setPen(Qt::black);
    p.drawText(QRectF(a.x() - 54, a.y() - 8, 50, 16), Qt::AlignRight | Qt::AlignVCenter, QString::number(k, 'g', 3));
  }
  const double ss = tickStep(s_max);
  for (double s = 0; s <= s_max; s += ss) {
    const QPointF a = map(s, k_lo);
    p.drawLine(a, a + QPointF(0, 4));
    p.drawText(QRectF(a.x() - 30, a.y() + 4, 60, 14), Qt::AlignCenter, QString::number(s, 'g', 4));
  }
  p.setPen(QPen(QColor(120, 120, 120), 1.0, Qt::DashLine));
  p.drawLine(map(0, 0), map(s_max, 0));
  // joints
  p.setPen(QPen(QColor(0, 0, 0, 60), 1.0));
  for (double s : m_joints) p.drawLine(map(s, k_lo), map(s, k_hi));
  auto draw = [&](const Series& ser, const QPen& pen) {
    QPolygonF line;
    for (std::size_t i = 0; i < ser.s.size(); ++i) line << map(ser.s[i], ser.kappa[i]);
    p.setPen(pen);
    p.drawPolyline(line);
  };
  draw(m_before, QPen(QColor(150, 150, 150), 1.2));
  draw(m_after, QPen(QColor(21, 101, 192), 2.0));
  p.setPen(QColor(21, 101, 192));
  if (m_before.s.empty()) {
    p.drawText(QPointF(area.right() - 170, area.top() + 14), "constructed curve");
    return;
  }
  p.drawText(QPointF(area.right() - 170, area.top() + 28), "after (LA curve, G2)");
  p.setPen(QColor(150, 150, 150));
  p.drawText(QPointF(area.right() - 170, area.top() + 14), "before (smoothed stroke)");
}

}  // namespace la::gui
