#pragma once
// Curvature against arc length, drawn as a chart with axes, ticks and labels: the
// smoothed B-spline's curvature (before fairing, grey) and the LA curve's (after, blue)
// of one fitted stroke, overlaid. Joints are marked on the axis and the selected
// segment's arc-length range is shaded. The y axis reads curvature (signed), |curvature|
// on a log scale (extrema of tight and gentle bends side by side, as Rhino's curvature
// graph in log mode), or radius (what a tool or a bending radius is checked against).
// The legend sits above the plotting area, never on the data.
// Its scope: the selected stroke (before and after), or every stroke visible in the
// canvas on one axis (their LA curves, each from its own start, s = 0; the selected one
// in blue, the others in muted colours), to compare their curvature.

#include <QWidget>

#include "fitting/pipeline.h"

class QComboBox;

namespace la::gui {

class CurvaturePlot : public QWidget {
  Q_OBJECT
 public:
  enum class Mode { kCurvature, kLogAbsCurvature, kRadius };
  enum class Scope { kSelectedStroke, kAllVisible };

  explicit CurvaturePlot(QWidget* parent = nullptr);
  void setFit(const FitResult* fit);  // nullptr: empty plot
  /// All visible strokes on one axis: the LA curves of `fits`, `highlighted` (an index
  /// into them, or -1) drawn as the selected one (its joints, its shaded segment).
  void setCurves(const std::vector<const FitResult*>& fits, int highlighted);
  /// A curve with no "before" (a construction): curvature at arc lengths, joints marked.
  void setCurve(const std::vector<double>& s, const std::vector<double>& kappa, const std::vector<double>& joints);
  /// Shades segment `piece`'s arc-length range (-1: none).
  void setHighlight(int piece);
  void setMode(Mode mode);
  Mode mode() const { return m_mode; }
  void setScope(Scope scope);  // as its combo box; emits scopeChanged (the window refills the plot)
  Scope scope() const { return m_scope; }
  QSize sizeHint() const override { return {420, 220}; }

  /// What is drawn, for tests: the plotting area and the legend's box (widget pixels),
  /// the shaded range of arc length (empty: none), the LA curve's points (s, y) in the
  /// current mode (y NaN where the mode has no value: log 0, radius of a straight piece).
  QRectF plotArea() const;
  QRectF legendRect() const;
  std::pair<double, double> highlight() const { return m_highlight; }
  std::vector<std::pair<double, double>> afterPoints() const;
  double totalLength() const { return m_after.s.empty() ? 0.0 : m_after.s.back(); }
  /// The curves drawn on the one axis: the length of each (setCurves' order; one for a
  /// single stroke, none when empty).
  std::vector<double> curveLengths() const;

 signals:
  void scopeChanged(Scope scope);

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  struct Series {
    std::vector<double> s, kappa;
  };
  double value(double kappa) const;  // kappa in the current mode's units (NaN: none)
  // The LA curve's curvature against arc length; each segment's start into `joints`.
  static Series laCurvature(const FitResult& fit, std::vector<double>* joints);
  Series m_before, m_after;   // m_after: the stroke shown, or the selected one of several
  std::vector<Series> m_curves;  // all visible strokes (Scope::kAllVisible)
  int m_highlighted = -1;         // which of m_curves is m_after
  std::vector<double> m_joints;  // arc length of each segment's start
  std::pair<double, double> m_highlight{0.0, 0.0};
  Mode m_mode = Mode::kCurvature;
  Scope m_scope = Scope::kSelectedStroke;
  QComboBox* m_mode_box = nullptr;
  QComboBox* m_scope_box = nullptr;
};

}  // namespace la::gui
