#include "app/gui/canvas.h"

#include <QDateTime>
#include <QGestureEvent>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QTabletEvent>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <optional>

#include "app/gui/markers.h"
#include "fitting/user_edits.h"

namespace la::gui {
namespace {

constexpr double kZoomStep = 1.15;  // per wheel notch
const QColor kRawColor(150, 150, 150);
const QColor kCurveColor(21, 101, 192);
const QColor kCombColor(211, 47, 47, 160);
const QColor kStrokeInkColor(60, 60, 60);
const QColor kTriangleColor(120, 60, 170);
const QColor kConstructionColor(27, 94, 32);
const QColor kSelectionColor(33, 150, 243, 70);

}  // namespace

QString emptyCanvasHint() {
  return "Draw with the pen or the mouse\n\n"
         "B draw · V select and edit · H pan (or hold Space) · wheel zooms · F fits the view\n"
         "File > Import points… for a scanned profile or a point file";
}

void drawControlPoint(QPainter& p, const QPointF& q) {  // a diamond
  p.drawPolygon(QPolygonF({q + QPointF(0, -5), q + QPointF(5, 0), q + QPointF(0, 5), q + QPointF(-5, 0)}));
}

namespace {

}  // namespace

Canvas::Canvas(QWidget* parent) : QWidget(parent) {
  setAttribute(Qt::WA_TabletTracking);
  setAttribute(Qt::WA_AcceptTouchEvents);
  grabGesture(Qt::PinchGesture);
  setMouseTracking(true);
  setMinimumSize(400, 300);
  setAutoFillBackground(true);
  QPalette pal = palette();
  pal.setColor(QPalette::Window, Qt::white);
  setPalette(pal);
}

void Canvas::setDocument(const Document* document) {
  m_document = document;
  update();
}

QPointF Canvas::toWorld(const QPointF& w) const { return m_view.inverted().map(w); }
QPointF Canvas::toWidget(const Vec2& p) const { return m_view.map(QPointF(p.x(), p.y())); }

void Canvas::fitView() {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  auto include = [&](const Vec2& q) {
    x0 = std::min(x0, q.x()), x1 = std::max(x1, q.x());
    y0 = std::min(y0, q.y()), y1 = std::max(y1, q.y());
  };
  if (m_document) {
    for (const DocumentStroke& s : m_document->strokes())
      for (const StrokeSample& p : s.raw.samples) include(p.p);
    for (const Construction& c : m_document->constructions()) {
      for (const Vec2& q : c.handles) include(q);
      for (const Vec2& q : c.result.points) include(q);
    }
  }
  if (!std::isfinite(x0)) {
    m_view = QTransform();
    update();
    emit viewChanged();
    return;
  }
  const double w = std::max(x1 - x0, 1e-9), h = std::max(y1 - y0, 1e-9);
  const double scale = 0.85 * std::min(width() / w, height() / h);
  m_view = QTransform();
  m_view.translate(width() / 2.0, height() / 2.0);
  m_view.scale(scale, m_layers.y_up ? -scale : scale);
  m_view.translate(-(x0 + x1) / 2.0, -(y0 + y1) / 2.0);
  update();
  emit viewChanged();
}

void Canvas::setPreview(std::optional<FitResult> preview) {
  m_preview = std::move(preview);
  update();
}

void Canvas::setBackground(const QImage& image, double opacity) {
  m_background = image;
  m_background_opacity = opacity;
  update();
}

bool Canvas::event(QEvent* e) {
  switch (e->type()) {
    case QEvent::TouchBegin:
    case QEvent::TouchUpdate:
    case QEvent::TouchEnd:
    case QEvent::TouchCancel: {
      // One finger draws (with its pressure where the screen reports one); a second
      // finger turns the touch into a pinch, so the stroke begun by the first is dropped.
      auto* t = static_cast<QTouchEvent*>(e);
      if (!m_drawing && (m_tool != Tool::kDraw || m_space_held)) {
        e->ignore();  // a finger selects and pans as the mouse does (Qt makes mouse events of it)
        return false;
      }
      const double now = static_cast<double>(t->timestamp());
      if (t->points().size() != 1 || e->type() == QEvent::TouchCancel) {
        if (m_drawing) {
          m_drawing = false;
          m_current = Stroke();
          m_preview.reset();
          update();
        }
        return QWidget::event(e);
      }
      const QEventPoint& point = t->points().front();
      const double pressure = point.pressure() > 0.0 && point.pressure() < 1.0 ? point.pressure() : NAN;
      if (e->type() == QEvent::TouchBegin) beginStroke(point.position(), pressure, now);
      else if (m_drawing) extendStroke(point.position(), pressure, now);
      if (e->type() == QEvent::TouchEnd && m_drawing) endStroke();
      e->accept();
      return true;
    }
    default: break;
  }
  if (e->type() == QEvent::Gesture) {
    auto* g = static_cast<QGestureEvent*>(e);
    if (auto* pinch = static_cast<QPinchGesture*>(g->gesture(Qt::PinchGesture))) {
      zoomAbout(mapFromGlobal(pinch->centerPoint().toPoint()), pinch->scaleFactor());
      g->accept(pinch);
      return true;
    }
  }
  return QWidget::event(e);
}

void Canvas::zoomAbout(const QPointF& c, double factor) {
  QTransform zoom;
  zoom.translate(c.x(), c.y());
  zoom.scale(factor, factor);
  zoom.translate(-c.x(), -c.y());
  m_view = m_view * zoom;
  update();
  emit viewChanged();
}

void Canvas::setSelection(int stroke, int piece) {
  m_selected_stroke = stroke;
  m_selected_piece = piece;
  update();
}

void Canvas::beginStroke(const QPointF& pos, double pressure, double time_ms) {
  m_drawing = true;
  m_current = Stroke();
  m_stroke_start_ms = static_cast<qint64>(time_ms);
  extendStroke(pos, pressure, time_ms);
}

void Canvas::extendStroke(const QPointF& pos, double pressure, double time_ms, double tilt_x, double tilt_y) {
  const QPointF w = toWorld(pos);
  StrokeSample s;
  s.p = Vec2(w.x(), w.y());
  s.t = time_ms - static_cast<double>(m_stroke_start_ms);
  s.pressure = pressure;
  s.tilt_x = tilt_x;
  s.tilt_y = tilt_y;
  m_current.samples.push_back(s);
  update();  // painting happens in paintEvent, never here
  emit strokeProgress();
}

void Canvas::endStroke() {
  m_drawing = false;
  const Stroke finished = m_current;
  m_current = Stroke();
  m_preview.reset();
  if (finished.samples.size() >= 2) emit strokeFinished(finished);
  update();
}

void Canvas::tabletEvent(QTabletEvent* e) {
  if (!m_drawing && (m_tool != Tool::kDraw || m_space_held)) {
    e->ignore();  // Qt makes mouse events of it: the pen selects and pans as the mouse does
    return;
  }
  const double now = static_cast<double>(e->timestamp());
  switch (e->type()) {
    case QEvent::TabletPress: beginStroke(e->position(), e->pressure(), now); break;
    case QEvent::TabletMove:
      if (m_drawing) extendStroke(e->position(), e->pressure(), now, e->xTilt(), e->yTilt());
      emit cursorMoved(toWorld(e->position()));
      break;
    case QEvent::TabletRelease:
      if (m_drawing) endStroke();
      break;
    default: break;
  }
  e->accept();  // no synthesized mouse events for pen input
}

bool Canvas::pansWithLeftButton(Qt::KeyboardModifiers modifiers) const {
  return m_space_held || m_tool == Tool::kPan || (m_tool == Tool::kDraw && (modifiers & Qt::ShiftModifier));
}

void Canvas::setTool(Tool tool) {
  m_tool = tool;
  m_band.reset();
  updateCursor();
  update();
}

void Canvas::updateCursor() {
  if (m_panning) setCursor(Qt::ClosedHandCursor);
  else if (m_space_held || m_tool == Tool::kPan) setCursor(Qt::OpenHandCursor);
  else if (m_tool == Tool::kDraw) setCursor(Qt::CrossCursor);
  else setCursor(Qt::ArrowCursor);
}

void Canvas::keyPressEvent(QKeyEvent* e) {
  if (e->key() == Qt::Key_Space && !e->isAutoRepeat()) {
    m_space_held = true;
    updateCursor();
    e->accept();
    return;
  }
  QWidget::keyPressEvent(e);
}

void Canvas::keyReleaseEvent(QKeyEvent* e) {
  if (e->key() == Qt::Key_Space && !e->isAutoRepeat()) {
    m_space_held = false;
    updateCursor();
    e->accept();
    return;
  }
  QWidget::keyReleaseEvent(e);
}

void Canvas::focusOutEvent(QFocusEvent* e) {
  m_space_held = false;
  updateCursor();
  QWidget::focusOutEvent(e);
}

bool Canvas::pickEditHandle(const QPointF& at, bool selected_only) {
  if (!m_document) return false;
  double best = 8.0;  // pixels
  auto consider = [&](const Vec2& q, std::size_t stroke, std::size_t index, bool apex) {
    const QPointF w = toWidget(q);
    const double d = std::hypot(w.x() - at.x(), w.y() - at.y());
    if (d < best) best = d, m_drag_stroke = static_cast<int>(stroke), m_drag_piece = static_cast<int>(index), m_drag_apex = apex;
  };
  for (std::size_t k = 0; k < m_document->strokes().size(); ++k) {
    const DocumentStroke& s = m_document->strokes()[k];
    if (!s.fit || (selected_only && !m_selection.contains(s))) continue;
    const auto& pieces = s.fit->curve.pieces;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      consider(pieces[i].segment.start(), k, i, false);
      if (!showsTriangle(static_cast<int>(k), static_cast<int>(i))) continue;
      if (const std::optional<Vec2> apex = controlApex(pieces[i].segment)) consider(*apex, k, i, true);
    }
    if (!s.fit->curve.closed && !pieces.empty()) consider(pieces.back().segment.end(), k, pieces.size(), false);
  }
  return m_drag_piece >= 0;
}

