#pragma once
// The app's sketch file, read and written without Qt (the GUI's Document holds the
// fits and builds the constructions; this is only the file):
//   {"format": "lafair-sketch", "version": 1, "options": {...} (app/io/fit_options_json.h),
//    "units": "px",
//    "strokes": [{"points": [[x, y], ...], "t": [...], "pressure": [...],
//                 "tilt": [[tx, ty], ...], "profile": true,
//                 "alpha_overrides": {"<segment>": alpha},
//                 "joint_overrides": {"<joint>": [x, y]},
//                 "apex_overrides": {"<segment>": [x, y]}}, ...],
//    "curves": [...] (the fits, for other tools; not read back: fits are recomputed),
//    "constructions": [{"kind", "handles", "parameters", "curve"}, ...]}.
// t, pressure and tilt are optional, one entry per point, null (or [null, null]) for
// unknown; a shorter list leaves the rest unknown (files of older versions). Override
// keys are segment or joint indices written in decimal.
//
// Reading is strict: every value of the wrong type or out of range throws
// SketchFileError "<file>: <where>: <what>", e.g.
// "a.lafair: strokes[2].alpha_overrides[\"x\"]: key is not a segment index".

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitting/pipeline.h"
#include "fitting/stroke.h"

namespace la {

struct SketchFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A stroke as the user drew it, with the edits the app reapplies after each fit.
struct SketchStroke {
  Stroke raw;
  std::map<int, double> alpha_overrides;  // segment -> alpha
  std::map<int, Vec2> joint_overrides;    // joint (segment i's start; n the end) -> position
  std::map<int, Vec2> apex_overrides;     // segment -> control-triangle apex
};

struct Sketch {
  FitOptions options;
  std::string units = "px";
  std::vector<SketchStroke> strokes;
  /// The constructions' JSON objects, as saved (app/gui/construction.h builds them);
  /// the reader checks only that each is an object.
  nlohmann::json constructions = nlohmann::json::array();
  /// The fitted curves, one entry per stroke (fit JSON or {"error": why}): written for
  /// other tools, ignored when reading.
  nlohmann::json curves = nlohmann::json::array();
};

/// Arrays and objects nested deeper than this are refused before parsing (copying and
/// printing nlohmann values recurse); a sketch nests at most 6 levels.
inline constexpr std::size_t kMaxSketchNesting = 256;

/// Parses sketch text; `name` (the file) starts every message. Throws SketchFileError.
Sketch parseSketch(const std::string& text, const std::string& name);

/// The document as text (JSON indented by 1, ending in a newline). Non-finite sample
/// values are written as null (unknown).
std::string sketchToString(const Sketch& sketch);

}  // namespace la
