#pragma once
// Curves a designer builds from end conditions instead of drawing them (DESIGN.md
// section 4): draggable handles plus a few numbers, solved by the core constructions.
// This is the model behind the app's construction tools; no widgets here.
//
// Handles per kind (all in world units):
//  - kSegment:   Q0, Q1, Q2 of one LA segment's control triangle (Yoshida & Saito);
//  - kCompound:  Q0..Q3 like a cubic Bezier, two LA pieces joined G3 (seed 001);
//  - kHermite:   P0, a point on the start tangent, a point on the end tangent, P1;
//                three LA pieces, G2, end curvatures from the parameters (seed 002);
//  - kAlp:       as kHermite, for a curve with an explicit Bezier curvature function
//                (seeds 000, 004), G1 or G2.
// End curvatures are given relative to the chord (kappa * |P1 - P0|), so a curve keeps
// its shape when the handles are scaled together.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/alp_curve.h"
#include "core/curve.h"
#include "nlohmann/json.hpp"

namespace la::gui {

enum class ConstructionKind { kSegment, kCompound, kHermite, kAlp };

const char* toString(ConstructionKind kind);            // "segment", "compound", "hermite", "alp"
std::optional<ConstructionKind> constructionKindFromString(const std::string& name);
const char* displayName(ConstructionKind kind);         // for menus and the panel

/// A number the user sets with a slider (or a check box for a toggle, 0 or 1).
/// `optional` ones may be unset (NaN): "auto".
struct ParameterSpec {
  enum class Type { kNumber, kToggle };
  std::string key, label, tooltip;
  double min, max, initial;
  int decimals = 2;  // 0 for whole numbers
  bool optional = false;
  Type type = Type::kNumber;
};
const std::vector<ParameterSpec>& parameterSpecs(ConstructionKind kind);

struct ConstructionResult {
  bool ok = false;
  std::string message;            // the solver's status, or why there is no curve
  std::optional<Curve> curve;     // the LA kinds: the curve in the shared format
  std::optional<AlpCurve> alp;    // kAlp: the curve with its explicit curvature function
  std::vector<Vec2> points;       // dense points along the curve, for drawing
  std::vector<Vec2> normals;      // unit left normals at those points
  std::vector<double> kappa;      // signed curvature there (comb, plots)
  std::vector<double> s;          // arc length there
  std::vector<double> joints;     // arc length of each piece's start
  nlohmann::json json;            // the export entry: shared format + "solve"
};

struct Construction {
  ConstructionKind kind = ConstructionKind::kSegment;
  std::vector<Vec2> handles;
  std::map<std::string, double> parameters;  // by ParameterSpec::key; NaN = auto
  ConstructionResult result;                 // of the handles and parameters above

  /// A new construction of that kind with its default parameters, its handles laid out
  /// in the box centred on `center` with half-width `size`.
  static Construction create(ConstructionKind kind, const Vec2& center, double size);
  double parameter(const std::string& key) const;  // the value, or the spec's initial one
  /// Recomputes `result` from the handles and parameters.
  void solve();

  nlohmann::json toJson() const;  // kind, handles, parameters and the result's entry
  /// Throws std::runtime_error naming `where` and what is wrong.
  static Construction fromJson(const nlohmann::json& json, const std::string& where);
};

}  // namespace la::gui
