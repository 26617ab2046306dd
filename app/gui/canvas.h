#pragma once
// The drawing canvas: records pen (QTabletEvent: position, pressure, time; tablet
// tracking on), mouse and touch input as strokes, and shows the document: raw points,
// fitted LA curves, curvature combs (comb.h), the marks of joints, inflections, extrema
// and corners (markers.h). What a plain left drag does is the tool's (tools.h): draw,
// select and move, or pan. Wheel zooms about the cursor; the middle button and Space held
// pan in every tool. The widget records and paints; fitting is the document's job, and
// every change of the document is the window's (it turns the signals into undo steps).

#include <QImage>
#include <QPainter>
#include <QPointF>
#include <QTransform>
#include <QWidget>
#include <cmath>
#include <optional>

#include "app/gui/comb.h"
#include "app/gui/document.h"
#include "app/gui/selection.h"
#include "app/gui/stroke_drawing.h"
#include "app/gui/tools.h"

namespace la::gui {

struct Layers {
  bool raw_points = true;
  bool pressure_ink = true;  // a pen stroke's width follows its pressure: ink while drawn, its samples' dots after
  bool spline = false;  // the smoothed B-spline (stage 2)
  bool curve = true;
  bool comb = true;
  bool markers = true;  // joints, inflections, extrema
  bool triangles = false;  // each segment's control triangle
  bool y_up = false;       // show the world's y axis pointing up (profiles, font outlines)
  double comb_scale = 0.08;  // longest tooth, relative to the view's shorter side
  int comb_teeth = 96;       // teeth along each curve, evenly spaced in arc length
  bool comb_shared = false;  // one gain for every curve (the largest curvature of all sets it), so they compare
};

/// What the empty canvas says: how to start, and the tools' keys.
QString emptyCanvasHint();
/// A control point (a segment's control-triangle apex) centred on `q`: a diamond.
void drawControlPoint(QPainter& p, const QPointF& q);

class Canvas : public QWidget {
  Q_OBJECT
 public:
  explicit Canvas(QWidget* parent = nullptr);
  void setDocument(const Document* document);
  Layers& layers() { return m_layers; }
  void fitView();  // zoom to show every stroke
  QPointF toWorld(const QPointF& widget_point) const;
  QPointF toWidget(const Vec2& world) const;
  /// The live fit of the stroke being drawn (shown until the pen lifts), or none.
  void setPreview(std::optional<FitResult> preview);
  bool hasPreview() const { return m_preview.has_value(); }
  const std::optional<FitResult>& preview() const { return m_preview; }
  const Stroke& currentStroke() const { return m_current; }
  void setSelection(int stroke, int piece);  // the selected segment (the LCG and alpha panels follow it)
  Tool tool() const { return m_tool; }
  void setTool(Tool tool);
  /// The selected strokes (the Select tool's): the window selects all or none through it,
  /// then calls update().
  Selection& selection() { return m_selection; }
  const Selection& selection() const { return m_selection; }
  /// The comb of stroke `stroke` as it is drawn (empty without a fit or without curvature).
  Comb combOf(int stroke) const;
  /// The comb's gain for a curve whose largest |curvature| is kmax, at the current view
  /// and comb settings (shared: the largest of every curve shown instead).
  double combGain(double kmax) const;
  const QTransform& view() const { return m_view; }
  /// The empty canvas says how to start (emptyCanvasHint) until something is drawn.
  bool showsHint() const;
  /// The construction whose parameters the panel shows (-1: none); drawn highlighted.
  void setSelectedConstruction(int index);
  /// A raster image under the drawing, to trace over; world units are its pixels.
  void setBackground(const QImage& image, double opacity);
  double backgroundOpacity() const { return m_background_opacity; }
  void setBackgroundOpacity(double opacity) {
    m_background_opacity = opacity;
    update();
  }
  bool hasBackground() const { return !m_background.isNull(); }

