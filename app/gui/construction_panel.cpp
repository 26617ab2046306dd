#include "app/gui/construction_panel.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSlider>
#include <QVBoxLayout>
#include <cmath>
#include <limits>

namespace la::gui {
namespace {

constexpr int kSliderSteps = 1000;

int toSlider(const ParameterSpec& spec, double value) {
  return static_cast<int>(std::lround(kSliderSteps * (value - spec.min) / (spec.max - spec.min)));
}
double fromSlider(const ParameterSpec& spec, int position) {
  return spec.min + (spec.max - spec.min) * position / kSliderSteps;
}

}  // namespace

ConstructionPanel::ConstructionPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  m_title = new QLabel;
  m_title->setWordWrap(true);
  layout->addWidget(m_title);
  m_rows_widget = new QWidget;
  m_rows = new QFormLayout(m_rows_widget);
  m_rows->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(m_rows_widget);
  m_status = new QLabel;
  m_status->setWordWrap(true);
  m_status->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(m_status);
  m_delete = new QPushButton("Delete construction");
  layout->addWidget(m_delete);
  layout->addStretch(1);
  connect(m_delete, &QPushButton::clicked, this, &ConstructionPanel::deleteRequested);
  setConstruction(nullptr);
}

void ConstructionPanel::setConstruction(const Construction* c) {
  m_updating = true;
  const bool same_kind = c && !m_params.empty() && parameterSpecs(c->kind).size() == m_params.size() &&
                         parameterSpecs(c->kind).front().key == m_params.front().spec.key;
  if (!same_kind) {  // rebuild the rows for this kind
    while (m_rows->rowCount() > 0) m_rows->removeRow(0);
    m_params.clear();
    if (c) {
      for (const ParameterSpec& spec : parameterSpecs(c->kind)) {
        Row row{spec};
        auto* line = new QWidget;
        auto* h = new QHBoxLayout(line);
        h->setContentsMargins(0, 0, 0, 0);
        if (spec.type == ParameterSpec::Type::kToggle) {
          row.toggle = new QCheckBox;
          row.toggle->setToolTip(QString::fromStdString(spec.tooltip));
          connect(row.toggle, &QCheckBox::toggled, this, [this] { emitChanged(); });
          m_rows->addRow(QString::fromStdString(spec.label), row.toggle);
          m_params.push_back(row);
          continue;
        }
        row.box = new QDoubleSpinBox;
        row.box->setRange(spec.min, spec.max);
        row.box->setDecimals(spec.decimals);
        row.box->setSingleStep(std::pow(10.0, -std::min(spec.decimals, 2)) * (spec.decimals == 0 ? 1.0 : 5.0));
        row.box->setKeyboardTracking(false);
        row.slider = new QSlider(Qt::Horizontal);
        row.slider->setRange(0, kSliderSteps);
        h->addWidget(row.slider, 1);
        h->addWidget(row.box);
        if (spec.optional) {
          row.automatic = new QCheckBox("auto");
          h->addWidget(row.automatic);
          connect(row.automatic, &QCheckBox::toggled, this, [this] { emitChanged(); });
        }
        line->setToolTip(QString::fromStdString(spec.tooltip));
        QDoubleSpinBox* box = row.box;
        QSlider* slider = row.slider;
        connect(box, &QDoubleSpinBox::valueChanged, this, [this, spec, slider](double v) {
          if (m_updating) return;
          m_updating = true;
          slider->setValue(toSlider(spec, v));
          m_updating = false;
          emitChanged();
        });
        connect(slider, &QSlider::valueChanged, this, [this, spec, box](int position) {
          if (m_updating) return;
          m_updating = true;
          box->setValue(fromSlider(spec, position));
          m_updating = false;
          emitChanged();
        });
        m_rows->addRow(QString::fromStdString(spec.label), line);
        m_params.push_back(row);
      }
    }
  }
  m_title->setText(c ? QString("<b>%1</b><br>drag its handles on the canvas").arg(displayName(c->kind))
                     : "Construct > … adds a curve built from handles; click a handle to select its curve.");
  for (Row& row : m_params) {
    const double v = c->parameter(row.spec.key);
    if (row.toggle) {
      row.toggle->setChecked(v != 0.0);
      continue;
    }
    const bool automatic = std::isnan(v);
    if (row.automatic) row.automatic->setChecked(automatic);
    row.box->setEnabled(!automatic);
    row.slider->setEnabled(!automatic);
    if (!automatic) {
      row.box->setValue(v);
      row.slider->setValue(toSlider(row.spec, v));
    }
  }
  m_status->setText(c ? QString::fromStdString((c->result.ok ? "solved: " : "no curve: ") + c->result.message) : QString());
  m_status->setStyleSheet(c && !c->result.ok ? "color: #c62828" : "");
  m_delete->setEnabled(c != nullptr);
  m_updating = false;
}

std::map<std::string, double> ConstructionPanel::values() const {
  std::map<std::string, double> out;
  for (const Row& row : m_params)
    out[row.spec.key] = row.toggle ? (row.toggle->isChecked() ? 1.0 : 0.0) : row.automatic && row.automatic->isChecked() ? std::numeric_limits<double>::quiet_NaN() : row.box->value();
  return out;
}

void ConstructionPanel::emitChanged() {
  if (!m_updating) emit parametersChanged(values());
}

}  // namespace la::gui
