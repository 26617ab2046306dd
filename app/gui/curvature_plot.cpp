#include "app/gui/curvature_plot.h"

#include "app/gui/chart.h"

#include <QComboBox>
#include <QPainter>
#include <algorithm>
#include <cmath>

namespace la::gui {
namespace {

constexpr int kSamplesPerSegment = 64;
constexpr int kSplineSamples = 400;
constexpr double kTopMargin = 32;  // the mode box and the legend, above the data
// The log scale shows this many decades below the largest |kappa|: a comb shows no finer
// difference, and the curvature's approach to 0 at an inflection would fill the axis.
constexpr double kLogDecades = 4.0;
const QColor kBeforeColor(150, 150, 150);
const QColor kAfterColor(21, 101, 192);
const QColor kHighlightColor(255, 143, 0, 45);  // the canvas' selected-segment orange, faint
// The other strokes of "all visible strokes": muted, distinct, none the selected blue.
const QColor kOtherColors[] = {{120, 144, 156}, {188, 170, 164}, {165, 214, 167}, {206, 147, 216}, {255, 204, 128},
                               {128, 203, 196}};

}  // namespace

CurvaturePlot::CurvaturePlot(QWidget* parent) : QWidget(parent) {
  setMinimumSize(300, 180);
  m_mode_box = new QComboBox(this);
  m_mode_box->setObjectName("curvature-plot-mode");
  m_mode_box->addItem("curvature κ", static_cast<int>(Mode::kCurvature));
  m_mode_box->addItem("|κ|, log scale", static_cast<int>(Mode::kLogAbsCurvature));
  m_mode_box->addItem("radius 1/|κ|", static_cast<int>(Mode::kRadius));
  m_mode_box->move(4, 3);
  m_mode_box->setFocusPolicy(Qt::ClickFocus);
  connect(m_mode_box, &QComboBox::currentIndexChanged, this,
          [this](int i) { setMode(static_cast<Mode>(m_mode_box->itemData(i).toInt())); });
  m_scope_box = new QComboBox(this);
  m_scope_box->setObjectName("curvature-plot-scope");
  m_scope_box->addItem("selected stroke", static_cast<int>(Scope::kSelectedStroke));
  m_scope_box->addItem("all visible strokes", static_cast<int>(Scope::kAllVisible));
  m_scope_box->adjustSize();
  m_mode_box->adjustSize();
  m_scope_box->move(m_mode_box->geometry().right() + 6, 3);
  m_scope_box->setFocusPolicy(Qt::ClickFocus);
  connect(m_scope_box, &QComboBox::currentIndexChanged, this,
          [this](int i) { setScope(static_cast<Scope>(m_scope_box->itemData(i).toInt())); });
}

void CurvaturePlot::setScope(Scope scope) {
  const int i = m_scope_box->findData(static_cast<int>(scope));
  if (m_scope_box->currentIndex() != i) m_scope_box->setCurrentIndex(i);  // (comes back here)
  if (scope == m_scope) return;
  m_scope = scope;
  emit scopeChanged(scope);
}

std::vector<double> CurvaturePlot::curveLengths() const {
  std::vector<double> out;
  if (m_scope == Scope::kAllVisible && !m_curves.empty()) {
    for (const Series& c : m_curves) out.push_back(c.s.empty() ? 0.0 : c.s.back());
  } else if (!m_after.s.empty()) {
    out.push_back(m_after.s.back());
  }
  return out;
}

void CurvaturePlot::setMode(Mode mode) {
  m_mode = mode;
  const int i = m_mode_box->findData(static_cast<int>(mode));
  if (m_mode_box->currentIndex() != i) m_mode_box->setCurrentIndex(i);
  update();
}

double CurvaturePlot::value(double kappa) const {
  switch (m_mode) {
    case Mode::kCurvature: return kappa;
    case Mode::kLogAbsCurvature: return kappa != 0.0 ? std::log10(std::abs(kappa)) : NAN;
    case Mode::kRadius: return kappa != 0.0 ? 1.0 / std::abs(kappa) : NAN;
  }
  return NAN;
}

std::vector<std::pair<double, double>> CurvaturePlot::afterPoints() const {
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 0; i < m_after.s.size(); ++i) out.emplace_back(m_after.s[i], value(m_after.kappa[i]));
  return out;
}

