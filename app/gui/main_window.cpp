#include "app/gui/main_window.h"

#include <QAction>
#include <QActionGroup>
#include <QToolBar>
#include <QToolButton>
#include <QCloseEvent>
#include <QDateTime>
#include <QElapsedTimer>
#include <QHBoxLayout>
#include <QInputDialog>
#include <QPainter>
#include <QSettings>
#include <QApplication>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTimer>
#include <QUndoCommand>
#include <QUndoStack>
#include <QSpinBox>
#include <QComboBox>
#include <QWidgetAction>
#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>
#include <cmath>
#include <functional>

#include "app/gui/canvas.h"
#include "app/gui/comb_panel.h"
#include "app/gui/construction_panel.h"
#include "app/gui/curvature_plot.h"
#include "app/gui/import_placement_dialog.h"
#include "app/gui/lcg_plot.h"
#include "app/gui/oversketch.h"
#include "app/gui/parameter_panel.h"
#include "app/gui/point_import.h"
#include "app/io/curve_export.h"
#include "app/io/point_file.h"
#include "core/atomic_file.h"
#include "core/curve_json.h"
#include "fitting/user_edits.h"

namespace la::gui {
namespace {

constexpr int kAutosaveMs = 20000;
// Live preview: refit the stroke being drawn at most this often, and never more often
// than every kPreviewCostFactor fit-times, so the pen never waits for the fit.
constexpr int kPreviewMinIntervalMs = 30;
constexpr double kPreviewCostFactor = 4.0;
constexpr int kPreviewMinPoints = 8;
constexpr int kRecentFiles = 8;
// "All visible strokes" follows a pan or zoom at most this often (a frame and a half):
// it samples every visible curve, too much for every mouse move of a pan.
constexpr int kPlotRefreshMs = 25;
// Exported Bezier paths stay within this fraction of the fit tolerance of the LA curves.
constexpr double kExportToleranceOfFit = 0.1;
// How long the status bar says where an import went, before the fit's figures return.
constexpr int kImportMessageMs = 15000;

const char* settingName(ImportPlacement p) {
  switch (p) {
    case ImportPlacement::kFitToView: return "fit-to-view";
    case ImportPlacement::kOwnCoordinates: return "own-coordinates";
    case ImportPlacement::kAsk: break;
  }
  return "ask";
}

ImportPlacement placementFromSetting(const QString& name) {
  if (name == "fit-to-view") return ImportPlacement::kFitToView;
  if (name == "own-coordinates") return ImportPlacement::kOwnCoordinates;
  return ImportPlacement::kAsk;
}

class AddStrokeCommand : public QUndoCommand {
 public:
  AddStrokeCommand(MainWindow* w, Stroke s) : QUndoCommand("draw stroke"), m_window(w), m_stroke(std::move(s)) {}
  void redo() override {
    m_index = m_window->document().strokes().size();
    m_window->document().insertStroke(m_index, m_stroke, /*provisional=*/true,
                                      /*unfitted=*/m_stroke.samples.size() > Document::kOffThreadFitSamples);
    m_window->fitInBackground(m_index);
    m_window->documentChanged();
  }
  void undo() override {
    m_window->document().removeStroke(m_index);
    m_window->documentChanged();
  }

 private:
  MainWindow* m_window;
  Stroke m_stroke;
  std::size_t m_index = 0;
};

// An import: every stroke of a file as one step, added as drawn strokes are (provisional,
// stage 7 in the background). Where they hold more samples together than one pen-up may
// fit on the UI thread (Document::kOffThreadFitSamples), all are inserted unfitted and
// fitted entirely in the background: a large file never holds the UI past a frame.
class ImportStrokesCommand : public QUndoCommand {
 public:
  ImportStrokesCommand(MainWindow* w, const QString& text, std::vector<Stroke> strokes)
      : QUndoCommand(text), m_window(w), m_strokes(std::move(strokes)) {}
  void redo() override {
    Document& d = m_window->document();
    m_first = d.strokes().size();
    std::size_t samples = 0;
    for (const Stroke& s : m_strokes) samples += s.samples.size();
    const bool unfitted = samples > Document::kOffThreadFitSamples;
    for (std::size_t k = 0; k < m_strokes.size(); ++k) d.insertStroke(m_first + k, m_strokes[k], /*provisional=*/true, unfitted);
    for (std::size_t k = 0; k < m_strokes.size(); ++k) m_window->fitInBackground(m_first + k);
    m_window->documentChanged();
  }
  void undo() override {
    for (std::size_t k = m_strokes.size(); k-- > 0;) m_window->document().removeStroke(m_first + k);
    m_window->documentChanged();
  }

 private:
  MainWindow* m_window;
  std::vector<Stroke> m_strokes;
  std::size_t m_first = 0;
};

// An oversketch: stroke `index` replaced by the spliced raw stroke, refitted like a drawn
// one (provisional now, in full in the background). Undo puts the old stroke back exactly
// (fit, the user's edits), without a refit.
class ReplaceStrokeCommand : public QUndoCommand {
 public:
  ReplaceStrokeCommand(MainWindow* w, const QString& text, std::size_t index, Stroke raw)
      : QUndoCommand(text), m_window(w), m_index(index), m_raw(std::move(raw)), m_before(w->document().strokes()[index]) {}
  void redo() override {
    Document& d = m_window->document();
    d.removeStroke(m_index);
    d.insertStroke(m_index, m_raw, /*provisional=*/true, /*unfitted=*/m_raw.samples.size() > Document::kOffThreadFitSamples);
    m_window->fitInBackground(m_index);
    m_window->documentChanged();
  }
  void undo() override {
    m_window->document().restoreStroke(m_index, m_before);
    // (its own background fit may have been dropped while it was replaced)
    if (m_before.provisional) m_window->fitInBackground(m_index);
    m_window->documentChanged();
  }

 private:
  MainWindow* m_window;
  std::size_t m_index;
  Stroke m_raw;
  DocumentStroke m_before;
};

// Removes strokes as one step; undo puts them back as they were (fit, the user's edits),
// without a refit, and selected.
class DeleteStrokesCommand : public QUndoCommand {
 public:
  DeleteStrokesCommand(MainWindow* w, std::vector<std::size_t> indices)  // increasing
      : QUndoCommand(indices.size() == 1 ? QString("delete stroke") : QString("delete %1 strokes").arg(indices.size())),
        m_window(w), m_indices(std::move(indices)) {
    for (std::size_t i : m_indices) m_strokes.push_back(w->document().strokes()[i]);
  }
  void redo() override {
    for (auto i = m_indices.rbegin(); i != m_indices.rend(); ++i) m_window->document().removeStroke(*i);
    m_window->documentChanged();
  }
  void undo() override {
    for (std::size_t k = 0; k < m_indices.size(); ++k)
      m_window->document().restoreStroke(m_indices[k], m_strokes[k], /*insert=*/true);
    m_window->documentChanged();
    m_window->canvas()->selection().set(m_window->document(), m_indices);
  }

 private:
  MainWindow* m_window;
  std::vector<std::size_t> m_indices;
  std::vector<DocumentStroke> m_strokes;
};

// Moves strokes by a translation, which does not change their fits: no refit. The
// steps of one drag merge (QUndoStack::push merges commands of one id), so a drag is one
// undo step; undo moves them back and selects them.
class MoveStrokesCommand : public QUndoCommand {
 public:
  static constexpr int kId = 1701;
  MoveStrokesCommand(MainWindow* w, std::vector<std::size_t> strokes, const Vec2& d, int drag)
      : QUndoCommand(strokes.size() == 1 ? QString("move stroke") : QString("move %1 strokes").arg(strokes.size())),
        m_window(w), m_strokes(std::move(strokes)), m_d(d), m_drag(drag) {}
  void redo() override { apply(m_d); }
  void undo() override { apply(-m_d); }
  int id() const override { return kId; }
  bool mergeWith(const QUndoCommand* other) override {
    const auto* next = static_cast<const MoveStrokesCommand*>(other);
    if (next->m_drag != m_drag || next->m_strokes != m_strokes) return false;
    m_d += next->m_d;
    return true;
  }

