#include "app/gui/parameter_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QSlider>
#include <QSpinBox>
#include <cmath>

namespace la::gui {
namespace {
constexpr double kAlphaRange = 3.0;        // the pipeline's alpha range (FitOptions::min_alpha, max_alpha)
constexpr double kAlphaSliderStep = 0.01;  // one slider tick
int sliderTicks(double alpha) { return static_cast<int>(std::lround(alpha / kAlphaSliderStep)); }
}  // namespace

ParameterPanel::ParameterPanel(QWidget* parent) : QWidget(parent) {
  auto* form = new QFormLayout(this);
  m_tolerance = new QDoubleSpinBox;
  m_tolerance->setRange(0.01, 10.0);
  m_tolerance->setDecimals(2);
  m_tolerance->setSingleStep(0.05);
  m_tolerance->setSuffix(" % of size");
  // (typed values apply on Enter or leaving the field, not at every keystroke: "1.25"
  // passed through 1 and refitted, one undo step a key; the arrows still apply at once)
  m_tolerance->setKeyboardTracking(false);
  m_tolerance->setToolTip("Largest distance of the curve from the points, relative to the stroke's bounding-box diagonal");
  form->addRow("Tolerance", m_tolerance);
  m_max_extrema = new QSpinBox;
  m_max_extrema->setRange(-1, 50);
  m_max_extrema->setSpecialValueText("all significant");
  m_max_extrema->setKeyboardTracking(false);
  m_max_extrema->setToolTip("Simplify: keep at most this many curvature extrema");
  form->addRow("Max extrema", m_max_extrema);
  m_g2 = new QComboBox;
  m_g2->addItem("Newton (all joints)", static_cast<int>(G2Method::kNewton));
  m_g2->addItem("Bisection (joint by joint)", static_cast<int>(G2Method::kBisection));
  m_g2->addItem("Off (G1 only)", static_cast<int>(G2Method::kOff));
  form->addRow("G2 method", m_g2);
  m_threshold = new QDoubleSpinBox;
  m_threshold->setRange(-12, -2);
  m_threshold->setDecimals(1);
  m_threshold->setPrefix("1e");
  m_threshold->setKeyboardTracking(false);
  m_threshold->setToolTip("Relative curvature gap allowed at a joint");
  form->addRow("G2 threshold", m_threshold);
  m_corners = new QCheckBox("keep sharp corners");
  form->addRow("", m_corners);
  m_polish = new QCheckBox("fit the chain to the points");
  m_polish->setToolTip("After pen-up, fit the whole G2 chain to the points by least squares and choose the "
                       "segments they need (stage 7): closer to them, truer alphas. Off: the paper's "
                       "construction alone (stages 1-6)");
  form->addRow("", m_polish);
  m_alpha = new QDoubleSpinBox;
  m_alpha->setRange(-kAlphaRange, kAlphaRange);
  m_alpha->setSingleStep(0.1);
  m_alpha->setDecimals(2);
  m_alpha->setKeyboardTracking(false);
  m_alpha->setToolTip("Right-click a segment to steer its LCG slope alpha; the curve stays G2");
  form->addRow("Segment alpha", m_alpha);
  // The slider previews while it is dragged and edits once, on release (one undo step).
  m_alpha_slider = new QSlider(Qt::Horizontal);
  m_alpha_slider->setRange(sliderTicks(-kAlphaRange), sliderTicks(kAlphaRange));
  m_alpha_slider->setTracking(false);
  form->addRow("", m_alpha_slider);
  setSegmentAlpha(false, 0.0, "select a segment first (click it with V, or right-click it)");
  connect(m_alpha, &QDoubleSpinBox::valueChanged, this, [this](double a) {
    if (m_updating) return;
    m_updating = true;
    m_alpha_slider->setValue(sliderTicks(a));
    m_updating = false;
    emit segmentAlphaChanged(a);
  });
  connect(m_alpha_slider, &QSlider::sliderMoved, this, [this](int ticks) {
    m_updating = true;
    m_alpha->setValue(ticks * kAlphaSliderStep);
    m_updating = false;
    emit segmentAlphaPreviewed(ticks * kAlphaSliderStep);
  });
  connect(m_alpha_slider, &QSlider::valueChanged, this, [this](int ticks) {
    if (m_updating) return;
    m_updating = true;
    m_alpha->setValue(ticks * kAlphaSliderStep);
    m_updating = false;
    emit segmentAlphaChanged(ticks * kAlphaSliderStep);
  });
  setOptions(FitOptions{});
  auto changed = [this] {
    if (!m_updating) emit optionsChanged(options());
  };
  connect(m_tolerance, &QDoubleSpinBox::valueChanged, this, changed);
  connect(m_max_extrema, &QSpinBox::valueChanged, this, changed);
  connect(m_g2, &QComboBox::currentIndexChanged, this, changed);
  connect(m_threshold, &QDoubleSpinBox::valueChanged, this, changed);
  connect(m_corners, &QCheckBox::toggled, this, changed);
  connect(m_polish, &QCheckBox::toggled, this, changed);
}

void ParameterPanel::setOptions(const FitOptions& o) {
  m_updating = true;
  m_base = o;
  m_tolerance->setValue(100.0 * o.tolerance_fraction);
  m_max_extrema->setValue(o.segmentation.max_extrema);
  m_g2->setCurrentIndex(m_g2->findData(static_cast<int>(o.g2)));
  m_threshold->setValue(std::log10(o.g2_threshold));
  m_corners->setChecked(o.cleanup.detect_corners);
  m_polish->setChecked(o.polish);
  m_updating = false;
}

void ParameterPanel::setSegmentAlpha(bool enabled, double alpha, const QString& reason) {
  m_updating = true;
  m_alpha->setEnabled(enabled);
  m_alpha_slider->setEnabled(enabled);
  if (enabled) {
    m_alpha->setValue(alpha);
    m_alpha_slider->setValue(sliderTicks(alpha));
  }
  m_alpha->setToolTip(enabled ? "the selected segment's LCG slope; the curve stays G2" : reason);
  m_alpha_slider->setToolTip(m_alpha->toolTip());
  m_updating = false;
}

FitOptions ParameterPanel::options() const {
  FitOptions o = m_base;
  o.tolerance_fraction = m_tolerance->value() / 100.0;
  o.segmentation.max_extrema = m_max_extrema->value();
  o.g2 = static_cast<G2Method>(m_g2->currentData().toInt());
  o.g2_threshold = std::pow(10.0, m_threshold->value());
  o.cleanup.detect_corners = m_corners->isChecked();
  o.polish = m_polish->isChecked();
  return o;
}

}  // namespace la::gui
