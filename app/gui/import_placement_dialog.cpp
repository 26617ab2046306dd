#include "app/gui/import_placement_dialog.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QLabel>
#include <QPushButton>
#include <QRadioButton>
#include <QVBoxLayout>

namespace la::gui {

ImportPlacementDialog::ImportPlacementDialog(QWidget* parent, const QString& file, const QString& units,
                                             ImportPlacement preset)
    : QDialog(parent) {
  setObjectName("import-placement");
  setWindowTitle("Import points");
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(new QLabel(QString("Where should the points of %1 go?").arg(file)));
  m_fit = new QRadioButton("&Fit to the view: scaled and moved to fill it (an airfoil of chord 1 becomes large)");
  m_fit->setObjectName("fit-to-view");
  m_own = new QRadioButton(QString("At their &own coordinates, read as %1; the view is fitted after")
                               .arg(units.isEmpty() ? QString("unitless") : units));
  m_own->setObjectName("own-coordinates");
  (preset == ImportPlacement::kOwnCoordinates ? m_own : m_fit)->setChecked(true);
  layout->addWidget(m_fit);
  layout->addWidget(m_own);
  m_remember = new QCheckBox("&Remember my choice (File > Import placement changes it)");
  m_remember->setObjectName("remember");
  layout->addWidget(m_remember);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  buttons->button(QDialogButtonBox::Ok)->setText("Import");
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  layout->addWidget(buttons);
}

ImportPlacement ImportPlacementDialog::choice() const {
  return m_own->isChecked() ? ImportPlacement::kOwnCoordinates : ImportPlacement::kFitToView;
}

bool ImportPlacementDialog::remember() const { return m_remember->isChecked(); }

}  // namespace la::gui