 private:
  void apply(const Vec2& d) {
    const int stroke = m_window->selectedStroke(), piece = m_window->selectedPiece();
    m_window->document().translateStrokes(m_strokes, d);
    m_window->documentChanged();
    m_window->selectSegment(stroke, piece);  // (indices do not change in a move)
    m_window->canvas()->selection().set(m_window->document(), m_strokes);
  }
  MainWindow* m_window;
  std::vector<std::size_t> m_strokes;
  Vec2 m_d;
  int m_drag;
};

class SetOptionsCommand : public QUndoCommand {
 public:
  SetOptionsCommand(MainWindow* w, FitOptions before, FitOptions after)
      : QUndoCommand("change fit parameters"), m_window(w), m_before(before), m_after(after) {}
  void redo() override { apply(m_after); }
  void undo() override { apply(m_before); }

 private:
  void apply(const FitOptions& o) {
    m_window->document().setOptions(o, /*provisional=*/true);
    m_window->fitProvisionalInBackground();
    m_window->parameters()->setOptions(o);
    m_window->documentChanged();
  }
  MainWindow* m_window;
  FitOptions m_before, m_after;
};

// A user edit of one fitted stroke (steer a segment's alpha, move a joint). Undo puts
// the stroke back as it was, overrides and fit together, without refitting.
class EditStrokeCommand : public QUndoCommand {
 public:
  using Edit = std::function<std::string(Document&)>;
  EditStrokeCommand(MainWindow* w, const QString& text, std::size_t stroke, int piece, Edit edit)
      : QUndoCommand(text), m_window(w), m_stroke(stroke), m_piece(piece), m_edit(std::move(edit)),
        m_before(w->document().strokes()[stroke]) {}
  void redo() override {
    const std::string why = m_edit(m_window->document());
    m_window->documentChanged();
    m_window->selectSegment(static_cast<int>(m_stroke), m_piece);
    if (!why.empty()) m_window->showMessage(QString::fromStdString(why));
  }
  void undo() override {
    m_window->document().restoreStroke(m_stroke, m_before);
    m_window->documentChanged();
    m_window->selectSegment(static_cast<int>(m_stroke), m_piece);
  }

 private:
  MainWindow* m_window;
  std::size_t m_stroke;
  int m_piece;
  Edit m_edit;
  DocumentStroke m_before;
};

// Adds, removes or replaces one construction: `before` empty adds `after` at `index`,
// `after` empty removes it.
class ConstructionCommand : public QUndoCommand {
 public:
  ConstructionCommand(MainWindow* w, const QString& text, std::size_t index, std::optional<Construction> before,
                      std::optional<Construction> after)
      : QUndoCommand(text), m_window(w), m_index(index), m_before(std::move(before)), m_after(std::move(after)) {}
  void redo() override { apply(m_before, m_after); }
  void undo() override { apply(m_after, m_before); }

 private:
  void apply(const std::optional<Construction>& from, const std::optional<Construction>& to) {
    Document& d = m_window->document();
    if (from && to) d.replaceConstruction(m_index, *to);
    else if (to) d.insertConstruction(m_index, *to);
    else d.removeConstruction(m_index);
    m_window->documentChanged();
    m_window->selectConstruction(to ? static_cast<int>(m_index) : -1);
  }
  MainWindow* m_window;
  std::size_t m_index;
  std::optional<Construction> m_before, m_after;
};

}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  setWindowTitle("lafair — fair curves from strokes");
  m_undo = new QUndoStack(this);
  m_canvas = new Canvas;
  m_canvas->setDocument(&m_document);
  setCentralWidget(m_canvas);
  // (the canvas has the focus at start, not the first field of a dock: a key typed before
  // anything is clicked must not edit the tolerance)
  m_canvas->setFocusPolicy(Qt::StrongFocus);
  m_canvas->setFocus();

  m_plot = new CurvaturePlot;
  auto* plot_dock = new QDockWidget("Curvature plot", this);
  plot_dock->setObjectName("curvature-plot");
  plot_dock->setWidget(m_plot);
  addDockWidget(Qt::BottomDockWidgetArea, plot_dock);
  m_plot_refresh = new QTimer(this);
  m_plot_refresh->setSingleShot(true);
  m_plot_refresh->setInterval(kPlotRefreshMs);
  connect(m_plot_refresh, &QTimer::timeout, this, &MainWindow::refreshCurvaturePlot);
  connect(m_plot, &CurvaturePlot::scopeChanged, this, &MainWindow::refreshCurvaturePlot);

  m_lcg = new LcgPlot;
  auto* lcg_dock = new QDockWidget("LCG of the selected segment (click it with V, or right-click)", this);
  lcg_dock->setObjectName("lcg-plot");
  lcg_dock->setWidget(m_lcg);
  addDockWidget(Qt::RightDockWidgetArea, lcg_dock);

  m_parameters = new ParameterPanel;
  auto* param_dock = new QDockWidget("Fit parameters", this);
  param_dock->setObjectName("parameters");
  param_dock->setWidget(m_parameters);
  addDockWidget(Qt::RightDockWidgetArea, param_dock);

  m_construction_panel = new ConstructionPanel;
  auto* construction_dock = new QDockWidget("Construction", this);
  construction_dock->setObjectName("construction");
  construction_dock->setWidget(m_construction_panel);
  addDockWidget(Qt::RightDockWidgetArea, construction_dock);
  tabifyDockWidget(param_dock, construction_dock);
  param_dock->raise();

  m_comb_panel = new CombPanel;
  auto* comb_dock = new QDockWidget("Comb and marks", this);
  comb_dock->setObjectName("comb");
  comb_dock->setWidget(m_comb_panel);
  addDockWidget(Qt::BottomDockWidgetArea, comb_dock);
  splitDockWidget(plot_dock, comb_dock, Qt::Horizontal);
  m_comb_panel->setSettings(m_canvas->layers().comb_scale, m_canvas->layers().comb_teeth, m_canvas->layers().comb_shared);
  connect(m_comb_panel, &CombPanel::settingsChanged, this, &MainWindow::applyCombSettings);

  m_status = new QLabel("draw with the pen or the mouse (B); V selects and moves, H or Space pans, the wheel zooms");
  statusBar()->addWidget(m_status, 1);

