#pragma once
// The application window: the canvas in the middle, the curvature plot and the fit
// parameters in docks, menus for files, editing and layers, and a status bar with the
// fitted stroke's figures. Every change of the document goes through the undo stack;
// the document is autosaved so nothing drawn is lost.

#include <QMainWindow>
#include <QString>

#include "app/gui/document.h"

class QLabel;
class QTimer;
class QUndoStack;

namespace la::gui {

class Canvas;
class CurvaturePlot;
class ParameterPanel;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);
  Document& document() { return m_document; }
  Canvas* canvas() const { return m_canvas; }
  QUndoStack* undoStack() const { return m_undo; }
  ParameterPanel* parameters() const { return m_parameters; }

  // The file actions without dialogs (the dialogs call these); errors are shown in a
  // message box and returned as false, never thrown.
  bool openFile(const QString& path);
  bool saveFile(const QString& path);
  bool importPoints(const QString& path);
  bool exportFile(const QString& path);  // format from the extension: svg, dxf, json, csv
  QString autosavePath() const;

  /// Records a stroke (as the canvas does on pen-up), undoably.
  void addStroke(const Stroke& stroke);
  /// Called after any change of the document: repaint, plot, status.
  void documentChanged();

 private:
  void buildMenus();
  void showError(const QString& what);
  void autosave();

  Document m_document;
  Canvas* m_canvas = nullptr;
  CurvaturePlot* m_plot = nullptr;
  ParameterPanel* m_parameters = nullptr;
  QUndoStack* m_undo = nullptr;
  QLabel* m_status = nullptr;
  QTimer* m_autosave = nullptr;
  QString m_path;
  bool m_dirty = false;
};

}  // namespace la::gui
