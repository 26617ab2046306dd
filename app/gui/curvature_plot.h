#pragma once
// Curvature against arc length, drawn as a chart with axes, ticks and labels: the
// smoothed B-spline's curvature (before fairing, grey) and the LA curve's (after,
// blue) of one fitted stroke, overlaid. Joints are marked on the axis.

#include <QWidget>

#include "fitting/pipeline.h"

namespace la::gui {

class CurvaturePlot : public QWidget {
  Q_OBJECT
 public:
  explicit CurvaturePlot(QWidget* parent = nullptr);
  void setFit(const FitResult* fit);  // nullptr: empty plot
  /// A curve with no "before" (a construction): curvature at arc lengths, joints marked.
  void setCurve(const std::vector<double>& s, const std::vector<double>& kappa, const std::vector<double>& joints);
  QSize sizeHint() const override { return {420, 220}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  struct Series {
    std::vector<double> s, kappa;
  };
  Series m_before, m_after;
  std::vector<double> m_joints;
};

}  // namespace la::gui