void Canvas::selectPress(const QPointF& at, bool shift) {
  if (!m_document) return;
  // the selected strokes' joints and the selected segment's apex are handles here, as
  // under ctrl in the Draw tool
  if (!shift && pickEditHandle(at, /*selected_only=*/true)) return;
  const StrokeHit hit = strokeAt(*m_document, m_view, at);
  if (hit.stroke < 0) {  // empty canvas: a rubber band
    m_band = QRectF(at, at);
    m_band_additive = shift;
    return;
  }
  const DocumentStroke& stroke = m_document->strokes()[static_cast<std::size_t>(hit.stroke)];
  if (shift) {
    m_selection.toggle(stroke);
    emit selectionChanged();
    update();
    return;
  }
  if (!m_selection.contains(stroke)) {
    m_selection.clear();
    m_selection.add(stroke);
    emit selectionChanged();
  }
  setSelection(hit.stroke, hit.piece);
  emit segmentClicked(hit.stroke, hit.piece);
  m_moving = true;
  m_move_last = toWorld(at);
  ++m_move_drag;
  update();
}

void Canvas::finishBand() {
  const QRectF band = m_band->normalized();
  m_band.reset();
  constexpr double kClickPixels = 3.0;  // a band this small was a click on empty canvas
  if (band.width() < kClickPixels && band.height() < kClickPixels) {
    if (!m_band_additive && !m_selection.empty()) {
      m_selection.clear();
      emit selectionChanged();
      emit segmentClicked(-1, -1);
    }
    update();
    return;
  }
  const std::vector<std::size_t> inside = strokesInside(*m_document, m_view, band);
  if (!m_band_additive) m_selection.clear();
  for (std::size_t i : inside) m_selection.add(m_document->strokes()[i]);
  emit selectionChanged();
  update();
}

