#include "app/gui/document.h"

#include <atomic>
#include <cmath>
#include <stdexcept>

#include "app/gui/translate.h"
#include "app/io/fit_json.h"
#include "app/io/fit_options_json.h"
#include "app/io/sketch_file.h"
#include "core/atomic_file.h"
#include "fitting/user_edits.h"
#include "nlohmann/json.hpp"

namespace la::gui {
namespace {

// Stroke ids are unique across documents: a background fit of a sketch that was
// replaced (opened over) must not find a stroke of the new one.
std::uint64_t nextStrokeId() {
  static std::atomic<std::uint64_t> next{1};
  return next++;
}

std::atomic<std::uint64_t> next_revision{1};

}  // namespace

void DocumentStroke::touch() { revision = next_revision++; }

void Document::fit(DocumentStroke& s) const {
  try {
    s.fit = fitStroke(s.raw, options_);
    s.error.clear();
  } catch (const StrokeError& e) {  // a dot or a straight tap: kept, shown unfitted
    s.fit.reset();
    s.error = e.what();
    return;
  }
  const int pieces = static_cast<int>(s.fit->curve.pieces.size());
  for (const auto& [piece, alpha] : s.alpha_overrides) {
    if (piece < 0 || piece >= pieces) continue;  // the segmentation changed under it
    if (auto steered = withSegmentAlpha(*s.fit, static_cast<std::size_t>(piece), alpha, options_)) s.fit = std::move(steered);
  }
  for (const auto& [joint, position] : s.joint_overrides) {
    if (joint < 0 || joint > pieces) continue;
    if (auto moved = withJointMoved(*s.fit, static_cast<std::size_t>(joint), position, options_)) s.fit = std::move(moved);
  }
  for (const auto& [piece, apex] : s.apex_overrides) {
    if (piece < 0 || piece >= pieces) continue;
    if (auto moved = withApexMoved(*s.fit, static_cast<std::size_t>(piece), apex, options_)) s.fit = std::move(moved);
  }
}

template <class Edit, class Remember>
std::string Document::editStroke(std::size_t stroke, Edit&& edit, Remember&& remember) {
  if (stroke >= strokes_.size() || !strokes_[stroke].fit) return "no fitted stroke there";
  DocumentStroke& s = strokes_[stroke];
  std::string why;
  std::optional<FitResult> edited = edit(*s.fit, &why);
  if (!edited) return why;
  s.fit = std::move(edited);
  s.touch();
  s.provisional = false;  // the user works on this fit now: a background one would undo it
  remember(s);
  return {};
}

std::string Document::steerSegment(std::size_t stroke, int piece, double alpha) {
  return editStroke(
      stroke,
      [&](const FitResult& f, std::string* why) { return withSegmentAlpha(f, static_cast<std::size_t>(piece), alpha, options_, why); },
      [&](DocumentStroke& s) { s.alpha_overrides[piece] = alpha; });
}

std::string Document::moveJoint(std::size_t stroke, int joint, const Vec2& position) {
  return editStroke(
      stroke,
      [&](const FitResult& f, std::string* why) { return withJointMoved(f, static_cast<std::size_t>(joint), position, options_, why); },
      [&](DocumentStroke& s) { s.joint_overrides[joint] = position; });
}

std::string Document::moveApex(std::size_t stroke, int piece, const Vec2& apex) {
  return editStroke(
      stroke,
      [&](const FitResult& f, std::string* why) { return withApexMoved(f, static_cast<std::size_t>(piece), apex, options_, why); },
      [&](DocumentStroke& s) { s.apex_overrides[piece] = apex; });
}

void Document::restoreStroke(std::size_t index, DocumentStroke stroke, bool insert) {
  if (insert) strokes_.insert(strokes_.begin() + static_cast<long>(std::min(index, strokes_.size())), std::move(stroke));
  else if (index < strokes_.size()) strokes_[index] = std::move(stroke);
}

std::size_t Document::addStroke(const Stroke& raw) {
  insertStroke(strokes_.size(), raw);
  return strokes_.size() - 1;
}

void Document::refit(DocumentStroke& s, bool provisional) const {
  s.touch();
  const bool edited = !s.alpha_overrides.empty() || !s.joint_overrides.empty() || !s.apex_overrides.empty();
  s.provisional = provisional && !edited && options_.polishes();
  if (!s.provisional) {
    fit(s);
    return;
  }
  FitOptions quick = options_;
  quick.polish = false;
  try {
    s.fit = fitStroke(s.raw, quick);
    s.error.clear();
  } catch (const StrokeError& e) {  // nothing to complete: the full fit refuses it too
    s.fit.reset();
    s.error = e.what();
    s.provisional = false;
  }
}

void Document::insertStroke(std::size_t index, const Stroke& raw, bool provisional, bool unfitted) {
  DocumentStroke s{raw, std::nullopt, {}, {}, {}, {}};
  s.id = nextStrokeId();
  if (unfitted) {
    s.touch();
    s.provisional = true;
    s.error = "fitting in the background";
  } else {
    refit(s, provisional);
  }
  strokes_.insert(strokes_.begin() + static_cast<long>(std::min(index, strokes_.size())), std::move(s));
}

bool Document::completeFit(std::uint64_t id, const FitOptions& options, std::optional<FitResult> fit,
                           const std::string& error, const Vec2& fitted_at) {
  // (options are compared through their JSON form, which holds every one the app sets)
  if (fitOptionsToJson(options) != fitOptionsToJson(options_)) return false;
  for (DocumentStroke& s : strokes_) {
    if (s.id != id) continue;
    if (!s.provisional) return false;
    const Vec2 moved = s.raw.samples.empty() ? Vec2::Zero() : Vec2(s.raw.samples.front().p - fitted_at);
    if (fit && moved != Vec2::Zero()) fit = translated(*fit, moved);
    s.fit = std::move(fit);
    s.touch();
    s.error = s.fit ? std::string() : error;
    s.provisional = false;
    return true;
  }
  return false;
}

void Document::translateStrokes(const std::vector<std::size_t>& indices, const Vec2& d) {
  for (std::size_t i : indices)
    if (i < strokes_.size()) translateStroke(strokes_[i], d);
}

void Document::removeStroke(std::size_t index) {
  if (index < strokes_.size()) strokes_.erase(strokes_.begin() + static_cast<long>(index));
}

void Document::setOptions(const FitOptions& options, bool provisional) {
  options_ = options;
  for (DocumentStroke& s : strokes_) refit(s, provisional);
}

void Document::clear() {
  units_ = "px";
  strokes_.clear();
  constructions_.clear();
}

void Document::insertConstruction(std::size_t index, Construction construction) {
  construction.solve();
  constructions_.insert(constructions_.begin() + static_cast<long>(std::min(index, constructions_.size())),
                        std::move(construction));
}

void Document::replaceConstruction(std::size_t index, Construction construction) {
  if (index >= constructions_.size()) return;
  construction.solve();
  constructions_[index] = std::move(construction);
}

void Document::removeConstruction(std::size_t index) {
  if (index < constructions_.size()) constructions_.erase(constructions_.begin() + static_cast<long>(index));
}

void Document::save(const QString& path) const {
  Sketch sketch;
  sketch.options = options_;
  sketch.units = units_;
  for (const DocumentStroke& s : strokes_) {
    sketch.strokes.push_back({s.raw, s.alpha_overrides, s.joint_overrides, s.apex_overrides});
    sketch.curves.push_back(s.fit ? fitResultToJson(*s.fit, s.raw, false) : nlohmann::json{{"error", s.error}});
  }
  for (const Construction& c : constructions_) sketch.constructions.push_back(c.toJson());
  writeFileAtomically(path.toStdString(), sketchToString(sketch));
}

void Document::load(const QString& path, bool provisional) {
  const std::string name = path.toStdString();
  Sketch sketch = parseSketch(readFile(name), name);
  std::vector<Construction> constructions;
  for (std::size_t i = 0; i < sketch.constructions.size(); ++i)
    constructions.push_back(Construction::fromJson(sketch.constructions[i], name + ": constructions[" + std::to_string(i) + "]"));
  std::vector<DocumentStroke> loaded;
  loaded.reserve(sketch.strokes.size());
  for (SketchStroke& s : sketch.strokes)
    loaded.push_back({std::move(s.raw), std::nullopt, {}, std::move(s.alpha_overrides), std::move(s.joint_overrides),
                      std::move(s.apex_overrides)});
  options_ = sketch.options;
  units_ = std::move(sketch.units);
  strokes_ = std::move(loaded);
  constructions_ = std::move(constructions);
  for (DocumentStroke& s : strokes_) {
    s.id = nextStrokeId();
    refit(s, provisional);
  }
}

}  // namespace la::gui
