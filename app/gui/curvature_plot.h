#pragma once
// Curvature against arc length, drawn as a chart with axes, ticks and labels: the
// smoothed B-spline's curvature (before fairing, grey) and the LA curve's (after, blue)
// of one fitted stroke, overlaid. Joints are marked on the axis and the selected
// segment's arc-length range is shaded. The y axis reads curvature (signed), |curvature|
// on a log scale (extrema of tight and gentle bends side by side, as Rhino's curvature
// graph in log mode), or radius (what a tool or a bending radius is checked against).
// The legend sits above the plotting area, never on the data.

#include <QWidget>

#include "fitting/pipeline.h"

class QComboBox;

namespace la::gui {

class CurvaturePlot : public QWidget {
  Q_OBJECT
 public:
  enum class Mode { kCurvature, kLogAbsCurvature, kRadius };

  explicit CurvaturePlot(QWidget* parent = nullptr);
  void setFit(const FitResult* fit);  // nullptr: empty plot
  /// A curve with no "before" (a construction): curvature at arc lengths, joints marked.
  void setCurve(const std::vector<double>& s, const std::vector<double>& kappa, const std::vector<double>& joints);
  /// Shades segment `piece`'s arc-length range (-1: none).
  void setHighlight(int piece);
  void setMode(Mode mode);
  Mode mode() const { return m_mode; }
  QSize sizeHint() const override { return {420, 220}; }

  /// What is drawn, for tests: the plotting area and the legend's box (widget pixels),
  /// the shaded range of arc length (empty: none), the LA curve's points (s, y) in the
  /// current mode (y NaN where the mode has no value: log 0, radius of a straight piece).
  QRectF plotArea() const;
  QRectF legendRect() const;
  std::pair<double, double> highlight() const { return m_highlight; }
  std::vector<std::pair<double, double>> afterPoints() const;
  double totalLength() const { return m_after.s.empty() ? 0.0 : m_after.s.back(); }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  struct Series {
    std::vector<double> s, kappa;
  };
  double value(double kappa) const;  // kappa in the current mode's units (NaN: none)
  Series m_before, m_after;
  std::vector<double> m_joints;  // arc length of each segment's start
  std::pair<double, double> m_highlight{0.0, 0.0};
  Mode m_mode = Mode::kCurvature;
  QComboBox* m_mode_box = nullptr;
};

}  // namespace la::gui