  connect(m_canvas, &Canvas::viewChanged, this, [this] {
    if (m_plot->scope() == CurvaturePlot::Scope::kAllVisible) m_plot_refresh->start();
  });
  connect(m_canvas, &Canvas::strokeFinished, this, &MainWindow::strokeDrawn);
  connect(m_canvas, &Canvas::strokeProgress, this, &MainWindow::updatePreview);
  connect(m_canvas, &Canvas::segmentClicked, this, &MainWindow::selectSegment);
  connect(m_canvas, &Canvas::strokesMoved, this, [this](const std::vector<std::size_t>& strokes, const QPointF& d, int drag) {
    moveStrokes(strokes, Vec2(d.x(), d.y()), drag);
  });
  connect(m_canvas, &Canvas::selectionChanged, this, [this] {
    const std::size_t n = selectedStrokes().size();
    if (n > 1) showMessage(QString("%1 strokes selected: drag one to move them all, Delete removes them").arg(n));
  });
  connect(m_parameters, &ParameterPanel::optionsChanged, this, [this](const FitOptions& o) {
    m_undo->push(new SetOptionsCommand(this, m_document.options(), o));
  });
  // Construction handles: a live solve while dragging, one undoable edit on release.
  connect(m_canvas, &Canvas::handlePressed, this, [this](int index) {
    selectConstruction(index);
    m_handle_drag_before = m_document.constructions()[static_cast<std::size_t>(index)];
  });
  connect(m_canvas, &Canvas::handleDragged, this, [this](int index, int handle, const QPointF& w) {
    Construction c = m_document.constructions()[static_cast<std::size_t>(index)];
    c.handles[static_cast<std::size_t>(handle)] = Vec2(w.x(), w.y());
    m_document.replaceConstruction(static_cast<std::size_t>(index), c);
    m_canvas->update();
    selectConstruction(index);
  });
  connect(m_canvas, &Canvas::handleDropped, this, [this](int index, int handle, const QPointF& w) {
    if (!m_handle_drag_before) return;
    Construction after = *m_handle_drag_before;
    after.handles[static_cast<std::size_t>(handle)] = Vec2(w.x(), w.y());
    const Construction before = *m_handle_drag_before;
    m_handle_drag_before.reset();
    editConstruction(index, before, after, "move handle");
  });
  connect(m_construction_panel, &ConstructionPanel::parametersChanged, this,
          [this](const std::map<std::string, double>& parameters) {
            if (m_selected_construction < 0) return;
            const Construction& before = m_document.constructions()[static_cast<std::size_t>(m_selected_construction)];
            Construction after = before;
            after.parameters = parameters;
            editConstruction(m_selected_construction, before, after, "change construction parameters");
          });
  connect(m_construction_panel, &ConstructionPanel::deleteRequested, this, [this] {
    if (m_selected_construction < 0) return;
    const std::size_t i = static_cast<std::size_t>(m_selected_construction);
    m_undo->push(new ConstructionCommand(this, "delete construction", i, m_document.constructions()[i], std::nullopt));
  });

  // Ctrl+drag of a joint or a control-triangle apex: a live preview while dragging, one
  // undoable edit on release.
  auto preview_edit = [this](int stroke, const std::function<std::optional<FitResult>(const FitResult&)>& edit) {
    const auto& s = m_document.strokes()[static_cast<std::size_t>(stroke)];
    if (!s.fit) return;
    m_canvas->setPreview(edit(*s.fit));
    // the plot follows the handle: the edited curve's curvature, live
    if (const auto& live = m_canvas->preview()) {
      plotCurvature(&*live, stroke);
      m_plot->setHighlight(stroke == m_selected_stroke ? m_selected_piece : -1);
    }
  };
  connect(m_canvas, &Canvas::jointDragged, this, [=, this](int stroke, int joint, const QPointF& w) {
    preview_edit(stroke, [&](const FitResult& f) {
      return withJointMoved(f, static_cast<std::size_t>(joint), Vec2(w.x(), w.y()), m_document.options());
    });
  });
  connect(m_canvas, &Canvas::apexDragged, this, [=, this](int stroke, int piece, const QPointF& w) {
    preview_edit(stroke, [&](const FitResult& f) {
      return withApexMoved(f, static_cast<std::size_t>(piece), Vec2(w.x(), w.y()), m_document.options());
    });
  });
  connect(m_canvas, &Canvas::jointDropped, this, [this](int stroke, int joint, const QPointF& w) {
    const Vec2 to(w.x(), w.y());
    m_undo->push(new EditStrokeCommand(this, "move joint", static_cast<std::size_t>(stroke), joint,
                                       [=](Document& d) { return d.moveJoint(static_cast<std::size_t>(stroke), joint, to); }));
  });
  connect(m_canvas, &Canvas::apexDropped, this, [this](int stroke, int piece, const QPointF& w) {
    const Vec2 to(w.x(), w.y());
    m_undo->push(new EditStrokeCommand(this, "move control point", static_cast<std::size_t>(stroke), piece,
                                       [=](Document& d) { return d.moveApex(static_cast<std::size_t>(stroke), piece, to); }));
  });
  connect(m_parameters, &ParameterPanel::segmentAlphaPreviewed, this, [=, this](double a) {
    if (m_selected_stroke < 0 || m_selected_piece < 0) return;
    preview_edit(m_selected_stroke, [&](const FitResult& f) {
      return withSegmentAlpha(f, static_cast<std::size_t>(m_selected_piece), a, m_document.options());
    });
  });
  connect(m_parameters, &ParameterPanel::segmentAlphaChanged, this, [this](double a) {
    m_canvas->setPreview(std::nullopt);
    if (m_selected_stroke >= 0 && m_selected_piece >= 0)
      m_undo->push(new EditStrokeCommand(this, "steer segment alpha", static_cast<std::size_t>(m_selected_stroke),
                                         m_selected_piece, [stroke = m_selected_stroke, piece = m_selected_piece, a](Document& d) {
                                           return d.steerSegment(static_cast<std::size_t>(stroke), piece, a);
                                         }));
  });
  m_autosave = new QTimer(this);
  connect(m_autosave, &QTimer::timeout, this, &MainWindow::autosave);
  m_autosave->start(kAutosaveMs);
  buildToolBar();
  m_export_points = QSettings().value("export/points", false).toBool();
  m_export_comb = QSettings().value("export/comb", false).toBool();
  m_import_placement = placementFromSetting(QSettings().value("import/placement", "ask").toString());
  buildMenus();
  // The document's units, in the status bar: exports state them (DXF $INSUNITS).
  auto* units = new QComboBox;
  units->setObjectName("units");
  units->setToolTip("the units of the sketch's coordinates (saved with it; DXF export states them)");
  for (const char* u : {"px", "mm", "in", "pt", "unitless"}) units->addItem(u);
  statusBar()->addPermanentWidget(units);
  connect(units, &QComboBox::currentTextChanged, this, [this](const QString& u) {
    m_document.setUnits(u == "unitless" ? std::string() : u.toStdString());
    m_dirty = true;
  });
  resize(1100, 760);
}

QString MainWindow::autosavePath() const {
  const QString dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
  QDir().mkpath(dir);
  return dir + "/autosave.lafair.json";
}

void MainWindow::autosave() {
  if (!m_dirty) return;
  try {
    m_document.save(autosavePath());
  } catch (const std::exception&) {
    // the next tick tries again; the document in memory is untouched
  }
}

void MainWindow::addStroke(const Stroke& stroke) { m_undo->push(new AddStrokeCommand(this, stroke)); }

void MainWindow::strokeDrawn(const Stroke& stroke) {
  if (oversketchEnabled()) {
    const double scale = std::sqrt(std::abs(m_canvas->view().determinant()));  // pixels per world unit
    if (scale > 0) {
      if (auto target = findOversketch(m_document, stroke, m_oversketch_reach / scale)) {
        const char* what = target->splice.closes ? "oversketch (closed the stroke)"
                           : target->splice.start && target->splice.end ? "oversketch"
                                                                        : "oversketch (replaced an end)";
        m_undo->push(new ReplaceStrokeCommand(this, what, target->stroke, std::move(target->splice.raw)));
        showMessage(QString("%1 of stroke %2 (Edit > Oversketch turns it off)").arg(what).arg(target->stroke + 1));
        return;
      }
    }
  }
  addStroke(stroke);
}

bool MainWindow::oversketchEnabled() const { return m_oversketch && m_oversketch->isChecked(); }

void MainWindow::setOversketch(bool on) { m_oversketch->setChecked(on); }

void MainWindow::setOversketchReach(double pixels) {
  m_oversketch_reach = pixels;
  QSettings().setValue("oversketch/reach_px", pixels);
  if (m_oversketch_reach_box && m_oversketch_reach_box->value() != static_cast<int>(std::lround(pixels)))
    m_oversketch_reach_box->setValue(static_cast<int>(std::lround(pixels)));
}

