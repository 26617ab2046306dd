#pragma once
// The application window: the canvas in the middle, the curvature plot and the fit
// parameters in docks, menus for files, editing and layers, and a status bar with the
// fitted stroke's figures. Every change of the document goes through the undo stack;
// the document is autosaved so nothing drawn is lost.

#include <QFutureWatcher>
#include <QMainWindow>
#include <QMessageBox>
#include <QString>
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "app/gui/document.h"
#include "app/gui/import_placement.h"
#include "app/gui/tools.h"

class QActionGroup;
class QLabel;
class QSpinBox;
class QMenu;
class QTimer;
class QUndoStack;

namespace la::gui {

class Canvas;
class CombPanel;
class ConstructionPanel;
class CurvaturePlot;
class LcgPlot;
class ParameterPanel;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;
  Document& document() { return m_document; }
  Canvas* canvas() const { return m_canvas; }
  QUndoStack* undoStack() const { return m_undo; }
  ParameterPanel* parameters() const { return m_parameters; }
  int selectedStroke() const { return m_selected_stroke; }
  int selectedPiece() const { return m_selected_piece; }

  // The file actions without dialogs (the dialogs call these); errors are shown in a
  // message box and returned as false, never thrown.
  bool openFile(const QString& path);
  bool saveFile(const QString& path);
  /// Imports a point file as one undo step: read off the UI thread (point_import.h; a
  /// progress dialog with Cancel for a slow read; cancelled or failed, the sketch is
  /// unchanged), placed as `placement` says, or as File > Import placement says (asking
  /// in a dialog where it says so; under LAFAIR_NO_DIALOGS "ask" keeps own coordinates).
  /// The status bar says where the points went ("imported at scale S").
  bool importPoints(const QString& path, std::optional<ImportPlacement> placement = std::nullopt);
  /// File > Import placement, remembered in QSettings ("import/placement").
  ImportPlacement importPlacement() const { return m_import_placement; }
  void setImportPlacement(ImportPlacement placement);
  bool importing() const { return m_importing; }  // a read is running (its event loop is)
  /// Format from the extension: svg, dxf, json, csv. All curves, or only the selected stroke's.
  bool exportFile(const QString& path, bool selected_only = false);
  /// What an SVG export adds to the curves (remembered in QSettings; off by default).
  void setExportExtras(bool points, bool comb);
  bool exportPng(const QString& path);   // the canvas and the plots, side by side
  bool loadBackground(const QString& path);  // a raster image to trace over
  /// Offers the autosaved sketch if the last session did not end cleanly (no dialog
  /// under LAFAIR_NO_DIALOGS: then it only reports whether there is one).
  bool offerRecovery();
  QString autosavePath() const;

  /// Records a stroke, undoably (imports use it; a drawn stroke goes through strokeDrawn).
  void addStroke(const Stroke& stroke);
  /// A stroke the canvas finished (pen-up): oversketches the stroke it starts or ends near
  /// (app/gui/oversketch.h) as one undo step where oversketch is on, else adds it.
  void strokeDrawn(const Stroke& stroke);
  /// Edit > Oversketch (remembered in QSettings), and its reach in pixels.
  bool oversketchEnabled() const;
  void setOversketch(bool on);
  double oversketchReach() const { return m_oversketch_reach; }
  void setOversketchReach(double pixels);
  /// Removes the selected strokes (or, where none is, the selected segment's stroke) as
  /// one undo step; says so where nothing is selected.
  void deleteSelectedStrokes();
  /// The selected strokes' indices, increasing (the Select tool, Edit > Select all).
  std::vector<std::size_t> selectedStrokes() const;
  void selectAll();       // every stroke (not an undo step: the document does not change)
  void clearSelection();  // strokes and segment
  /// Moves strokes by `d` (world) undoably, without refitting; the steps of one drag
  /// (`drag`) merge into one undo step.
  void moveStrokes(const std::vector<std::size_t>& strokes, const Vec2& d, int drag);
  Tool tool() const;
  void setTool(Tool tool);  // as its toolbar button does
  QAction* toolAction(Tool tool) const;
  /// Called after any change of the document: repaint, plot, status.
  void documentChanged();
  void selectSegment(int stroke, int piece);  // -1, -1: none
  /// Adds a construction of that kind in the middle of the view, undoably, and selects it.
  void addConstruction(ConstructionKind kind);
  void selectConstruction(int index);         // -1: none
  int selectedConstruction() const { return m_selected_construction; }
  /// Replaces construction `index` by `after` as one undoable step (`before` is what undo restores).
  void editConstruction(int index, const Construction& before, const Construction& after, const QString& what);
  void showMessage(const QString& what);      // in the status bar
  /// Before work is replaced (New, Open, Quit, closing the window): true if there are no
  /// unsaved changes, or the user saved them or chose to discard them; false to cancel.
  /// Asks Save / Discard / Cancel, naming what would be lost; under LAFAIR_NO_DIALOGS it
  /// takes the answer set by answerUnsavedChanges (Discard unless set).
  bool keepOrDiscardChanges(const QString& before);
  void answerUnsavedChanges(QMessageBox::StandardButton answer) { m_unsaved_answer = answer; }
  /// A drawn stroke shows its stages 1-6 fit at pen-up; stage 7 runs on a worker thread
  /// and replaces it when done (a hard stroke takes a few hundred ms). This waits for
  /// those still running and takes their results (saving, exporting and tests use it).
  void finishBackgroundFits();
  /// Starts stage 7 of provisional stroke `index` off the UI thread. A fit of that stroke
  /// still waiting for a thread is dropped: only the newest request's result can apply.
  void fitInBackground(std::size_t index);
  void fitProvisionalInBackground();  // of every provisional stroke
  /// Background fits dropped before they ran because a newer one for the same stroke
  /// was requested (rapid parameter changes).
  int supersededBackgroundFits() const { return m_superseded_fits; }