void Canvas::mousePressEvent(QMouseEvent* e) {
  const QPointF at = e->position();
  const bool left = e->button() == Qt::LeftButton;
  if (e->button() == Qt::MiddleButton || (left && pansWithLeftButton(e->modifiers()))) {
    m_panning = true;
    m_pan_anchor = at;
    updateCursor();
  } else if (left && (e->modifiers() & Qt::ControlModifier) && m_document) {
    // ctrl+drag moves the joint (the open curve's end too) or the shown control-triangle
    // apex under the cursor, within 8 pixels, in any tool
    pickEditHandle(at, /*selected_only=*/false);
  } else if (left && pickHandle(at)) {
    emit handlePressed(m_drag_construction);
  } else if (left && m_tool == Tool::kSelect) {
    selectPress(at, e->modifiers() & Qt::ShiftModifier);
  } else if (left) {
    beginStroke(at, NAN, static_cast<double>(e->timestamp()));
  } else if (e->button() == Qt::RightButton && m_document) {
    // selects the segment nearest the click (within 12 pixels), and its stroke
    const StrokeHit hit = strokeAt(*m_document, m_view, at, 12.0);
    m_selection.clear();
    if (hit.stroke >= 0) m_selection.add(m_document->strokes()[static_cast<std::size_t>(hit.stroke)]);
    emit selectionChanged();
    setSelection(hit.stroke, hit.piece);
    emit segmentClicked(hit.stroke, hit.piece);
  }
}

