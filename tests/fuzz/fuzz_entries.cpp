#include "tests/fuzz/fuzz_entries.h"

#include <cmath>
#include <string>
#include <vector>

#include "app/io/point_file.h"
#include "app/io/sketch_file.h"
#include "core/curve_json.h"
#include "fitting/pipeline.h"

namespace la::fuzz {
namespace {

// The fit target's bounds: fuzzing wants many fast runs, and a stroke of a few hundred
// samples already reaches every stage (the shared data's strokes have 30-600).
constexpr std::size_t kMaxFitStrokes = 3;
constexpr std::size_t kMaxFitSamples = 300;
constexpr double kFitBudgetMs = 200.0;

void require(bool holds, const std::string& what) {
  if (!holds) throw FuzzFinding(what);
}

// Every reader refuses NaN and infinite coordinates (app/io/point_file.h).
void checkStrokes(const std::vector<Stroke>& strokes, const std::string& name) {
  for (const Stroke& s : strokes)
    for (const StrokeSample& p : s.samples) require(std::isfinite(p.p.x()) && std::isfinite(p.p.y()), name + ": non-finite point read");
}

std::vector<Stroke> readAs(std::string_view data, const std::string& name) {
  try {
    std::vector<Stroke> strokes = parseStrokes(std::string(data), name);
    checkStrokes(strokes, name);
    return strokes;
  } catch (const PointFileError&) {
    return {};
  }
}

// The reader a file of this text would most likely go through.
std::string nameFor(std::string_view data) {
  const std::size_t first = data.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return "x.csv";
  if (data[first] == '<') return "x.svg";
  if (data[first] == '{') return "x.json";
  // A name line (letters, no field separator) starts an airfoil.
  const std::string_view line = data.substr(first, data.find_first_of("\r\n", first) - first);
  bool letters = false;
  for (char c : line) letters |= (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
  return letters && line.find_first_of(",;") == std::string_view::npos ? "x.dat" : "x.csv";
}

void checkCurve(const Curve& curve) {
  require(!curve.pieces.empty(), "fitStroke returned an empty curve");
  for (std::size_t i = 0; i < curve.pieces.size(); ++i) {
    const LaSegment& s = curve.pieces[i].segment;
    const std::string where = "segment " + std::to_string(i) + ": ";
    require(std::isfinite(s.length()) && s.length() > 0.0, where + "length not finite and positive");
    require(std::isfinite(s.start().x()) && std::isfinite(s.start().y()), where + "start not finite");
    require(std::isfinite(s.theta0()), where + "theta0 not finite");
    require(std::isfinite(s.kappaStart()) && std::isfinite(s.kappaEnd()), where + "end curvature not finite");
    require(!std::isnan(s.alpha()), where + "alpha is NaN");
    const Vec2 end = s.end();
    require(std::isfinite(end.x()) && std::isfinite(end.y()), where + "end not finite");
  }
}

}  // namespace

void pointFile(std::string_view data) {
  readAs(data, "x.csv");
  readAs(data, "x.dat");
}

void svg(std::string_view data) { readAs(data, "x.svg"); }

void json(std::string_view data) {
  readAs(data, "x.json");
  std::vector<CurveOrError> curves;
  try {
    curves = parseCurvesDocument(data, "x.json");
  } catch (const CurveFormatError&) {
    return;
  }
  // Numbers round-trip exactly (core/curve_json.h): what was read writes and reads back
  // to the same text.
  const std::string written = curvesDocumentToString(curves);
  require(curvesDocumentToString(parseCurvesDocument(written, "written.json")) == written, "curves do not round-trip");
}

void sketch(std::string_view data) {
  Sketch sketch;
  try {
    sketch = parseSketch(std::string(data), "x.lafair");
  } catch (const SketchFileError&) {
    return;
  }
  const std::string written = sketchToString(sketch);
  require(sketchToString(parseSketch(written, "written.lafair")) == written, "sketch does not round-trip");
}

void fit(std::string_view data) {
  std::vector<Stroke> strokes = readAs(data, nameFor(data));
  if (strokes.size() > kMaxFitStrokes) strokes.resize(kMaxFitStrokes);
  FitOptions options;
  options.time_budget_ms = kFitBudgetMs;
  for (Stroke& stroke : strokes) {
    if (stroke.samples.size() > kMaxFitSamples) stroke.samples.resize(kMaxFitSamples);
    try {
      checkCurve(fitStroke(stroke, options).curve);
    } catch (const StrokeError&) {  // too few distinct points, all collinear: documented
    }
  }
}

}  // namespace la::fuzz