 signals:
  void strokeFinished(const la::Stroke& stroke);
  void strokeProgress();
  void cursorMoved(const QPointF& world);
  void viewChanged();  // zoom, pan, fit view (what is visible changed)
  void segmentClicked(int stroke, int piece);  // right click near a segment, or a Select-tool click (-1: none)
  void selectionChanged();
  /// A Select-tool drag moved the selected strokes by `d` (world) since the last signal;
  /// `drag` numbers the drag, so the window can merge one drag's steps into one undo step.
  void strokesMoved(const std::vector<std::size_t>& strokes, const QPointF& d, int drag);
  // ctrl+drag of joint `joint` (the start of that segment; n is an open curve's end), live
  void jointDragged(int stroke, int joint, const QPointF& world);
  void jointDropped(int stroke, int joint, const QPointF& world);
  // ctrl+drag of a shown control triangle's apex (Q1), live
  void apexDragged(int stroke, int piece, const QPointF& world);
  void apexDropped(int stroke, int piece, const QPointF& world);
  // drag of a construction's handle (a plain left drag near it), live and on release
  void handlePressed(int construction);
  void handleDragged(int construction, int handle, const QPointF& world);
  void handleDropped(int construction, int handle, const QPointF& world);

 protected:
  void paintEvent(QPaintEvent*) override;
  void tabletEvent(QTabletEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;    // Space held: pan
  void keyReleaseEvent(QKeyEvent* event) override;
  void focusOutEvent(QFocusEvent* event) override;  // (a Space released elsewhere)

 private:
  bool event(QEvent* event) override;  // touch drawing and pinch gestures
  void beginStroke(const QPointF& pos, double pressure, double time_ms);
  void extendStroke(const QPointF& pos, double pressure, double time_ms, double tilt_x = NAN, double tilt_y = NAN);
  void zoomAbout(const QPointF& center, double factor);
  void endStroke();
  // `stroke` is the document's index (selection, triangles), -1 for the preview;
  // `drawing` its cached drawing (none for the preview: computed here).
  void paintCurve(QPainter& p, const FitResult& fit, int stroke, const StrokeDrawing* drawing = nullptr) const;
  double viewScale() const { return std::sqrt(std::abs(m_view.determinant())); }  // pixels per world unit
  // The triangles layer, or the selected segment: its control triangle and apex handle.
  bool showsTriangle(int stroke, int piece) const;
  bool pickHandle(const QPointF& at);  // a construction handle within reach: sets m_drag_*
  // A joint or a shown apex within reach (of the selected strokes only, or of any): sets m_drag_*.
  bool pickEditHandle(const QPointF& at, bool selected_only);
  void selectPress(const QPointF& at, bool shift);  // the Select tool's left press
  void finishBand();
  void updateCursor();
  bool pansWithLeftButton(Qt::KeyboardModifiers modifiers) const;
  double sharedMaxCurvature() const;  // over every fitted stroke and construction
  void paintSelection(QPainter& p, const DocumentStroke& stroke) const;
  /// A stroke's raw samples: dots as wide as the pen's pressure makes its ink
  /// (Layers::pressure_ink, where they carry pressure), else dots of one size.
  void paintRaw(QPainter& p, const std::vector<StrokeSample>& samples, const QColor& color) const;
  void paintHint(QPainter& p) const;  // on the empty canvas: how to start
  void paintConstruction(QPainter& p, const Construction& c, bool selected) const;
  void paintComb(QPainter& p, const Comb& comb) const;

  const Document* m_document = nullptr;
  mutable StrokeDrawings m_drawings;  // what is drawn of each stroke, by revision (world coordinates)
  Layers m_layers;
  QTransform m_view;          // world -> widget
  bool m_drawing = false;
  bool m_panning = false;
  QPointF m_pan_anchor;
  Stroke m_current;           // the stroke being drawn, in world coordinates
  qint64 m_stroke_start_ms = 0;
  std::optional<FitResult> m_preview;
  int m_drag_stroke = -1, m_drag_piece = -1;  // the joint or apex being dragged
  bool m_drag_apex = false;
  int m_drag_construction = -1, m_drag_handle = -1;
  int m_selected_construction = -1;
  QImage m_background;
  double m_background_opacity = 0.5;
  int m_selected_stroke = -1, m_selected_piece = -1;
  Tool m_tool = Tool::kDraw;
  bool m_space_held = false;
  Selection m_selection;
  bool m_moving = false;       // a Select-tool drag of the selected strokes
  QPointF m_move_last;         // where it was at the last signal (world)
  int m_move_drag = 0;         // numbers the drags
  std::optional<QRectF> m_band;  // the rubber band being dragged (widget pixels)
  bool m_band_additive = false;  // shift held: adds to the selection
};

}  // namespace la::gui