void MainWindow::updatePreview() {
  const Stroke& current = m_canvas->currentStroke();
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  if (static_cast<int>(current.samples.size()) < kPreviewMinPoints ||
      now - m_preview_at < std::max<qint64>(kPreviewMinIntervalMs, static_cast<qint64>(kPreviewCostFactor * m_preview_ms)))
    return;
  QElapsedTimer clock;
  clock.start();
  FitOptions quick = m_document.options();
  quick.polish = false;  // the preview keeps up with the pen; the pen-up fit adds stage 7
  try {
    m_canvas->setPreview(fitStroke(current, quick));
    plotCurvature(&*m_canvas->preview(), -1);  // the plot follows the pen
  } catch (const StrokeError&) {
    m_canvas->setPreview(std::nullopt);  // too few points yet
  }
  m_preview_ms = static_cast<double>(clock.nsecsElapsed()) * 1e-6;
  m_preview_at = QDateTime::currentMSecsSinceEpoch();
}

void MainWindow::selectSegment(int stroke, int piece) {
  const auto& strokes = m_document.strokes();
  const FitResult* fit = (stroke >= 0 && stroke < static_cast<int>(strokes.size()) && strokes[stroke].fit) ? &*strokes[stroke].fit : nullptr;
  if (fit) piece = std::min(piece, static_cast<int>(fit->pieces.size()) - 1);  // the end joint selects the last segment
  m_selected_stroke = stroke;
  m_selected_piece = piece;
  m_lcg->setSegment(fit, piece);
  m_canvas->setSelection(stroke, piece);
  if (fit) plotCurvature(fit, stroke);  // the plot follows the selected stroke
  m_plot->setHighlight(fit ? piece : -1);
  const std::string fixed = fit && piece >= 0 ? whyAlphaIsFixed(*fit, static_cast<std::size_t>(piece)) : "select a segment first (click it with V, or right-click it)";
  m_parameters->setSegmentAlpha(fixed.empty(), fixed.empty() ? fit->curve.pieces[piece].segment.alpha() : 0.0,
                                QString::fromStdString(fixed));
  if (fit && piece >= 0) {
    const LaSegment& seg = fit->curve.pieces[piece].segment;
    m_status->setText(QString("segment %1 of stroke %2: alpha %3, length %4, curvature %5 → %6, %7")
                          .arg(piece + 1).arg(stroke + 1).arg(seg.alpha(), 0, 'g', 3).arg(seg.length(), 0, 'g', 4)
                          .arg(seg.kappaStart(), 0, 'g', 3).arg(seg.kappaEnd(), 0, 'g', 3)
                          .arg(toString(fit->pieces[piece].kind)));
  }
}

void MainWindow::plotCurvature(const FitResult* shown, int stroke) {
  if (m_plot->scope() == CurvaturePlot::Scope::kSelectedStroke) {
    m_plot->setFit(shown);
    return;
  }
  const QPointF a = m_canvas->toWorld(QPointF(0, 0)), b = m_canvas->toWorld(QPointF(m_canvas->width(), m_canvas->height()));
  const QRectF view = QRectF(a, b).normalized();
  std::vector<const FitResult*> fits;
  int highlighted = -1;
  const auto& strokes = m_document.strokes();
  for (std::size_t i = 0; i < strokes.size(); ++i) {
    const bool this_one = static_cast<int>(i) == stroke;
    const FitResult* fit = this_one ? shown : (strokes[i].fit ? &*strokes[i].fit : nullptr);
    const std::optional<WorldBox> box = boundsOf({strokes[i].raw});
    // (a straight stroke's box has no area: widened a little so it can meet the view)
    if (!fit || !box || !view.intersects(QRectF(QPointF(box->lo.x(), box->lo.y()), QPointF(box->hi.x(), box->hi.y()))
                                             .adjusted(-1e-9, -1e-9, 1e-9, 1e-9)))
      continue;
    if (this_one) highlighted = static_cast<int>(fits.size());
    fits.push_back(fit);
  }
  if (stroke < 0 && shown) {  // the stroke being drawn
    highlighted = static_cast<int>(fits.size());
    fits.push_back(shown);
  }
  m_plot->setCurves(fits, highlighted);
}

void MainWindow::refreshCurvaturePlot() {
  const auto& strokes = m_document.strokes();
  if (m_selected_stroke >= 0 && m_selected_stroke < static_cast<int>(strokes.size()) && strokes[m_selected_stroke].fit) {
    plotCurvature(&*strokes[m_selected_stroke].fit, m_selected_stroke);
    m_plot->setHighlight(m_selected_piece);
    return;
  }
  if (m_selected_construction >= 0) {
    selectConstruction(m_selected_construction);  // (shows its curve)
    return;
  }
  for (int i = static_cast<int>(strokes.size()) - 1; i >= 0; --i)
    if (strokes[i].fit) return plotCurvature(&*strokes[i].fit, i);
  plotCurvature(nullptr, -1);
}

void MainWindow::addConstruction(ConstructionKind kind) {
  const QPointF a = m_canvas->toWorld(QPointF(0, 0)), b = m_canvas->toWorld(QPointF(m_canvas->width(), m_canvas->height()));
  const Vec2 center(0.5 * (a.x() + b.x()), 0.5 * (a.y() + b.y()));
  const double size = 0.3 * std::min(std::abs(b.x() - a.x()), std::abs(b.y() - a.y()));
  m_undo->push(new ConstructionCommand(this, QString("add ") + displayName(kind), m_document.constructions().size(),
                                       std::nullopt, Construction::create(kind, center, size)));
  if (auto* dock = findChild<QDockWidget*>("construction")) dock->raise();
}

void MainWindow::selectConstruction(int index) {
  if (index >= static_cast<int>(m_document.constructions().size())) index = -1;
  m_selected_construction = index;
  m_canvas->setSelectedConstruction(index);
  m_construction_panel->setConstruction(index >= 0 ? &m_document.constructions()[static_cast<std::size_t>(index)] : nullptr);
  if (index >= 0) {
    const ConstructionResult& r = m_document.constructions()[static_cast<std::size_t>(index)].result;
    m_plot->setCurve(r.s, r.kappa, r.joints);
    m_status->setText(QString("%1: %2").arg(displayName(m_document.constructions()[static_cast<std::size_t>(index)].kind),
                                           QString::fromStdString((r.ok ? "" : "no curve: ") + r.message)));
  }
}

void MainWindow::editConstruction(int index, const Construction& before, const Construction& after, const QString& what) {
  m_undo->push(new ConstructionCommand(this, what, static_cast<std::size_t>(index), before, after));
}

void MainWindow::rememberRecent(const QString& path) {
  QSettings settings;
  QStringList files = settings.value("recent").toStringList();
  files.removeAll(path);
  files.prepend(path);
  while (files.size() > kRecentFiles) files.removeLast();
  settings.setValue("recent", files);
  refreshRecentMenu();
}

void MainWindow::refreshRecentMenu() {
  if (!m_recent) return;
  m_recent->clear();
  for (const QString& f : QSettings().value("recent").toStringList())
    m_recent->addAction(QFileInfo(f).fileName(), this, [this, f] {
      if (keepOrDiscardChanges("opening another sketch")) openFile(f);
    });
  m_recent->setEnabled(!m_recent->isEmpty());
}

bool MainWindow::loadBackground(const QString& path) {
  QImage image(path);
  if (image.isNull()) {
    showError(path + ": not an image Qt can read");
    return false;
  }
  m_canvas->setBackground(image, m_canvas->backgroundOpacity());
  return true;
}