void Canvas::mouseMoveEvent(QMouseEvent* e) {
  if (m_panning) {
    const QPointF d = e->position() - m_pan_anchor;
    m_pan_anchor = e->position();
    QTransform shift;
    shift.translate(d.x(), d.y());
    m_view = m_view * shift;
    update();
    emit viewChanged();
  } else if (m_drag_handle >= 0) {
    emit handleDragged(m_drag_construction, m_drag_handle, toWorld(e->position()));
  } else if (m_drag_piece >= 0) {
    if (m_drag_apex) emit apexDragged(m_drag_stroke, m_drag_piece, toWorld(e->position()));
    else emit jointDragged(m_drag_stroke, m_drag_piece, toWorld(e->position()));
  } else if (m_moving) {
    const QPointF now = toWorld(e->position()), d = now - m_move_last;
    m_move_last = now;
    if (d != QPointF() && m_document) emit strokesMoved(m_selection.indices(*m_document), d, m_move_drag);
  } else if (m_band) {
    m_band->setBottomRight(e->position());
    update();
  } else if (m_drawing) {
    extendStroke(e->position(), NAN, static_cast<double>(e->timestamp()));
  }
  emit cursorMoved(toWorld(e->position()));
}

void Canvas::mouseReleaseEvent(QMouseEvent* e) {
  if (m_drag_handle >= 0) {
    const int construction = m_drag_construction, handle = m_drag_handle;
    m_drag_construction = m_drag_handle = -1;
    emit handleDropped(construction, handle, toWorld(e->position()));
    return;
  }
  if (m_drag_piece >= 0) {
    const int stroke = m_drag_stroke, piece = m_drag_piece;
    m_drag_stroke = m_drag_piece = -1;
    m_preview.reset();
    if (m_drag_apex) emit apexDropped(stroke, piece, toWorld(e->position()));
    else emit jointDropped(stroke, piece, toWorld(e->position()));
    return;
  }
  if (m_panning) {
    m_panning = false;
    updateCursor();
  } else if (m_moving) {
    m_moving = false;
  } else if (m_band) {
    m_band->setBottomRight(e->position());
    finishBand();
  } else if (m_drawing) {
    endStroke();
  }
}

void Canvas::wheelEvent(QWheelEvent* e) { zoomAbout(e->position(), std::pow(kZoomStep, e->angleDelta().y() / 120.0)); }

bool Canvas::pickHandle(const QPointF& at) {
  if (!m_document) return false;
  double best = 8.0;  // pixels
  for (std::size_t k = 0; k < m_document->constructions().size(); ++k) {
    const auto& handles = m_document->constructions()[k].handles;
    for (std::size_t i = 0; i < handles.size(); ++i) {
      const QPointF w = toWidget(handles[i]);
      const double d = std::hypot(w.x() - at.x(), w.y() - at.y());
      if (d < best) best = d, m_drag_construction = static_cast<int>(k), m_drag_handle = static_cast<int>(i);
    }
  }
  return m_drag_handle >= 0;
}

void Canvas::setSelectedConstruction(int index) {
  m_selected_construction = index;
  update();
}

void Canvas::paintComb(QPainter& p, const Comb& comb) const {
  QPen pen(kCombColor, 1.0);
  pen.setCosmetic(true);  // (one pixel wide: Qt's fast path for thin lines)
  p.setPen(pen);
  std::vector<QLineF> teeth;
  teeth.reserve(comb.base.size());
  for (std::size_t i = 0; i < comb.base.size(); ++i) teeth.emplace_back(toWidget(comb.base[i]), toWidget(comb.tip[i]));
  // The teeth without antialiasing, as CAD combs are drawn: antialiased translucent 1-px
  // lines cost Qt's raster engine ~0.4 ms per 100 (50 combs: 23 ms of a 39 ms repaint;
  // aliased, 4 ms in all). The envelope stays smooth.
  p.save();
  p.setRenderHint(QPainter::Antialiasing, false);
  p.drawLines(teeth.data(), static_cast<int>(teeth.size()));
  p.restore();
  QPolygonF envelope;
  for (const Vec2& q : comb.envelope) envelope << toWidget(q);
  p.drawPolyline(envelope);
}

double Canvas::sharedMaxCurvature() const {
  double kmax = 0.0;
  if (!m_document) return kmax;
  for (const DocumentStroke& s : m_document->strokes())
    if (s.fit) kmax = std::max(kmax, m_drawings.of(s, viewScale(), m_layers.comb_teeth).max_abs_kappa);
  for (const Construction& c : m_document->constructions())
    for (double k : c.result.kappa) kmax = std::max(kmax, std::abs(k));
  return kmax;
}

