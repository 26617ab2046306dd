#include "app/gui/canvas.h"

#include <QDateTime>
#include <QGestureEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QTabletEvent>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <optional>

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
    return;
  }
  const double w = std::max(x1 - x0, 1e-9), h = std::max(y1 - y0, 1e-9);
  const double scale = 0.85 * std::min(width() / w, height() / h);
  m_view = QTransform();
  m_view.translate(width() / 2.0, height() / 2.0);
  m_view.scale(scale, m_layers.y_up ? -scale : scale);
  m_view.translate(-(x0 + x1) / 2.0, -(y0 + y1) / 2.0);
  update();
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

void Canvas::mousePressEvent(QMouseEvent* e) {
  if (e->button() == Qt::MiddleButton || (e->button() == Qt::LeftButton && (e->modifiers() & Qt::ShiftModifier))) {
    m_panning = true;
    m_pan_anchor = e->position();
  } else if (e->button() == Qt::LeftButton && (e->modifiers() & Qt::ControlModifier) && m_document) {
    // ctrl+drag moves the joint (the open curve's end too) or the shown control-triangle
    // apex under the cursor, within 8 pixels
    double best = 8.0;
    auto consider = [&](const Vec2& q, std::size_t stroke, std::size_t index, bool apex) {
      const QPointF w = toWidget(q);
      const double d = std::hypot(w.x() - e->position().x(), w.y() - e->position().y());
      if (d < best) best = d, m_drag_stroke = static_cast<int>(stroke), m_drag_piece = static_cast<int>(index), m_drag_apex = apex;
    };
    for (std::size_t k = 0; k < m_document->strokes().size(); ++k) {
      const auto& fit = m_document->strokes()[k].fit;
      if (!fit) continue;
      const auto& pieces = fit->curve.pieces;
      for (std::size_t i = 0; i < pieces.size(); ++i) {
        consider(pieces[i].segment.start(), k, i, false);
        if (!showsTriangle(static_cast<int>(k), static_cast<int>(i))) continue;
        if (const std::optional<Vec2> apex = controlApex(pieces[i].segment)) consider(*apex, k, i, true);
      }
      if (!fit->curve.closed && !pieces.empty()) consider(pieces.back().segment.end(), k, pieces.size(), false);
    }
  } else if (e->button() == Qt::LeftButton && pickHandle(e->position())) {
    emit handlePressed(m_drag_construction);
  } else if (e->button() == Qt::LeftButton) {
    beginStroke(e->position(), NAN, static_cast<double>(e->timestamp()));
  } else if (e->button() == Qt::RightButton && m_document) {
    // select the segment nearest the click (within 12 pixels)
    double best = 12.0;
    int best_stroke = -1, best_piece = -1;
    for (std::size_t k = 0; k < m_document->strokes().size(); ++k) {
      const auto& fit = m_document->strokes()[k].fit;
      if (!fit) continue;
      for (std::size_t i = 0; i < fit->curve.pieces.size(); ++i) {
        const CurveSamples smp = fit->curve.pieces[i].segment.sample(48);
        for (const Vec2& q : smp.point) {
          const double d = std::hypot(toWidget(q).x() - e->position().x(), toWidget(q).y() - e->position().y());
          if (d < best) best = d, best_stroke = static_cast<int>(k), best_piece = static_cast<int>(i);
        }
      }
    }
    setSelection(best_stroke, best_piece);
    emit segmentClicked(best_stroke, best_piece);
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
  } else if (m_drag_handle >= 0) {
    emit handleDragged(m_drag_construction, m_drag_handle, toWorld(e->position()));
  } else if (m_drag_piece >= 0) {
    if (m_drag_apex) emit apexDragged(m_drag_stroke, m_drag_piece, toWorld(e->position()));
    else emit jointDragged(m_drag_stroke, m_drag_piece, toWorld(e->position()));
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
  if (m_panning) m_panning = false;
  else if (m_drawing) endStroke();
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

void Canvas::paintComb(QPainter& p, const std::vector<Vec2>& points, const std::vector<Vec2>& normals,
                       const std::vector<double>& kappa, double scale) const {
  p.setPen(QPen(kCombColor, 1.0));
  QPolygonF envelope;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2 tip = points[i] - scale * kappa[i] * normals[i];
    p.drawLine(toWidget(points[i]), toWidget(tip));
    envelope << toWidget(tip);
  }
  p.drawPolyline(envelope);
}

void Canvas::paintConstruction(QPainter& p, const Construction& c, bool selected) const {
  const ConstructionResult& r = c.result;
  if (m_layers.comb && !r.kappa.empty()) {
    double kmax = 0.0;
    for (double k : r.kappa) kmax = std::max(kmax, std::abs(k));
    if (kmax > 0) {
      // about comb_density teeth per segment's worth of samples, like the fitted curves
      const std::size_t every = std::max<std::size_t>(1, r.points.size() / std::max(2, 3 * m_layers.comb_density));
      std::vector<Vec2> points, normals;
      std::vector<double> kappa;
      for (std::size_t i = 0; i < r.points.size(); i += every) {
        points.push_back(r.points[i]);
        normals.push_back(r.normals[i]);
        kappa.push_back(r.kappa[i]);
      }
      paintComb(p, points, normals, kappa, m_layers.comb_scale * std::min(width(), height()) / m_view.m11() / kmax);
    }
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

void Canvas::paintCurve(QPainter& p, const FitResult& fit, int stroke) const {
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
  double kmax = 0.0;
  for (const CurvePiece& piece : curve.pieces)
    kmax = std::max({kmax, std::abs(piece.segment.kappaStart()), std::abs(piece.segment.kappaEnd())});
  const double comb_world = kmax > 0 ? m_layers.comb_scale * std::min(width(), height()) / m_view.m11() / kmax : 0.0;
  for (std::size_t index = 0; index < curve.pieces.size(); ++index) {
    const CurvePiece& piece = curve.pieces[index];
    const LaSegment& seg = piece.segment;
    const std::optional<Vec2> apex = stroke >= 0 && showsTriangle(stroke, static_cast<int>(index)) ? controlApex(seg) : std::nullopt;
    if (apex) {
      p.setPen(QPen(kTriangleColor, 1.0, Qt::DotLine));
      p.setBrush(Qt::NoBrush);
      p.drawPolyline(QPolygonF({toWidget(seg.start()), toWidget(*apex), toWidget(seg.end())}));
      p.setPen(QPen(kTriangleColor, 1.2));
      const QPointF q = toWidget(*apex);  // a diamond: ctrl+drag it
      p.drawPolygon(QPolygonF({q + QPointF(0, -5), q + QPointF(5, 0), q + QPointF(0, 5), q + QPointF(-5, 0)}));
    }
    if (m_layers.comb && comb_world > 0) {
      const CurveSamples teeth = seg.sample(std::max(2, m_layers.comb_density));
      std::vector<Vec2> normals;
      for (const Vec2& t : teeth.tangent) normals.push_back(Vec2(-t.y(), t.x()));
      paintComb(p, teeth.point, normals, teeth.kappa, comb_world);
    }
    if (m_layers.curve) {
      const int n = std::clamp(static_cast<int>(seg.length() * m_view.m11() / 3.0), 8, 2000);
      const CurveSamples smp = seg.sample(n);
      QPolygonF line;
      for (const Vec2& q : smp.point) line << toWidget(q);
      p.setPen(QPen(static_cast<int>(index) == selected_piece ? QColor(255, 143, 0) : kCurveColor,
                    static_cast<int>(index) == selected_piece ? 3.5 : 2.2));
      p.drawPolyline(line);
    }
    if (m_layers.markers) {
      const QPointF joint = toWidget(seg.start());
      p.setPen(QPen(Qt::black, 1.0));
      p.setBrush(Qt::NoBrush);
      if (seg.kappaStart() == 0.0) {
        p.drawEllipse(joint, 5, 5);  // inflection
      } else if (piece.corner) {
        p.drawLine(joint + QPointF(-5, -5), joint + QPointF(5, 5));  // corner
        p.drawLine(joint + QPointF(-5, 5), joint + QPointF(5, -5));
      } else {
        p.drawRect(QRectF(joint - QPointF(4, 4), QSizeF(8, 8)));  // curvature extremum / joint
      }
    }
  }
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
    for (std::size_t k = 0; k < m_document->strokes().size(); ++k) {
      const DocumentStroke& s = m_document->strokes()[k];
      if (m_layers.raw_points || !s.fit) {
        p.setPen(Qt::NoPen);
        p.setBrush(kRawColor);
        for (const StrokeSample& q : s.raw.samples) p.drawEllipse(toWidget(q.p), 1.8, 1.8);
      }
      if (s.fit) paintCurve(p, *s.fit, static_cast<int>(k));
    }
  }
  if (m_document)
    for (std::size_t k = 0; k < m_document->constructions().size(); ++k)
      paintConstruction(p, m_document->constructions()[k], static_cast<int>(k) == m_selected_construction);
  if (m_preview) paintCurve(p, *m_preview, -1);
  if (!m_current.samples.empty()) {  // the stroke in progress, as ink
    QPolygonF ink;
    for (const StrokeSample& q : m_current.samples) ink << toWidget(q.p);
    p.setPen(QPen(kStrokeInkColor, 1.5));
    p.drawPolyline(ink);
  }
}

}  // namespace la::gui