bool MainWindow::offerRecovery() {
  const QString lock = autosavePath() + ".running";
  const bool crashed = QFileInfo::exists(lock) && QFileInfo::exists(autosavePath());
  QFile(lock).open(QIODevice::WriteOnly);  // removed again by a clean exit (destructor)
  if (!crashed || qEnvironmentVariableIsSet("LAFAIR_NO_DIALOGS")) return crashed;
  if (QMessageBox::question(this, "lafair", "The last session did not end cleanly. Recover the autosaved sketch?") ==
      QMessageBox::Yes)
    openFile(autosavePath());
  return true;
}

MainWindow::~MainWindow() {
  for (auto* watcher : m_background) watcher->waitForFinished();  // (their threads hold copies only)
  // (the crash-recovery marker goes only where nothing unsaved is lost: a clean save or
  // the user's own discard; else the next start offers the autosave)
  if (m_undo->isClean() || m_discarded) QFile::remove(autosavePath() + ".running");
}

bool MainWindow::keepOrDiscardChanges(const QString& before) {
  if (m_undo->isClean()) return true;
  QMessageBox::StandardButton answer = m_unsaved_answer;
  if (!qEnvironmentVariableIsSet("LAFAIR_NO_DIALOGS")) {
    const QString what = QString("The sketch has unsaved changes (%1 strokes, %2 constructions, the last: %3). "
                                 "Save them before %4?")
                             .arg(m_document.strokes().size())
                             .arg(m_document.constructions().size())
                             .arg(m_undo->undoText().isEmpty() ? "an edit" : m_undo->undoText())
                             .arg(before);
    answer = QMessageBox::question(this, "lafair", what, QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel,
                                   QMessageBox::Save);
  }
  if (answer == QMessageBox::Discard) return m_discarded = true;
  if (answer != QMessageBox::Save) return false;
  QString path = m_path;
  if (path.isEmpty() && !qEnvironmentVariableIsSet("LAFAIR_NO_DIALOGS"))
    path = QFileDialog::getSaveFileName(this, "Save sketch", {}, "lafair sketches (*.json)");
  return !path.isEmpty() && saveFile(path);
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (keepOrDiscardChanges("quitting")) event->accept();
  else event->ignore();
}

void MainWindow::fitInBackground(std::size_t index) {
  const DocumentStroke& s = m_document.strokes()[index];
  if (!s.provisional) return;
  auto* watcher = new QFutureWatcher<BackgroundFit>(this);
  connect(watcher, &QFutureWatcher<BackgroundFit>::finished, this, [this, watcher] { takeBackgroundFit(watcher); });
  m_background.push_back(watcher);
  auto superseded = std::make_shared<std::atomic<bool>>(false);
  if (auto& newest = m_newest_fit[s.id]) newest->store(true);
  m_newest_fit[s.id] = superseded;
  watcher->setFuture(QtConcurrent::run([raw = s.raw, id = s.id, options = m_document.options(), superseded] {
    BackgroundFit out{id, raw.samples.empty() ? Vec2::Zero() : raw.samples.front().p, options, std::nullopt, {}, superseded};
    // (a fit already running finishes; Document::completeFit drops it if its options are stale)
    if ((out.superseded = superseded->load())) return out;
    try {
      out.fit = fitStroke(raw, options);
    } catch (const std::exception& e) {
      out.error = e.what();
    }
    return out;
  }));
}

void MainWindow::fitProvisionalInBackground() {
  for (std::size_t i = 0; i < m_document.strokes().size(); ++i) fitInBackground(i);
}

void MainWindow::takeBackgroundFit(QFutureWatcher<BackgroundFit>* watcher) {
  const auto it = std::find(m_background.begin(), m_background.end(), watcher);
  if (it == m_background.end()) return;  // taken already (finishBackgroundFits)
  m_background.erase(it);
  BackgroundFit done = watcher->result();
  watcher->deleteLater();
  if (const auto newest = m_newest_fit.find(done.id); newest != m_newest_fit.end() && newest->second == done.superseded_flag)
    m_newest_fit.erase(newest);
  if (done.superseded) {
    ++m_superseded_fits;
    return;
  }
  const int stroke = m_selected_stroke, piece = m_selected_piece;
  if (!m_document.completeFit(done.id, done.options, std::move(done.fit), done.error, done.fitted_at)) return;
  documentChanged();
  // A segment selected on another stroke stays selected (that stroke did not change).
  const auto& strokes = m_document.strokes();
  if (stroke >= 0 && stroke < static_cast<int>(strokes.size()) && strokes[stroke].id != done.id) selectSegment(stroke, piece);
}

void MainWindow::finishBackgroundFits() {
  while (!m_background.empty()) {
    QFutureWatcher<BackgroundFit>* watcher = m_background.front();
    watcher->waitForFinished();
    takeBackgroundFit(watcher);
  }
}

bool MainWindow::exportPng(const QString& path) {
  finishBackgroundFits();  // the curves as they end up, not the provisional ones
  const QPixmap canvas = m_canvas->grab(), plot = m_plot->grab(), lcg = m_lcg->grab();
  QImage out(canvas.width() + std::max(plot.width(), lcg.width()), std::max(canvas.height(), plot.height() + lcg.height()),
             QImage::Format_RGB32);
  out.fill(Qt::white);
  QPainter painter(&out);
  painter.drawPixmap(0, 0, canvas);
  painter.drawPixmap(canvas.width(), 0, plot);
  painter.drawPixmap(canvas.width(), plot.height(), lcg);
  painter.end();
  const QString tmp = path + ".part";  // written whole, then renamed over the target
  if (!out.save(tmp, "PNG") || (QFile::exists(path) && !QFile::remove(path)) || !QFile::rename(tmp, path)) {
    QFile::remove(tmp);
    showError("cannot write " + path);
    return false;
  }
  return true;
}

void MainWindow::documentChanged() {
  m_dirty = true;
  m_canvas->selection().set(m_document, selectedStrokes());  // (forgets strokes no longer there)
  m_canvas->update();
  const FitResult* last = nullptr;
  int last_index = -1;
  for (std::size_t i = 0; i < m_document.strokes().size(); ++i)
    if (m_document.strokes()[i].fit) last = &*m_document.strokes()[i].fit, last_index = static_cast<int>(i);
  plotCurvature(last, last_index);
  selectSegment(-1, -1);
  selectConstruction(m_selected_construction);
  const bool fitting_huge = std::any_of(m_document.strokes().begin(), m_document.strokes().end(),
                                       [](const DocumentStroke& s) { return s.provisional && !s.fit; });
  if (!last || fitting_huge) {
    m_status->setText(fitting_huge                   ? "fitting a long stroke in the background (its points are shown)…"
                      : m_document.strokes().empty() ? "no strokes"
                                                     : "the last stroke could not be fitted");
    return;
  }
  const QualityFigures& q = last->quality;
  const bool refining = std::any_of(m_document.strokes().begin(), m_document.strokes().end(),
                                    [](const DocumentStroke& s) { return s.provisional; });
  // (what the clean-up left out, said where it is more than duplicates and a resampler's
  // points, which lie on the points kept)
  const auto& left_out = last->cleaned.left_out;
  const auto on_kept = std::count_if(left_out.begin(), left_out.end(),
                                     [](const LeftOutPoint& l) { return liesOnKeptPoints(l.why); });
  const QString left = static_cast<std::size_t>(on_kept) == left_out.size()
                           ? QString()
                           : QString(" · %1 samples left out (%2% of the length)")
                                 .arg(left_out.size() - static_cast<std::size_t>(on_kept))
                                 .arg(100.0 * last->cleaned.left_out_fraction, 0, 'f', 0);
  m_status->setText(QString("segments %1 · max deviation %2 (%3% of size) · g2 gap %4 · extrema %5 · fit %6 ms%7%8")
                        .arg(q.segments)
                        .arg(q.max_dev, 0, 'g', 3)
                        .arg(100.0 * q.max_dev / std::max(q.diagonal, 1e-300), 0, 'f', 2)
                        .arg(q.g2_gap, 0, 'g', 2)
                        .arg(q.extrema)
                        .arg(last->timings.total_ms, 0, 'f', 2)
                        .arg(left)
                        .arg(refining ? " · fitting the chain to the points…" : ""));
}

