#pragma once
// The logarithmic curvature graph (LCG) of one segment of a fitted stroke, as a chart:
// the smoothed stroke's LCG points over that piece (x = log rho, y = log(rho |ds/drho|)),
// their least-squares line (seed 003 section 3.1), and the LA segment's own LCG, a
// straight line of slope alpha. The title and the legend sit above the plotting area,
// never on the data.

#include <QWidget>

#include "fitting/pipeline.h"

namespace la::gui {

class LcgPlot : public QWidget {
  Q_OBJECT
 public:
  explicit LcgPlot(QWidget* parent = nullptr);
  /// fit == nullptr or a piece out of range: empty plot.
  void setSegment(const FitResult* fit, int piece);
  QSize sizeHint() const override { return {300, 240}; }
  /// What is drawn, for tests (widget pixels): the plotting area and the legend's box.
  QRectF plotArea() const;
  QRectF legendRect() const;
  bool hasSegment() const { return !m_segment.empty(); }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  std::vector<QPointF> m_data;     // LCG of the smoothed piece
  std::vector<QPointF> m_segment;  // LCG of the LA segment
  double m_alpha = NAN, m_fit_alpha = NAN, m_fit_intercept = NAN, m_r2 = NAN;
  QString m_title;
};

}  // namespace la::gui
