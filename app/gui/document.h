#pragma once
// The sketch document: the strokes the user drew (kept raw, never modified), the fit
// options, and the fitted result of each stroke (recomputed from the raw strokes, so a
// document file only needs strokes and options). No Qt widgets here.

#include <QString>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/construction.h"
#include "fitting/pipeline.h"

namespace la::gui {

struct DocumentStroke {
  Stroke raw;
  std::optional<FitResult> fit;  // empty if the stroke could not be fitted
  std::string error;             // why, then
  std::map<int, double> alpha_overrides;  // the user's alpha per segment, reapplied after each fit
  std::map<int, Vec2> joint_overrides;    // the user's position of joint i (segment i's start; n the end), likewise
  std::map<int, Vec2> apex_overrides;     // the user's control-triangle apex of a segment, likewise
  /// Drawn strokes are fitted at once without stage 7 (provisional), then again with it
  /// in the background (completeFit); `id` finds the stroke when that fit comes back.
  std::uint64_t id = 0;
  bool provisional = false;
  /// Changes with every change of the raw samples or the fit, unique across documents
  /// (undo's restoreStroke brings a stroke back with the revision it had, as it was): the
  /// canvas caches what it draws of a stroke by it (app/gui/stroke_drawing.h).
  std::uint64_t revision = 0;
  void touch();  // a new revision
};

class Document {
 public:
  const std::vector<DocumentStroke>& strokes() const { return strokes_; }
  /// Curves built from handles and parameters (the Construct menu), after the strokes.
  const std::vector<Construction>& constructions() const { return constructions_; }
  /// Inserts (index <= count) or replaces (index < count) a construction, solving it.
  void insertConstruction(std::size_t index, Construction construction);
  void replaceConstruction(std::size_t index, Construction construction);
  void removeConstruction(std::size_t index);
  const FitOptions& options() const { return options_; }
  /// The units of the world coordinates: "px", "mm", "in", "pt" or "" (unitless); saved
  /// in the sketch file, "px" by default; exports state them (DXF $INSUNITS).
  const std::string& units() const { return units_; }
  void setUnits(const std::string& units) { units_ = units; }

  /// Adds a stroke and fits it; returns its index.
  std::size_t addStroke(const Stroke& raw);
  void removeStroke(std::size_t index);
  /// Inserts and fits a stroke. `provisional`: where the options ask for stage 7, fits
  /// without it (milliseconds: a pen-up must not wait) and marks the stroke provisional.
  /// `unfitted`: no fit at all yet, provisional (a huge stroke: the whole fit is made in
  /// the background and taken by completeFit; meanwhile its points are shown).
  void insertStroke(std::size_t index, const Stroke& raw, bool provisional = false, bool unfitted = false);
  /// Strokes of more samples than this are inserted unfitted by the window: their
  /// provisional fit alone would hold the UI past a frame (16 ms). From
  /// gui_paint_benchmark's BM_PenUpProvisionalFit: 8000 samples 6 ms, ~linear.
  static constexpr std::size_t kOffThreadFitSamples = 16000;
  /// The full fit of provisional stroke `id` (fitStroke with `options`, or the
  /// StrokeError's message), made in the background: taken if that stroke is still
  /// there, still provisional (not edited since) and the options are the same. Returns
  /// whether it was taken. `fitted_at` is the first raw sample of the stroke as it was
  /// fitted: where the stroke has moved since (translateStrokes), the fit moves with it.
  bool completeFit(std::uint64_t id, const FitOptions& options, std::optional<FitResult> fit, const std::string& error,
                   const Vec2& fitted_at);
  /// Moves strokes by `d` without refitting (app/gui/translate.h).
  void translateStrokes(const std::vector<std::size_t>& indices, const Vec2& d);
  /// Refits every stroke; `provisional` as insertStroke (strokes the user edited are
  /// always fitted in full: their edits are applied to the full fit).
  void setOptions(const FitOptions& options, bool provisional = false);
  /// Gives a segment the user's alpha (kept across refits while the segmentation has
  /// the same number of pieces). Returns "" or why it cannot.
  std::string steerSegment(std::size_t stroke, int piece, double alpha);
  /// Moves joint `joint` (segment joint's start; n the open curve's end; kept across
  /// refits like the alphas).
  std::string moveJoint(std::size_t stroke, int joint, const Vec2& position);
  /// Moves the apex of a segment's control triangle (its end tangents follow).
  std::string moveApex(std::size_t stroke, int piece, const Vec2& apex);
  /// Puts a stroke back exactly as it was (for undo; no refit): in place of stroke
  /// `index`, or inserted there with `insert` (undoing its removal).
  void restoreStroke(std::size_t index, DocumentStroke stroke, bool insert = false);
  void clear();

  /// The sketch file (app/io/sketch_file.h), written atomically. Reading throws
  /// std::runtime_error naming the file and the problem (SketchFileError for the file's
  /// contents, Construction::fromJson's errors for a construction it cannot build).
  void save(const QString& path) const;
  void load(const QString& path, bool provisional = false);  // fits as setOptions

  /// The library's defaults with a time budget (FitOptions::time_budget_ms): the pen-up
  /// fit of a hard stroke arrives within a quarter second, the best G2 chain by then.
  static FitOptions appOptions() {
    FitOptions o;
    o.time_budget_ms = 250.0;
    return o;
  }

 private:
  void fit(DocumentStroke& s) const;
  void refit(DocumentStroke& s, bool provisional) const;  // fit(), or stages 1-6 only (provisional)
  // Runs one user edit of a fitted stroke: `edit` returns the edited fit or nothing
  // (with why); on success `remember` records the edit as an override.
  template <class Edit, class Remember>
  std::string editStroke(std::size_t stroke, Edit&& edit, Remember&& remember);
  std::vector<DocumentStroke> strokes_;
  std::vector<Construction> constructions_;
  FitOptions options_ = appOptions();
  std::string units_ = "px";
};

}  // namespace la::gui
