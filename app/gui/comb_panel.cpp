#include "app/gui/comb_panel.h"

#include <QButtonGroup>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QRadioButton>
#include <QSlider>
#include <QSpinBox>
#include <QVBoxLayout>
#include <cmath>

#include "app/gui/canvas.h"
#include "app/gui/markers.h"

namespace la::gui {
namespace {

// The scale's range in percent of the view's shorter side: below half a percent the teeth
// vanish under the curve, above half the view they cross the drawing.
constexpr double kMinScalePercent = 0.5, kMaxScalePercent = 50.0;
constexpr int kScaleSliderSteps = 10;  // per percent
constexpr int kMinTeeth = 4, kMaxTeeth = 400;
constexpr int kLegendRow = 20;  // pixels
const QColor kLegendComb(211, 47, 47, 160);
const QColor kLegendControl(120, 60, 170);

}  // namespace

MarkerLegend::MarkerLegend(QWidget* parent) : QWidget(parent) { setMinimumHeight(sizeHint().height()); }

QStringList MarkerLegend::entries() const {
  QStringList out;
  for (MarkerKind kind : kMarkerKinds) out << markerName(kind);
  out << "control point (drag it)" << "curvature comb";
  return out;
}

QSize MarkerLegend::sizeHint() const { return {180, kLegendRow * static_cast<int>(kMarkerKinds.size() + 2) + 4}; }

void MarkerLegend::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  int row = 0;
  auto label = [&](const QString& text) {
    p.setPen(palette().color(QPalette::WindowText));
    p.drawText(QRectF(34, row * kLegendRow, width() - 34, kLegendRow), Qt::AlignVCenter | Qt::AlignLeft, text);
    ++row;
  };
  auto centre = [&] { return QPointF(14, row * kLegendRow + kLegendRow / 2.0); };
  for (MarkerKind kind : kMarkerKinds) {
    p.setPen(QPen(Qt::black, 1.0));
    drawMarker(p, kind, centre());
    label(markerName(kind));
  }
  p.setPen(QPen(kLegendControl, 1.2));
  p.setBrush(Qt::NoBrush);
  drawControlPoint(p, centre());
  label("control point (drag it)");
  p.setPen(QPen(kLegendComb, 1.0));
  const QPointF c = centre();
  for (int i = -2; i <= 2; ++i) p.drawLine(c + QPointF(4 * i, 6), c + QPointF(4 * i, 6 - (8 - 1.5 * i * i)));
  label("curvature comb");
}

CombPanel::CombPanel(QWidget* parent) : QWidget(parent) {
  auto* form = new QFormLayout;
  m_scale_slider = new QSlider(Qt::Horizontal);
  m_scale_slider->setObjectName("comb-scale-slider");
  m_scale_slider->setRange(static_cast<int>(kMinScalePercent * kScaleSliderSteps), static_cast<int>(kMaxScalePercent * kScaleSliderSteps));
  m_scale = new QDoubleSpinBox;
  m_scale->setObjectName("comb-scale");
  m_scale->setRange(kMinScalePercent, kMaxScalePercent);
  m_scale->setDecimals(1);
  m_scale->setSingleStep(0.5);
  m_scale->setSuffix(" % of view");
  m_scale->setKeyboardTracking(false);  // a typed value applies on Enter (issue 17, part 4)
  m_scale->setToolTip("the longest tooth, as a share of the view's shorter side");
  auto* scale_row = new QHBoxLayout;
  scale_row->addWidget(m_scale_slider, 1);
  scale_row->addWidget(m_scale);
  form->addRow("Scale", scale_row);

  m_teeth_slider = new QSlider(Qt::Horizontal);
  m_teeth_slider->setObjectName("comb-teeth-slider");
  m_teeth_slider->setRange(kMinTeeth, kMaxTeeth);
  m_teeth = new QSpinBox;
  m_teeth->setObjectName("comb-teeth");
  m_teeth->setRange(kMinTeeth, kMaxTeeth);
  m_teeth->setKeyboardTracking(false);
  m_teeth->setToolTip("teeth along each curve, evenly spaced in arc length");
  auto* teeth_row = new QHBoxLayout;
  teeth_row->addWidget(m_teeth_slider, 1);
  teeth_row->addWidget(m_teeth);
  form->addRow("Teeth", teeth_row);

  m_per_curve = new QRadioButton("each curve its own");
  m_per_curve->setObjectName("comb-per-curve");
  m_per_curve->setToolTip("each curve's longest tooth is the scale: every comb reads well");
  m_shared = new QRadioButton("same for all curves");
  m_shared->setObjectName("comb-shared");
  m_shared->setToolTip("one scale for every curve, set by the largest curvature of all: combs compare");
  auto* group = new QButtonGroup(this);
  group->addButton(m_per_curve);
  group->addButton(m_shared);
  auto* mode = new QVBoxLayout;
  mode->addWidget(m_per_curve);
  mode->addWidget(m_shared);
  form->addRow("Scale of", mode);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  auto* legend_title = new QLabel("<b>Marks on the curves</b>");
  layout->addWidget(legend_title);
  layout->addWidget(new MarkerLegend);
  layout->addStretch(1);

  connect(m_scale_slider, &QSlider::valueChanged, this, [this](int v) {
    if (m_updating) return;
    m_updating = true;
    m_scale->setValue(static_cast<double>(v) / kScaleSliderSteps);
    m_updating = false;
    emitChanged();
  });
  connect(m_scale, &QDoubleSpinBox::valueChanged, this, [this](double v) {
    if (m_updating) return;
    m_updating = true;
    m_scale_slider->setValue(static_cast<int>(std::lround(v * kScaleSliderSteps)));
    m_updating = false;
    emitChanged();
  });
  connect(m_teeth_slider, &QSlider::valueChanged, this, [this](int v) {
    if (m_updating) return;
    m_updating = true;
    m_teeth->setValue(v);
    m_updating = false;
    emitChanged();
  });
  connect(m_teeth, &QSpinBox::valueChanged, this, [this](int v) {
    if (m_updating) return;
    m_updating = true;
    m_teeth_slider->setValue(v);
    m_updating = false;
    emitChanged();
  });
  connect(m_shared, &QRadioButton::toggled, this, [this] { emitChanged(); });
  setSettings(0.08, 96, false);
}

void CombPanel::emitChanged() {
  if (!m_updating) emit settingsChanged();
}

void CombPanel::setSettings(double scale, int teeth, bool shared) {
  m_updating = true;
  m_scale->setValue(100.0 * scale);
  m_scale_slider->setValue(static_cast<int>(std::lround(100.0 * scale * kScaleSliderSteps)));
  m_teeth->setValue(teeth);
  m_teeth_slider->setValue(teeth);
  (shared ? m_shared : m_per_curve)->setChecked(true);
  m_updating = false;
}

double CombPanel::scale() const { return m_scale->value() / 100.0; }
int CombPanel::teeth() const { return m_teeth->value(); }
bool CombPanel::shared() const { return m_shared->isChecked(); }

}  // namespace la::gui
