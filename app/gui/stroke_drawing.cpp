#include "app/gui/stroke_drawing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_set>

#include <QPainter>
#include <QPixmap>

namespace la::gui {
namespace {

// Curve samples every this many pixels along a segment, as the canvas drew them before
// the cache: smooth at 2.2 px line width.
constexpr double kCurveStepPixels = 3.0;
constexpr int kMinSamplesPerSegment = 8, kMaxSamplesPerSegment = 2000;
constexpr double kResampleZoomIn = 2.0, kResampleZoomOut = 8.0;

QPointF widgetPoint(const QTransform& view, const StrokeSample& sample) {
  return view.map(QPointF(sample.p.x(), sample.p.y()));
}

// An ink width in whole kInkWidthStep, at least one.
int inkWidthSteps(double width) { return std::max(1, static_cast<int>(std::lround(width / kInkWidthStep))); }

}  // namespace

std::vector<std::size_t> decimatedIndices(const std::vector<StrokeSample>& points, const QTransform& view,
                                          double step) {
  // One point per cell of a `step` grid: a stroke of length l pixels keeps at most about
  // 2 l / step of them however densely or noisily it was sampled (a distance to the last
  // kept point alone lets noise through: 0.3 px jitter at 0.005 px spacing kept half).
  std::vector<std::size_t> kept;
  std::unordered_set<std::uint64_t> cells;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const QPointF q = widgetPoint(view, points[i]);
    if (!std::isfinite(q.x()) || !std::isfinite(q.y())) continue;
    const auto cx = static_cast<std::int64_t>(std::floor(q.x() / step)), cy = static_cast<std::int64_t>(std::floor(q.y() / step));
    const std::uint64_t cell = (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint32_t>(cy);
    if (cells.insert(cell).second || i + 1 == points.size()) kept.push_back(i);
  }
  return kept;
}

QPolygonF decimatedPoints(const std::vector<StrokeSample>& points, const QTransform& view, double step) {
  QPolygonF out;
  for (std::size_t i : decimatedIndices(points, view, step)) out << widgetPoint(view, points[i]);
  return out;
}

bool hasPressure(const std::vector<StrokeSample>& points) {
  return std::any_of(points.begin(), points.end(),
                     [](const StrokeSample& s) { return std::isfinite(s.pressure) && s.pressure > 0.0; });
}

std::vector<double> inkWidths(const std::vector<StrokeSample>& points, double width) {
  double largest = 1.0;
  for (const StrokeSample& s : points)
    if (std::isfinite(s.pressure)) largest = std::max(largest, s.pressure);
  std::vector<double> share(points.size(), NAN);
  for (std::size_t i = 0; i < points.size(); ++i)
    if (std::isfinite(points[i].pressure)) share[i] = std::max(kInkLeastShare, std::min(1.0, points[i].pressure / largest));
  // a sample without pressure (a dropped report) takes the mean of the share before it
  // (already settled) and of the next sample that has one
  for (std::size_t i = 0; i < share.size(); ++i) {
    if (std::isfinite(share[i])) continue;
    double sum = 0.0;
    int n = 0;
    if (i > 0) sum += share[i - 1], ++n;
    for (std::size_t j = i + 1; j < share.size(); ++j)
      if (std::isfinite(share[j])) {
        sum += share[j], ++n;
        break;
      }
    share[i] = n ? sum / n : 1.0;
  }
  for (double& s : share) s *= width;
  return share;
}

void drawPressureInk(QPainter& p, const std::vector<StrokeSample>& points, const QTransform& view, const QColor& color,
                     double width) {
  const std::vector<double> widths = inkWidths(points, width);
  const std::vector<std::size_t> kept = decimatedIndices(points, view, kInkStepPixels);
  if (kept.empty()) return;
  auto at = [&](std::size_t i) { return widgetPoint(view, points[i]); };
  auto stepOf = [&](std::size_t k) {  // the width from kept[k] to the next, in kInkWidthStep
    const std::size_t i = kept[k], j = kept[std::min(k + 1, kept.size() - 1)];
    return inkWidthSteps(0.5 * (widths[i] + widths[j]));
  };
  // (runs of one width as one polyline: pressure changes slowly, and a polyline with round
  // joins strokes far faster than its steps as lines with round caps)
  p.save();
  QPolygonF run{at(kept.front())};
  int step = stepOf(0);
  for (std::size_t k = 1; k <= kept.size(); ++k) {
    const bool last = k == kept.size();
    if (!last) run << at(kept[k]);
    if (last || (k + 1 < kept.size() && stepOf(k) != step)) {
      p.setPen(QPen(color, step * kInkWidthStep, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
      if (run.size() == 1) p.drawPoint(run.front());
      else p.drawPolyline(run);
      if (last) break;
      run = QPolygonF{run.back()};
      step = stepOf(k);
    }
  }
  p.restore();
}

void drawDots(QPainter& p, const QPolygonF& at, const QColor& color, double diameter) {
  // one antialiased dot, blitted at every point in one call (a round-capped point or an
  // ellipse per point is flattened from Beziers each time: 200,000 of them took 250 ms),
  // made once per color and diameter (pressure dots come in up to 16 diameters a stroke)
  static std::map<std::pair<QRgb, double>, QPixmap> sprites;
  const int size = static_cast<int>(std::ceil(diameter)) + 2;
  QPixmap& dot = sprites[{color.rgba(), diameter}];
  if (dot.isNull()) {
    dot = QPixmap(size, size);
    dot.fill(Qt::transparent);
    QPainter d(&dot);
    d.setRenderHint(QPainter::Antialiasing);
    d.setPen(Qt::NoPen);
    d.setBrush(color);
    d.drawEllipse(QPointF(size / 2.0, size / 2.0), diameter / 2.0, diameter / 2.0);
  }
  std::vector<QPainter::PixmapFragment> fragments;
  fragments.reserve(static_cast<std::size_t>(at.size()));
  for (const QPointF& q : at) fragments.push_back(QPainter::PixmapFragment::create(q, QRectF(0, 0, size, size)));
  p.drawPixmapFragments(fragments.data(), static_cast<int>(fragments.size()), dot);
}

void drawPressureDots(QPainter& p, const std::vector<StrokeSample>& points, const QTransform& view, const QColor& color,
                      double width) {
  const std::vector<double> widths = inkWidths(points, width);
  std::map<int, QPolygonF> by_width;  // in kInkWidthStep
  for (std::size_t i : decimatedIndices(points, view))
    by_width[inkWidthSteps(widths[i])] << widgetPoint(view, points[i]);
  for (const auto& [step, at] : by_width) drawDots(p, at, color, step * kInkWidthStep);
}

Comb StrokeDrawing::comb(double gain) const {
  Comb c = unit_comb;
  c.gain = gain;
  for (std::size_t i = 0; i < c.tip.size(); ++i) c.tip[i] = c.base[i] + gain * (unit_comb.tip[i] - c.base[i]);
  for (std::size_t i = 0; i < c.envelope.size() && i < envelope_base.size(); ++i)
    c.envelope[i] = envelope_base[i] + gain * (unit_comb.envelope[i] - envelope_base[i]);
  return c;
}

const StrokeDrawing& StrokeDrawings::of(const DocumentStroke& stroke, double scale, int teeth) {
  StrokeDrawing& d = m_drawings[stroke.revision];
  if (!stroke.fit) return d;
  const Curve& curve = stroke.fit->curve;
  if (d.revision != stroke.revision) {
    d.revision = stroke.revision;
    d.max_abs_kappa = maxAbsCurvature(curve);
    d.markers = curveMarkers(curve, stroke.fit->quality.diagonal > 0 ? stroke.fit->quality.diagonal : 1.0);
  }
  if (d.sampled_scale <= 0 || scale > kResampleZoomIn * d.sampled_scale || scale * kResampleZoomOut < d.sampled_scale) {
    d.sampled_scale = scale;
    d.segments.clear();
    for (const CurvePiece& piece : curve.pieces) {
      const int n = std::clamp(static_cast<int>(piece.segment.length() * scale / kCurveStepPixels), kMinSamplesPerSegment,
                               kMaxSamplesPerSegment);
      QPolygonF line;
      for (const Vec2& q : piece.segment.sample(n).point) line << QPointF(q.x(), q.y());
      d.segments.push_back(std::move(line));
    }
  }
  if (d.comb_teeth != teeth) {
    d.comb_teeth = teeth;
    d.unit_comb = curvatureComb(curve, 1.0, teeth);
    d.envelope_base = curvatureComb(curve, 0.0, teeth).envelope;
  }
  return d;
}

void StrokeDrawings::prune(const Document& document) {
  std::unordered_set<std::uint64_t> live;
  for (const DocumentStroke& s : document.strokes()) live.insert(s.revision);
  for (auto it = m_drawings.begin(); it != m_drawings.end();) it = live.count(it->first) ? std::next(it) : m_drawings.erase(it);
}

}  // namespace la::gui
