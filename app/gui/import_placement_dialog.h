#pragma once
// The question asked on File > Import points while File > Import placement says "ask":
// fit the points to the view, or keep their own coordinates (in the document's units),
// and whether to remember the answer (then the menu holds it and the dialog stops asking).

#include <QDialog>

#include "app/gui/import_placement.h"

class QCheckBox;
class QRadioButton;

namespace la::gui {

class ImportPlacementDialog : public QDialog {
  Q_OBJECT
 public:
  /// `file`: the name shown; `units`: the document's ("" unitless); `preset`: the choice
  /// selected at first (kFitToView or kOwnCoordinates).
  ImportPlacementDialog(QWidget* parent, const QString& file, const QString& units, ImportPlacement preset);
  ImportPlacement choice() const;
  bool remember() const;

 private:
  QRadioButton* m_fit = nullptr;
  QRadioButton* m_own = nullptr;
  QCheckBox* m_remember = nullptr;
};

}  // namespace la::gui
