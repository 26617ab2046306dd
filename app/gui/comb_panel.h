#pragma once
// The comb and marker controls, live (a dock beside the curvature plot): the comb's scale
// and its number of teeth, each a slider with a field, whether each curve's comb has its
// own scale or all share one (to compare curves), and the legend of the marks on a curve.

#include <QWidget>

class QButtonGroup;
class QDoubleSpinBox;
class QRadioButton;
class QSlider;
class QSpinBox;

namespace la::gui {

/// The symbols drawn on the canvas, each with its name (markers.h draws both).
class MarkerLegend : public QWidget {
  Q_OBJECT
 public:
  explicit MarkerLegend(QWidget* parent = nullptr);
  QSize sizeHint() const override;
  /// The rows as drawn, top to bottom.
  QStringList entries() const;

 protected:
  void paintEvent(QPaintEvent*) override;
};

class CombPanel : public QWidget {
  Q_OBJECT
 public:
  explicit CombPanel(QWidget* parent = nullptr);
  /// Shows these settings without emitting.
  void setSettings(double scale, int teeth, bool shared);
  double scale() const;  // longest tooth, fraction of the view's shorter side
  int teeth() const;     // along each curve
  bool shared() const;   // one scale for all curves

 signals:
  void settingsChanged();

 private:
  void emitChanged();
  QSlider* m_scale_slider = nullptr;  // percent of the view, in tenths
  QDoubleSpinBox* m_scale = nullptr;  // percent of the view
  QSlider* m_teeth_slider = nullptr;
  QSpinBox* m_teeth = nullptr;
  QRadioButton* m_per_curve = nullptr;
  QRadioButton* m_shared = nullptr;
  bool m_updating = false;
};

}  // namespace la::gui