 protected:
  void closeEvent(QCloseEvent* event) override;

 private:
  struct BackgroundFit {
    std::uint64_t id = 0;
    Vec2 fitted_at = Vec2::Zero();  // the stroke's first raw sample as fitted (it may move meanwhile)
    FitOptions options;
    std::optional<FitResult> fit;
    std::string error;
    std::shared_ptr<std::atomic<bool>> superseded_flag;  // set when a newer fit of the stroke is requested
    bool superseded = false;                             // so it did not run
  };
  void takeBackgroundFit(QFutureWatcher<BackgroundFit>* watcher);
  void buildMenus();
  void buildToolBar();
  void applyCombSettings();  // the comb dock's settings to the canvas
  void showError(const QString& what);
  void autosave();
  void updatePreview();  // live fit of the stroke being drawn, as often as time allows
  // The curvature plot shows `shown` as stroke `stroke`'s curve (-1: a stroke being drawn):
  // alone, or among every visible stroke (the plot's scope), highlighted.
  void plotCurvature(const FitResult* shown, int stroke);
  void refreshCurvaturePlot();  // after a change of scope or view: what the selection shows
  void rememberRecent(const QString& path);
  void refreshRecentMenu();

  Document m_document;
  Canvas* m_canvas = nullptr;
  QAction* m_oversketch = nullptr;
  ImportPlacement m_import_placement = ImportPlacement::kAsk;
  QActionGroup* m_placement_actions = nullptr;
  bool m_importing = false;
  bool m_export_points = false, m_export_comb = false;
  QSpinBox* m_oversketch_reach_box = nullptr;
  double m_oversketch_reach = 8.0;  // pixels (kDefaultOversketchReachPixels)
  CurvaturePlot* m_plot = nullptr;
  LcgPlot* m_lcg = nullptr;
  QTimer* m_plot_refresh = nullptr;  // coalesces the view changes of a pan or zoom
  QMenu* m_recent = nullptr;
  int m_selected_stroke = -1, m_selected_piece = -1;
  double m_preview_ms = 0.0;   // time of the last live fit
  qint64 m_preview_at = 0;     // when it ran (ms since epoch)
  ParameterPanel* m_parameters = nullptr;
  ConstructionPanel* m_construction_panel = nullptr;
  CombPanel* m_comb_panel = nullptr;
  QActionGroup* m_tools = nullptr;
  int m_selected_construction = -1;
  std::optional<Construction> m_handle_drag_before;  // the construction as it was when a handle drag began
  QUndoStack* m_undo = nullptr;
  QLabel* m_status = nullptr;
  QTimer* m_autosave = nullptr;
  QString m_path;
  bool m_dirty = false;
  QMessageBox::StandardButton m_unsaved_answer = QMessageBox::Discard;  // (LAFAIR_NO_DIALOGS)
  bool m_discarded = false;  // the user chose to lose the unsaved changes (the recovery marker may go)
  std::vector<QFutureWatcher<BackgroundFit>*> m_background;  // running, in start order
  // Per stroke id, the flag of its newest background fit; set when a newer one is asked for.
  std::map<std::uint64_t, std::shared_ptr<std::atomic<bool>>> m_newest_fit;
  int m_superseded_fits = 0;
};

}  // namespace la::gui
