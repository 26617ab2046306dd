#pragma once
// The fit parameters the user steers: tolerance, maximum number of curvature extrema,
// G2 method and threshold, corner detection. Emits optionsChanged on every edit.

#include <QWidget>

#include "fitting/pipeline.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QSlider;
class QSpinBox;

namespace la::gui {

class ParameterPanel : public QWidget {
  Q_OBJECT
 public:
  explicit ParameterPanel(QWidget* parent = nullptr);
  void setOptions(const FitOptions& options);  // without emitting
  FitOptions options() const;
  /// The selected segment's alpha; disabled (with the reason as tool tip) if none can be steered.
  void setSegmentAlpha(bool enabled, double alpha, const QString& reason = {});

 signals:
  void optionsChanged(const la::FitOptions& options);
  void segmentAlphaChanged(double alpha);    // an edit: typed, or the slider released
  void segmentAlphaPreviewed(double alpha);  // the slider is being dragged

 private:
  QDoubleSpinBox* m_tolerance = nullptr;  // percent of the stroke's diagonal
  QSpinBox* m_max_extrema = nullptr;      // -1: all significant
  QComboBox* m_g2 = nullptr;
  QDoubleSpinBox* m_threshold = nullptr;  // log10 of the relative G2 gap
  QCheckBox* m_corners = nullptr;
  QCheckBox* m_polish = nullptr;
  QDoubleSpinBox* m_alpha = nullptr;      // the selected segment's alpha
  QSlider* m_alpha_slider = nullptr;      // the same, in steps of kAlphaSliderStep
  FitOptions m_base;                      // the options not on the panel
  bool m_updating = false;
};

}  // namespace la::gui