double Canvas::combGain(double kmax) const {
  if (m_layers.comb_shared) kmax = std::max(kmax, sharedMaxCurvature());
  return kmax > 0 ? m_layers.comb_scale * std::min(width(), height()) / m_view.m11() / kmax : 0.0;
}

Comb Canvas::combOf(int stroke) const {
  if (!m_document || stroke < 0 || stroke >= static_cast<int>(m_document->strokes().size())) return {};
  const auto& fit = m_document->strokes()[static_cast<std::size_t>(stroke)].fit;
  if (!fit) return {};
  const double gain = combGain(maxAbsCurvature(fit->curve));
  return gain > 0 ? curvatureComb(fit->curve, gain, m_layers.comb_teeth) : Comb{};
}

void Canvas::paintConstruction(QPainter& p, const Construction& c, bool selected) const {
  const ConstructionResult& r = c.result;
  if (m_layers.comb && !r.kappa.empty()) {
    double kmax = 0.0;
    for (double k : r.kappa) kmax = std::max(kmax, std::abs(k));
    if (const double gain = combGain(kmax); gain > 0)
      paintComb(p, curvatureComb(r.s, r.points, r.normals, r.kappa, gain, m_layers.comb_teeth));
  }
  QPolygonF polygon;
  for (const Vec2& q : c.handles) polygon << toWidget(q);
  p.setPen(QPen(kTriangleColor, 1.0, Qt::DotLine));
  p.setBrush(Qt::NoBrush);
  p.drawPolyline(polygon);
  if (!r.points.empty()) {
    QPolygonF line;
    for (const Vec2& q : r.points) line << toWidget(q);
    p.setPen(QPen(selected ? QColor(255, 143, 0) : kConstructionColor, selected ? 3.0 : 2.2));
    p.drawPolyline(line);
  } else {
    p.setPen(QPen(kCombColor));
    p.drawText(polygon.boundingRect().bottomLeft() + QPointF(0, 14), QString::fromStdString(r.message));
  }
  p.setPen(QPen(kTriangleColor, 1.2));
  p.setBrush(Qt::white);
  for (const QPointF& q : polygon) p.drawEllipse(q, 4.5, 4.5);
}

bool Canvas::showsTriangle(int stroke, int piece) const {
  return m_layers.triangles || (stroke == m_selected_stroke && piece == m_selected_piece);
}

void Canvas::paintCurve(QPainter& p, const FitResult& fit, int stroke, const StrokeDrawing* drawing) const {
  const int selected_piece = stroke >= 0 && stroke == m_selected_stroke ? m_selected_piece : -1;
  const Curve& curve = fit.curve;
  if (m_layers.spline) {
    p.setPen(QPen(QColor(46, 160, 67), 1.2, Qt::DashLine));
    for (const CubicBSpline& s : fit.splines) {
      QPolygonF line;
      for (int k = 0; k <= 400; ++k) {
        const Vec2 q = s.point(s.tMin() + (s.tMax() - s.tMin()) * k / 400.0);
        line << toWidget(q);
      }
      p.drawPolyline(line);
    }
  }
  if (m_layers.comb) {
    if (const double gain = combGain(drawing ? drawing->max_abs_kappa : maxAbsCurvature(curve)); gain > 0)
      paintComb(p, drawing ? drawing->comb(gain) : curvatureComb(curve, gain, m_layers.comb_teeth));
  }
  for (std::size_t index = 0; index < curve.pieces.size(); ++index) {
    const LaSegment& seg = curve.pieces[index].segment;
    const std::optional<Vec2> apex = stroke >= 0 && showsTriangle(stroke, static_cast<int>(index)) ? controlApex(seg) : std::nullopt;
    if (apex) {
      p.setPen(QPen(kTriangleColor, 1.0, Qt::DotLine));
      p.setBrush(Qt::NoBrush);
      p.drawPolyline(QPolygonF({toWidget(seg.start()), toWidget(*apex), toWidget(seg.end())}));
      p.setPen(QPen(kTriangleColor, 1.2));
      drawControlPoint(p, toWidget(*apex));  // drag it (Select tool, or ctrl+drag)
    }
    if (m_layers.curve) {
      QPolygonF line;
      if (drawing && index < drawing->segments.size()) {
        line = m_view.map(drawing->segments[index]);
      } else {
        const int n = std::clamp(static_cast<int>(seg.length() * viewScale() / 3.0), 8, 2000);
        for (const Vec2& q : seg.sample(n).point) line << toWidget(q);
      }
      p.setPen(QPen(static_cast<int>(index) == selected_piece ? QColor(255, 143, 0) : kCurveColor,
                    static_cast<int>(index) == selected_piece ? 3.5 : 2.2));
      p.drawPolyline(line);
    }
  }
  if (m_layers.markers) {
    p.setPen(QPen(Qt::black, 1.0));
    const std::vector<CurveMarker> computed =
        drawing ? std::vector<CurveMarker>{} : curveMarkers(curve, fit.quality.diagonal > 0 ? fit.quality.diagonal : 1.0);
    for (const CurveMarker& m : drawing ? drawing->markers : computed) drawMarker(p, m.kind, toWidget(m.at));
  }
}