void CurvaturePlot::setCurves(const std::vector<const FitResult*>& fits, int highlighted) {
  m_before = {};
  m_after = {};
  m_curves.clear();
  m_joints.clear();
  m_highlight = {0.0, 0.0};
  m_highlighted = highlighted >= 0 && highlighted < static_cast<int>(fits.size()) ? highlighted : -1;
  for (std::size_t k = 0; k < fits.size(); ++k)
    m_curves.push_back(laCurvature(*fits[k], static_cast<int>(k) == m_highlighted ? &m_joints : nullptr));
  if (m_highlighted >= 0) m_after = m_curves[static_cast<std::size_t>(m_highlighted)];
  update();
}

CurvaturePlot::Series CurvaturePlot::laCurvature(const FitResult& fit, std::vector<double>* joints) {
  Series out;
  double s0 = 0.0;
  for (const CurvePiece& piece : fit.curve.pieces) {
    const CurveSamples smp = piece.segment.sample(kSamplesPerSegment);
    for (std::size_t i = 0; i < smp.size(); ++i) {
      out.s.push_back(s0 + smp.s[i]);
      out.kappa.push_back(smp.kappa[i]);
    }
    if (joints) joints->push_back(s0);
    s0 += piece.segment.length();
  }
  return out;
}

void CurvaturePlot::setFit(const FitResult* fit) {
  m_before = {};
  m_after = {};
  m_curves.clear();
  m_highlighted = -1;
  m_joints.clear();
  m_highlight = {0.0, 0.0};
  if (fit) {
    m_after = laCurvature(*fit, &m_joints);
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
  m_curves.clear();
  m_highlighted = -1;
  m_after = {s, kappa};
  m_joints = joints;
  m_highlight = {0.0, 0.0};
  update();
}

void CurvaturePlot::setHighlight(int piece) {
  m_highlight = {0.0, 0.0};
  if (piece >= 0 && piece < static_cast<int>(m_joints.size())) {
    const std::size_t p = static_cast<std::size_t>(piece);
    m_highlight = {m_joints[p], p + 1 < m_joints.size() ? m_joints[p + 1] : totalLength()};
  }
  update();
}

QRectF CurvaturePlot::plotArea() const { return QRectF(62, kTopMargin, width() - 76, height() - kTopMargin - 34); }

QRectF CurvaturePlot::legendRect() const {
  // right of the mode box, in the top margin
  const double left = m_scope_box->geometry().right() + 12;
  return QRectF(left, 2, std::max(0.0, width() - left - 8), kTopMargin - 6);
}

void CurvaturePlot::paintEvent(QPaintEvent*) {
  QPainter p(this);
  const QRectF area = plotArea();
  const char* y_label = m_mode == Mode::kCurvature ? "curvature κ" : (m_mode == Mode::kRadius ? "radius" : "|κ| (log)");
  drawChartPage(p, *this, area, "arc length s", y_label);
  if (m_after.s.empty() && m_curves.empty()) {
    p.drawText(area, Qt::AlignCenter,
               m_scope == Scope::kAllVisible ? "no fitted stroke in view" : "draw a stroke to see its curvature");
    return;
  }
  std::vector<const Series*> all{&m_before, &m_after};
  for (const Series& c : m_curves) all.push_back(&c);
  double s_max = 0.0;  // the longest curve's length: every curve starts at s = 0
  for (const Series* ser : all)
    if (!ser->s.empty()) s_max = std::max(s_max, ser->s.back());
  s_max = std::max(s_max, 1e-300);
  double lo = INFINITY, hi = -INFINITY, smallest_radius = INFINITY;
  for (const Series* ser : all)
    for (double k : ser->kappa)
      if (const double v = value(k); std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;
  if (m_mode == Mode::kCurvature) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);  // the zero line shows
  if (m_mode == Mode::kLogAbsCurvature)  // near an inflection |kappa| falls through every decade
    lo = std::max(lo, hi - kLogDecades);
  if (m_mode == Mode::kRadius) {
    // a radius longer than the whole curve reads as straight: the axis stops there
    // (near an inflection the radius grows without bound)
    smallest_radius = lo;
    lo = 0.0;
    hi = std::min(hi, std::max(s_max, 2.0 * smallest_radius));
  }
  const double pad = 0.08 * std::max(hi - lo, 1e-12 * std::max(1.0, std::abs(hi)));
  if (m_mode != Mode::kRadius) lo -= pad;
  hi += pad;
  auto map = [&](double s, double v) {
    return QPointF(area.left() + area.width() * s / s_max, area.bottom() - area.height() * (v - lo) / (hi - lo));
  };
  // the selected segment's range, under everything
  if (m_highlight.second > m_highlight.first)
    p.fillRect(QRectF(map(m_highlight.first, hi), map(m_highlight.second, lo)).normalized(), kHighlightColor);
  p.setPen(QPen(Qt::black, 1.0));
  p.drawRect(area);
  QFont small = font();
  small.setPointSizeF(small.pointSizeF() * 0.8);
  p.setFont(small);
  for (double v : roundTicks(lo, hi)) {
    const QPointF a = map(0, v);
    p.setPen(QPen(QColor(225, 225, 225), 1.0));
    p.drawLine(a, map(s_max, v));
    p.setPen(Qt::black);
    const QString label = m_mode == Mode::kLogAbsCurvature ? QString::number(std::pow(10.0, v), 'g', 2)
                                                           : QString::number(std::abs(v) < 1e-12 * (hi - lo) ? 0.0 : v, 'g', 3);
    p.drawText(QRectF(a.x() - 60, a.y() - 8, 56, 16), Qt::AlignRight | Qt::AlignVCenter, label);
  }
  for (double s : roundTicks(0.0, s_max)) {
    const QPointF a = map(s, lo);
    p.drawLine(a, a + QPointF(0, 4));
    p.drawText(QRectF(a.x() - 30, a.y() + 4, 60, 14), Qt::AlignCenter, QString::number(s, 'g', 4));
  }
  p.save();
  p.setClipRect(area);
  if (m_mode == Mode::kCurvature) {
    p.setPen(QPen(QColor(120, 120, 120), 1.0, Qt::DashLine));
    p.drawLine(map(0, 0), map(s_max, 0));
  }
  p.setPen(QPen(QColor(0, 0, 0, 60), 1.0));
  for (double s : m_joints) p.drawLine(map(s, lo), map(s, hi));
  auto draw = [&](const Series& ser, const QPen& pen) {
    p.setPen(pen);
    QPolygonF line;  // broken where the mode has no value (log of 0, radius of a line)
    for (std::size_t i = 0; i <= ser.s.size(); ++i) {
      const double v = i < ser.s.size() ? value(ser.kappa[i]) : NAN;
      if (std::isfinite(v)) {
        line << map(ser.s[i], v);
        continue;
      }
      if (line.size() > 1) p.drawPolyline(line);
      line.clear();
    }
  };
  draw(m_before, QPen(kBeforeColor, 1.2));
  for (std::size_t k = 0; k < m_curves.size(); ++k)  // (the selected one is drawn last, on top)
    if (static_cast<int>(k) != m_highlighted) draw(m_curves[k], QPen(kOtherColors[k % std::size(kOtherColors)], 1.4));
  draw(m_after, QPen(kAfterColor, 2.0));
  p.restore();
  // the legend, in the margin above the data
  p.setFont(small);
  const QRectF legend = legendRect();
  auto entry = [&](double x, const QColor& color, const QString& text) {
    p.setPen(QPen(color, 2.0));
    p.drawLine(QPointF(x, legend.center().y()), QPointF(x + 14, legend.center().y()));
    p.drawText(QRectF(x + 18, legend.top(), legend.right() - x - 18, legend.height()), Qt::AlignVCenter | Qt::AlignLeft, text);
    return x + 24 + p.fontMetrics().horizontalAdvance(text);
  };
  if (!m_curves.empty()) {
    const double x = entry(legend.left(), kOtherColors[0], m_curves.size() == 1 ? QString("the visible stroke")
                                                                      : QString("%1 visible strokes, each from its start").arg(m_curves.size()));
    if (m_highlighted >= 0) entry(x, kAfterColor, "selected");
    return;
  }
  if (m_before.s.empty()) {
    entry(legend.left(), kAfterColor, "constructed curve");
    return;
  }
  const double x = entry(legend.left(), kBeforeColor, "before (smoothed stroke)");
  entry(x, kAfterColor, "after (LA curve, G2)");
}

}  // namespace la::gui
