#pragma once
// The selected construction's numbers (alphas, end curvatures, degree...), one spin box
// and slider per parameter, the solver's status, and a delete button. The handles are
// dragged on the canvas; this panel only edits the parameters.

#include <QWidget>
#include <map>
#include <string>
#include <vector>

#include "app/gui/construction.h"

class QCheckBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;
class QPushButton;
class QSlider;

namespace la::gui {

class ConstructionPanel : public QWidget {
  Q_OBJECT
 public:
  explicit ConstructionPanel(QWidget* parent = nullptr);
  /// Shows a construction's parameters and status (nullptr: none selected).
  void setConstruction(const Construction* construction);

 signals:
  void parametersChanged(const std::map<std::string, double>& parameters);
  void deleteRequested();

 private:
  struct Row {
    ParameterSpec spec;
    QDoubleSpinBox* box = nullptr;
    QSlider* slider = nullptr;
    QCheckBox* automatic = nullptr;  // optional parameters only
    QCheckBox* toggle = nullptr;     // toggles instead of box and slider
  };
  std::map<std::string, double> values() const;
  void emitChanged();

  QLabel* m_title = nullptr;
  QWidget* m_rows_widget = nullptr;
  QFormLayout* m_rows = nullptr;
  QLabel* m_status = nullptr;
  QPushButton* m_delete = nullptr;
  std::vector<Row> m_params;
  bool m_updating = false;
};

}  // namespace la::gui