void Canvas::paintSelection(QPainter& p, const DocumentStroke& stroke) const {
  // a halo under the curve and a dashed box around it, as Inkscape marks a selection
  QPolygonF line;
  for (const Vec2& q : strokeOutline(stroke)) line << toWidget(q);
  QRectF box = line.boundingRect();
  for (const StrokeSample& q : stroke.raw.samples) box |= QRectF(toWidget(q.p), QSizeF(0, 0));
  p.setPen(QPen(kSelectionColor, 8.0, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
  p.setBrush(Qt::NoBrush);
  p.drawPolyline(line);
  p.setPen(QPen(QColor(60, 60, 60), 1.0, Qt::DashLine));
  p.drawRect(box.adjusted(-6, -6, 6, 6));
}

void Canvas::paintHint(QPainter& p) const {
  p.setPen(QColor(140, 140, 140));
  QFont f = font();
  f.setPointSizeF(f.pointSizeF() * 1.2);
  p.setFont(f);
  p.drawText(rect().adjusted(20, 20, -20, -20), Qt::AlignCenter | Qt::TextWordWrap, emptyCanvasHint());
}

void Canvas::paintRaw(QPainter& p, const std::vector<StrokeSample>& samples, const QColor& color) const {
  if (m_layers.pressure_ink && hasPressure(samples)) drawPressureDots(p, samples, m_view, color);
  else drawDots(p, decimatedPoints(samples, m_view), color, 3.6);  // 3.6 px wide, ~2 per pixel
}

void Canvas::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  if (!m_background.isNull()) {
    p.save();
    p.setTransform(m_view);
    p.setOpacity(m_background_opacity);
    p.drawImage(QPointF(0, 0), m_background);
    p.restore();
  }
  if (m_document) {
    m_drawings.prune(*m_document);
    for (const DocumentStroke& s : m_document->strokes())
      if (m_selection.contains(s)) paintSelection(p, s);
    const double scale = viewScale();
    for (std::size_t k = 0; k < m_document->strokes().size(); ++k) {
      const DocumentStroke& s = m_document->strokes()[k];
      if (m_layers.raw_points || !s.fit) paintRaw(p, s.raw.samples, kRawColor);
      if (s.fit) paintCurve(p, *s.fit, static_cast<int>(k), &m_drawings.of(s, scale, m_layers.comb_teeth));
    }
  }
  if (m_document)
    for (std::size_t k = 0; k < m_document->constructions().size(); ++k)
      paintConstruction(p, m_document->constructions()[k], static_cast<int>(k) == m_selected_construction);
  if (m_preview) paintCurve(p, *m_preview, -1);
  if (!m_current.samples.empty()) {  // the stroke in progress, as ink
    if (m_layers.pressure_ink && hasPressure(m_current.samples)) {
      drawPressureInk(p, m_current.samples, m_view, kStrokeInkColor);
    } else {
      QPolygonF ink;
      for (const StrokeSample& q : m_current.samples) ink << toWidget(q.p);
      p.setPen(QPen(kStrokeInkColor, 1.5));
      p.drawPolyline(ink);
    }
  }
  if (m_band) {
    p.setPen(QPen(QColor(60, 60, 60), 1.0, Qt::DashLine));
    p.setBrush(QColor(33, 150, 243, 30));
    p.drawRect(m_band->normalized());
  }
  if (showsHint()) paintHint(p);
}

bool Canvas::showsHint() const {
  const bool empty = !m_document || (m_document->strokes().empty() && m_document->constructions().empty());
  return empty && m_current.samples.empty() && m_background.isNull();
}

}  // namespace la::gui