void MainWindow::deleteSelectedStrokes() {
  std::vector<std::size_t> doomed = selectedStrokes();
  if (doomed.empty() && m_selected_stroke >= 0 && m_selected_stroke < static_cast<int>(m_document.strokes().size()))
    doomed.push_back(static_cast<std::size_t>(m_selected_stroke));
  if (doomed.empty()) {
    showMessage("select strokes first (V, then click or drag a box; or right-click one), then Delete removes them");
    return;
  }
  m_undo->push(new DeleteStrokesCommand(this, doomed));
}

std::vector<std::size_t> MainWindow::selectedStrokes() const { return m_canvas->selection().indices(m_document); }

void MainWindow::selectAll() {
  std::vector<std::size_t> all(m_document.strokes().size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  m_canvas->selection().set(m_document, all);
  m_canvas->update();
  showMessage(QString("%1 strokes selected").arg(all.size()));
}

void MainWindow::clearSelection() {
  m_canvas->selection().clear();
  selectSegment(-1, -1);
  m_canvas->update();
}

void MainWindow::moveStrokes(const std::vector<std::size_t>& strokes, const Vec2& d, int drag) {
  if (strokes.empty()) return;
  m_undo->push(new MoveStrokesCommand(this, strokes, d, drag));
}

QAction* MainWindow::toolAction(Tool tool) const {
  for (QAction* a : m_tools->actions())
    if (a->data().toInt() == static_cast<int>(tool)) return a;
  return nullptr;
}

Tool MainWindow::tool() const { return m_canvas->tool(); }

void MainWindow::setTool(Tool tool) { toolAction(tool)->trigger(); }

void MainWindow::applyCombSettings() {
  Layers& layers = m_canvas->layers();
  layers.comb_scale = m_comb_panel->scale();
  layers.comb_teeth = m_comb_panel->teeth();
  layers.comb_shared = m_comb_panel->shared();
  m_canvas->update();
}

void MainWindow::buildToolBar() {
  auto* bar = new QToolBar("Tools", this);
  bar->setObjectName("tools");
  bar->setToolButtonStyle(Qt::ToolButtonTextUnderIcon);
  bar->setMovable(true);
  addToolBar(Qt::LeftToolBarArea, bar);
  m_tools = new QActionGroup(this);
  m_tools->setExclusive(true);
  for (const ToolSpec& spec : kTools) {
    QAction* a = bar->addAction(toolIcon(spec.tool), QString(spec.name).remove('&'));
    a->setObjectName(QString("tool-") + QString(spec.name).remove('&').section(' ', 0, 0).toLower());
    a->setData(static_cast<int>(spec.tool));
    a->setCheckable(true);
    QList<QKeySequence> keys{QKeySequence(spec.shortcut)};
    if (spec.tool == Tool::kDraw) keys << QKeySequence("P");  // Inkscape's pencil key beside Krita's brush key
    a->setShortcuts(keys);
    QStringList names;
    for (const QKeySequence& k : keys) names << k.toString(QKeySequence::NativeText);
    a->setToolTip(QString("%1 (%2): %3").arg(QString(spec.name).remove('&'), names.join(" or "), spec.tip));
    a->setStatusTip(spec.tip);
    m_tools->addAction(a);
    connect(a, &QAction::triggered, this, [this, spec] {
      m_canvas->setTool(spec.tool);
      showMessage(QString("%1: %2").arg(QString(spec.name).remove('&'), spec.tip));
    });
  }
  toolAction(Tool::kDraw)->setChecked(true);
  bar->addSeparator();
  // the constructions are added, not drawn: a button with their menu
  auto* construct = new QToolButton;
  construct->setText("Construct");
  construct->setIcon(toolIcon(std::nullopt));
  construct->setToolButtonStyle(Qt::ToolButtonTextUnderIcon);
  construct->setPopupMode(QToolButton::InstantPopup);
  construct->setToolTip("add a curve built from handles and parameters (drag its handles in Draw or Select)");
  auto* menu = new QMenu(construct);
  for (ConstructionKind kind : {ConstructionKind::kSegment, ConstructionKind::kCompound, ConstructionKind::kHermite,
                                ConstructionKind::kAlp})
    menu->addAction(displayName(kind), this, [this, kind] { addConstruction(kind); });
  construct->setMenu(menu);
  bar->addWidget(construct);
}

void MainWindow::showMessage(const QString& what) { m_status->setText(what); }

void MainWindow::showError(const QString& what) {
  m_status->setText(what);
  if (!qEnvironmentVariableIsSet("LAFAIR_NO_DIALOGS")) QMessageBox::warning(this, "lafair", what);
}

bool MainWindow::openFile(const QString& path) {
  Document loaded;
  try {
    loaded.load(path, /*provisional=*/true);
  } catch (const std::exception& e) {
    showError(QString::fromStdString(e.what()));
    return false;  // the open document is untouched
  }
  m_document = std::move(loaded);
  fitProvisionalInBackground();
  m_canvas->setDocument(&m_document);
  m_parameters->setOptions(m_document.options());
  if (auto* units = findChild<QComboBox*>("units"))
    units->setCurrentText(m_document.units().empty() ? QString("unitless") : QString::fromStdString(m_document.units()));
  m_undo->clear();
  m_path = path;
  documentChanged();
  m_dirty = false;
  m_canvas->fitView();
  if (path != autosavePath()) rememberRecent(path);
  return true;
}

bool MainWindow::saveFile(const QString& path) {
  finishBackgroundFits();  // the curves as they end up, not the provisional ones
  try {
    m_document.save(path);
  } catch (const std::exception& e) {
    showError(QString::fromStdString(e.what()));
    return false;
  }
  m_path = path;
  m_dirty = false;
  m_undo->setClean();
  rememberRecent(path);
  return true;
}

bool MainWindow::importPoints(const QString& path, std::optional<ImportPlacement> placement) {
  if (m_importing) {
    showError("an import is running: wait for it or cancel it first");
    return false;
  }
  const QString name = QFileInfo(path).fileName();
  ImportPlacement how = placement.value_or(m_import_placement);
  if (how == ImportPlacement::kAsk && qEnvironmentVariableIsSet("LAFAIR_NO_DIALOGS")) {
    how = ImportPlacement::kOwnCoordinates;  // as imports always were
  } else if (how == ImportPlacement::kAsk) {
    const QString last = QSettings().value("import/last_placement", "fit-to-view").toString();
    ImportPlacementDialog ask(this, name, QString::fromStdString(m_document.units()), placementFromSetting(last));
    if (ask.exec() != QDialog::Accepted) return false;
    how = ask.choice();
    QSettings().setValue("import/last_placement", settingName(how));
    if (ask.remember()) setImportPlacement(how);
  }
  std::optional<WorldBox> view;
  if (how == ImportPlacement::kFitToView) {
    const QPointF a = m_canvas->toWorld(QPointF(0, 0)), b = m_canvas->toWorld(QPointF(m_canvas->width(), m_canvas->height()));
    view = WorldBox{Vec2(std::min(a.x(), b.x()), std::min(a.y(), b.y())), Vec2(std::max(a.x(), b.x()), std::max(a.y(), b.y()))};
  }
  m_importing = true;
  ReadPointsResult read = readPointsOffThread(this, path, view);
  m_importing = false;
  if (read.status == ReadPointsResult::Status::kCancelled) {
    showMessage("import of " + name + " cancelled: the sketch is unchanged");
    return false;
  }
  if (read.status != ReadPointsResult::Status::kRead) {
    showError(QString::fromStdString(read.error));  // "file:line: what"; the sketch is untouched
    return false;
  }
  const std::size_t count = read.strokes.size();
  m_undo->push(new ImportStrokesCommand(this, "import " + name, std::move(read.strokes)));
  QString where;
  if (read.placed) {
    where = QString("imported at scale %1 (fitted to the view)").arg(read.placed->scale, 0, 'g', 4);
  } else {
    m_canvas->fitView();
    const std::string& units = m_document.units();
    where = QString("imported at their own coordinates (%1)").arg(units.empty() ? QString("unitless") : QString::fromStdString(units));
  }
  statusBar()->showMessage(QString("%1: %2 stroke%3, %4").arg(name).arg(count).arg(count == 1 ? "" : "s").arg(where),
                           kImportMessageMs);
  return true;
}

void MainWindow::setImportPlacement(ImportPlacement placement) {
  m_import_placement = placement;
  QSettings().setValue("import/placement", settingName(placement));
  if (m_placement_actions)
    for (QAction* a : m_placement_actions->actions())
      if (a->data().toInt() == static_cast<int>(placement)) a->setChecked(true);
}

void MainWindow::setExportExtras(bool points, bool comb) {
  m_export_points = points;
  m_export_comb = comb;
  QSettings().setValue("export/points", points);
  QSettings().setValue("export/comb", comb);
}

bool MainWindow::exportFile(const QString& path, bool selected_only) {
  finishBackgroundFits();  // the curves as they end up, not the provisional ones
  // the selection: the Select tool's strokes, else the selected segment's stroke
  std::vector<std::size_t> chosen = selectedStrokes();
  if (chosen.empty() && m_selected_stroke >= 0) chosen.push_back(static_cast<std::size_t>(m_selected_stroke));
  const bool only_construction = selected_only && chosen.empty() && m_selected_construction >= 0;
  if (selected_only && chosen.empty() && !only_construction) {
    showError("select a curve first (click it with V or right-click it, or click a construction's handle)");
    return false;
  }
  std::vector<Curve> curves;
  std::vector<std::vector<Vec2>> points;
  std::vector<CurveOrError> entries;
  std::vector<AlpCurve> alps;
  double fit_tolerance = INFINITY;  // the smallest of the exported strokes' fits (absolute)
  nlohmann::json alp_entries = nlohmann::json::array();
  for (std::size_t k = 0; k < m_document.strokes().size() && !only_construction; ++k) {
    if (selected_only && std::find(chosen.begin(), chosen.end(), k) == chosen.end()) continue;
    const DocumentStroke& s = m_document.strokes()[k];
    if (!s.fit) {
      entries.push_back({std::nullopt, s.error});
      continue;
    }
    curves.push_back(s.fit->curve);
    points.push_back(s.fit->cleaned.points);
    fit_tolerance = std::min(fit_tolerance, s.fit->tolerance);
    entries.push_back({s.fit->curve, {}});
  }
  for (std::size_t k = 0; k < m_document.constructions().size(); ++k) {
    if (selected_only && !(only_construction && static_cast<int>(k) == m_selected_construction)) continue;
    const Construction& c = m_document.constructions()[k];
    if (c.result.alp) {  // not an LA curve: drawn by the same writers, kept apart in JSON
      alps.push_back(*c.result.alp);
      alp_entries.push_back(c.result.json);
      points.push_back(c.handles);
      continue;
    }
    if (!c.result.curve) {
      entries.push_back({std::nullopt, c.result.message});
      continue;
    }
    curves.push_back(*c.result.curve);
    points.push_back(c.handles);
    entries.push_back({*c.result.curve, {}});
  }
  // LA curves first, then ALP curves, as chains for the general writers.
  std::vector<LaSegmentView> views;
  std::vector<ExportCurve> chains = exportChains(curves, views);
  for (ExportCurve& chain : exportChains(alps)) chains.push_back(std::move(chain));
  const QString ext = QFileInfo(path).suffix().toLower();
  try {
    if (ext == "svg") {
      SvgOptions o;
      o.show_points = m_export_points;
      o.show_comb = m_export_comb;
      // a tenth of the fit tolerance: the Bezier path is as close to the LA curve as the
      // curve is to the points, ten times over (constructions alone: the writer's default)
      if (std::isfinite(fit_tolerance) && fit_tolerance > 0) o.bezier_tolerance_absolute = kExportToleranceOfFit * fit_tolerance;
      writeFileAtomically(path.toStdString(), exportCurvesToSvg(chains, points, o));
    } else if (ext == "dxf") {
      DxfOptions o;
      if (std::isfinite(fit_tolerance) && fit_tolerance > 0) o.absolute_tolerance = kExportToleranceOfFit * fit_tolerance;
      const std::string& units = m_document.units();
      o.units = units == "mm" ? DxfUnits::kMillimeters : units == "in" ? DxfUnits::kInches : DxfUnits::kUnitless;
      if (units == "px" || units == "pt")
        o.units_comment = "lafair: drawing units are " + units + " (DXF has no such unit: $INSUNITS 0, unitless)";
      writeFileAtomically(path.toStdString(), exportCurvesToDxf(chains, m_export_points ? points : std::vector<std::vector<Vec2>>{}, o));
    } else if (ext == "csv") {
      writeFileAtomically(path.toStdString(), exportCurvesToCsv(chains));
    } else if (ext == "json" && alps.empty()) {
      writeCurvesFile(path.toStdString(), entries);
    } else if (ext == "json") {
      // The shared format holds LA curves only; ALP curves follow under their own key.
      nlohmann::json doc = nlohmann::json::parse(curvesDocumentToString(entries));
      doc["alp_curves"] = alp_entries;
      writeFileAtomically(path.toStdString(), doc.dump(2) + "\n");
    } else {
      showError("unknown export format '." + ext + "' (svg, dxf, json or csv)");
      return false;
    }
  } catch (const std::exception& e) {
    showError(QString::fromStdString(e.what()));
    return false;
  }
  return true;
}

void MainWindow::buildMenus() {
  QMenu* file = menuBar()->addMenu("&File");
  file->addAction("&New", QKeySequence::New, this, [this] {
    if (!keepOrDiscardChanges("starting a new sketch")) return;
    m_document.clear();
    m_undo->clear();
    m_path.clear();
    documentChanged();
  });
  file->addAction("&Open…", QKeySequence::Open, this, [this] {
    if (!keepOrDiscardChanges("opening another sketch")) return;
    const QString p = QFileDialog::getOpenFileName(this, "Open sketch", {}, "lafair sketches (*.json)");
    if (!p.isEmpty()) openFile(p);
  });
  file->addAction("&Save", QKeySequence::Save, this, [this] {
    QString p = m_path;
    if (p.isEmpty()) p = QFileDialog::getSaveFileName(this, "Save sketch", {}, "lafair sketches (*.json)");
    if (!p.isEmpty()) saveFile(p);
  });
  file->addAction("Save &As…", QKeySequence::SaveAs, this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, "Save sketch", {}, "lafair sketches (*.json)");
    if (!p.isEmpty()) saveFile(p);
  });
  m_recent = file->addMenu("Open &recent");
  refreshRecentMenu();
  file->addAction("Recover &autosave", this, [this] {
    if (!QFileInfo::exists(autosavePath())) showError("no autosaved sketch");
    else if (keepOrDiscardChanges("opening the autosaved sketch")) openFile(autosavePath());
  });
  file->addSeparator();
  file->addAction("Import &background image…", this, [this] {
    const QString p = QFileDialog::getOpenFileName(this, "Background image", {}, "Images (*.png *.jpg *.jpeg *.bmp *.gif)");
    if (!p.isEmpty()) loadBackground(p);
  });
  file->addAction("&Import points…", this, [this] {
    const QString p = QFileDialog::getOpenFileName(this, "Import points", {}, "Points (*.csv *.txt *.dat *.json *.svg)");
    if (!p.isEmpty()) importPoints(p);
  });
  // Where imported points go (import_placement.h): asked, or the remembered answer.
  QMenu* placement = file->addMenu("Import p&lacement");
  placement->setObjectName("import-placement-menu");
  m_placement_actions = new QActionGroup(this);
  m_placement_actions->setExclusive(true);
  for (const auto& [what, text] : {std::pair{ImportPlacement::kAsk, "&Ask on each import"},
                                   std::pair{ImportPlacement::kFitToView, "&Fit to the view"},
                                   std::pair{ImportPlacement::kOwnCoordinates, "At their &own coordinates"}}) {
    QAction* a = placement->addAction(text);
    a->setObjectName(QString("import-") + settingName(what));
    a->setCheckable(true);
    a->setData(static_cast<int>(what));
    a->setChecked(what == m_import_placement);
    m_placement_actions->addAction(a);
    connect(a, &QAction::triggered, this, [this, choice = what] { setImportPlacement(choice); });
  }
  file->addAction("&Export curves…", this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, "Export curves", {}, "SVG (*.svg);;DXF (*.dxf);;JSON (*.json);;CSV samples (*.csv)");
    if (!p.isEmpty()) exportFile(p);
  });
  file->addAction("Export &selected curve…", this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, "Export selected curve", {}, "SVG (*.svg);;DXF (*.dxf);;JSON (*.json);;CSV samples (*.csv)");
    if (!p.isEmpty()) exportFile(p, true);
  });
  QMenu* extras = file->addMenu("Export &with");
  QAction* with_points = extras->addAction("the &points (SVG and DXF)");
  with_points->setCheckable(true);
  with_points->setChecked(m_export_points);
  connect(with_points, &QAction::toggled, this, [this](bool on) { setExportExtras(on, m_export_comb); });
  QAction* with_comb = extras->addAction("the curvature &comb (SVG)");
  with_comb->setCheckable(true);
  with_comb->setChecked(m_export_comb);
  connect(with_comb, &QAction::toggled, this, [this](bool on) { setExportExtras(m_export_points, on); });
  file->addAction("Export &picture (PNG)…", this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, "Export picture", {}, "PNG (*.png)");
    if (!p.isEmpty()) exportPng(p);
  });
  file->addSeparator();
  file->addAction("&Quit", QKeySequence::Quit, this, &QWidget::close);

  QMenu* edit = menuBar()->addMenu("&Edit");
  QAction* undo = m_undo->createUndoAction(this, "&Undo");
  undo->setShortcut(QKeySequence::Undo);
  QAction* redo = m_undo->createRedoAction(this, "&Redo");
  // (the platform's Redo keys, and Ctrl+Shift+Z and Ctrl+Y where they are not among them)
  QList<QKeySequence> redo_keys = QKeySequence::keyBindings(QKeySequence::Redo);
  for (const QKeySequence& key : {QKeySequence("Ctrl+Shift+Z"), QKeySequence("Ctrl+Y")})
    if (!redo_keys.contains(key)) redo_keys.append(key);
  redo->setShortcuts(redo_keys);
  edit->addAction(undo);
  edit->addAction(redo);
  edit->addSeparator();
  edit->addAction("&Delete", QKeySequence::Delete, this, [this] { deleteSelectedStrokes(); });
  edit->addAction("Select &all", QKeySequence::SelectAll, this, [this] { selectAll(); });
  QAction* none = edit->addAction("&Clear selection", this, [this] { clearSelection(); });
  none->setShortcuts({QKeySequence(Qt::Key_Escape), QKeySequence("Ctrl+Shift+A")});
  edit->addSeparator();
  // Oversketch: on by default, as in Inkscape's pencil; the reach is a spin box in the menu.
  m_oversketch = edit->addAction("&Oversketch");
  m_oversketch->setObjectName("oversketch");
  m_oversketch->setCheckable(true);
  m_oversketch->setToolTip("a stroke drawn from or to an existing curve replaces that part of it");
  m_oversketch->setChecked(QSettings().value("oversketch/enabled", true).toBool());
  connect(m_oversketch, &QAction::toggled, this, [](bool on) { QSettings().setValue("oversketch/enabled", on); });
  m_oversketch_reach = QSettings().value("oversketch/reach_px", kDefaultOversketchReachPixels).toDouble();
  auto* reach_row = new QWidget;
  auto* reach_layout = new QHBoxLayout(reach_row);
  reach_layout->setContentsMargins(24, 2, 8, 2);
  reach_layout->addWidget(new QLabel("Oversketch reach (px)"));
  m_oversketch_reach_box = new QSpinBox;
  m_oversketch_reach_box->setObjectName("oversketch-reach");
  m_oversketch_reach_box->setRange(1, 50);
  m_oversketch_reach_box->setValue(static_cast<int>(std::lround(m_oversketch_reach)));
  reach_layout->addWidget(m_oversketch_reach_box);
  connect(m_oversketch_reach_box, &QSpinBox::valueChanged, this, [this](int v) { setOversketchReach(v); });
  auto* reach_action = new QWidgetAction(this);
  reach_action->setDefaultWidget(reach_row);
  edit->addAction(reach_action);
  edit->addSeparator();
  QMenu* tools = edit->addMenu("&Tool");
  tools->addActions(m_tools->actions());

  QMenu* construct = menuBar()->addMenu("&Construct");
  for (ConstructionKind kind : {ConstructionKind::kSegment, ConstructionKind::kCompound, ConstructionKind::kHermite,
                                ConstructionKind::kAlp})
    construct->addAction(displayName(kind), this, [this, kind] { addConstruction(kind); });

  QMenu* view = menuBar()->addMenu("&View");
  auto toggle = [&](const char* name, bool Layers::*flag) {
    QAction* a = view->addAction(name);
    a->setCheckable(true);
    a->setChecked(m_canvas->layers().*flag);
    connect(a, &QAction::toggled, this, [this, flag](bool on) {
      m_canvas->layers().*flag = on;
      m_canvas->update();
    });
  };
  toggle("Raw points", &Layers::raw_points);
  toggle("Ink from pen &pressure", &Layers::pressure_ink);
  toggle("Smoothed B-spline", &Layers::spline);
  toggle("LA curve", &Layers::curve);
  toggle("Curvature comb", &Layers::comb);
  toggle("Joints, inflections, corners", &Layers::markers);
  toggle("Control triangles", &Layers::triangles);
  QAction* y_up = view->addAction("Y axis &up");
  y_up->setCheckable(true);
  connect(y_up, &QAction::toggled, this, [this](bool on) {
    m_canvas->layers().y_up = on;
    m_canvas->fitView();
  });
  if (auto* dock = findChild<QDockWidget*>("comb")) view->addAction(dock->toggleViewAction());  // scale, teeth, legend
  view->addAction("Background &opacity…", this, [this] {
    bool ok = false;
    const double v = QInputDialog::getDouble(this, "Background", "Opacity", m_canvas->backgroundOpacity(), 0.0, 1.0, 2, &ok);
    if (ok) m_canvas->setBackgroundOpacity(v);
  });
  view->addSeparator();
  view->addAction("&Fit view", QKeySequence(Qt::Key_F), m_canvas, &Canvas::fitView);
}

}  // namespace la::gui
