// Tests of app/io/sketch_file.h: a sketch written and read back is the same (samples
// with unknown values, overrides, options, units, constructions); every bad value is a
// SketchFileError naming the file and the key, never a std::invalid_argument,
// std::out_of_range or nlohmann exception escaping (the std::stoi and .get<double>()
// of the reader's first version in app/gui/document.cpp).

#include "app/io/sketch_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <string>

namespace la {
namespace {

/// The message of the SketchFileError parsing `text` throws, or a note that none came
/// (any other exception fails the test where it is thrown).
std::string errorOf(const std::string& text) {
  try {
    parseSketch(text, "s.lafair");
  } catch (const SketchFileError& e) {
    return e.what();
  }
  return "(no SketchFileError thrown)";
}

void expectError(const std::string& text, std::initializer_list<std::string> parts) {
  const std::string message = errorOf(text);
  EXPECT_EQ(message.rfind("s.lafair: ", 0), 0u) << "message: " << message;
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "message: " << message << "\nexpected to contain: " << part
                                                     << "\ninput: " << text;
}

/// A sketch with one stroke whose JSON object is `stroke`.
std::string withStroke(const std::string& stroke) {
  return R"({"format": "lafair-sketch", "version": 1, "strokes": [)" + stroke + "]}";
}

TEST(SketchFile, RoundTripsStrokesOverridesOptionsAndConstructions) {
  Sketch sketch;
  sketch.options.tolerance_fraction = 0.01;
  sketch.options.time_budget_ms = 250.0;
  sketch.units = "mm";
  SketchStroke s;
  for (int k = 0; k < 5; ++k) {
    StrokeSample p;
    p.p = Vec2(k * 1.5, 0.1 * k * k);
    if (k != 2) p.t = 16.0 * k;  // sample 2 has no time stamp
    p.pressure = 0.5;
    if (k == 3) p.tilt_x = 10.0, p.tilt_y = -20.0;
    s.raw.samples.push_back(p);
  }
  s.raw.profile = true;
  s.alpha_overrides = {{0, -1.0}, {3, 2.5}};
  s.joint_overrides = {{1, Vec2(1.0, 2.0)}};
  s.apex_overrides = {{12, Vec2(-3.0, 4.0)}};
  sketch.strokes.push_back(s);
  sketch.constructions.push_back({{"kind", "whatever the GUI writes"}, {"handles", {{0, 0}, {1, 1}}}});

  const Sketch back = parseSketch(sketchToString(sketch), "s.lafair");
  EXPECT_EQ(back.options.tolerance_fraction, 0.01);
  EXPECT_EQ(back.options.time_budget_ms, 250.0);
  EXPECT_EQ(back.units, "mm");
  ASSERT_EQ(back.strokes.size(), 1u);
  const SketchStroke& b = back.strokes[0];
  ASSERT_EQ(b.raw.samples.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    const StrokeSample &p = s.raw.samples[k], &q = b.raw.samples[k];
    EXPECT_EQ(p.p, q.p) << "sample " << k;
    EXPECT_EQ(std::isnan(p.t), std::isnan(q.t)) << "sample " << k;
    if (!std::isnan(p.t)) {
      EXPECT_EQ(p.t, q.t) << "sample " << k;
    }
    EXPECT_EQ(p.pressure, q.pressure) << "sample " << k;
    EXPECT_EQ(std::isnan(q.tilt_x), k != 3) << "sample " << k;
  }
  EXPECT_TRUE(b.raw.profile);
  EXPECT_EQ(b.alpha_overrides, s.alpha_overrides);
  EXPECT_EQ(b.joint_overrides, s.joint_overrides);
  EXPECT_EQ(b.apex_overrides, s.apex_overrides);
  EXPECT_EQ(back.constructions, sketch.constructions);
}

TEST(SketchFile, ReadsAMinimalSketchWithDefaults) {
  const Sketch sketch = parseSketch(withStroke(R"({"points": [[0, 0], [1, 1], [2, 0]]})"), "s.lafair");
  EXPECT_EQ(sketch.units, "px");
  EXPECT_EQ(sketch.options.tolerance_fraction, FitOptions().tolerance_fraction);
  ASSERT_EQ(sketch.strokes.size(), 1u);
  EXPECT_EQ(sketch.strokes[0].raw.samples.size(), 3u);
  EXPECT_TRUE(std::isnan(sketch.strokes[0].raw.samples[0].t));
  EXPECT_TRUE(sketch.constructions.empty());
}

TEST(SketchFile, RefusesWhatIsNotASketch) {
  expectError("", {"not a JSON document"});
  expectError("{\"format\": ", {"not a JSON document"});
  expectError("[1, 2]", {"not a lafair sketch"});
  expectError(R"({"format": 7, "strokes": []})", {"not a lafair sketch"});
  expectError(R"({"format": "lafair-sketch", "version": 2, "strokes": []})", {"version", "later version"});
  expectError(R"({"format": "lafair-sketch"})", {"missing \"strokes\""});
  expectError(R"({"format": "lafair-sketch", "strokes": {}})", {"strokes: not an array"});
  expectError(R"({"format": "lafair-sketch", "strokes": [], "points": [1e400]})", {"not a JSON document"});
  expectError(std::string(300, '[') + std::string(300, ']'), {"nested deeper than 256"});
}

TEST(SketchFile, NamesTheKeyOfEveryBadValue) {
  expectError(R"({"format": "lafair-sketch", "strokes": [], "options": {"tolerance": "big"}})",
              {"options: ", "\"tolerance\" is not a number"});
  expectError(R"({"format": "lafair-sketch", "strokes": [], "units": 3})", {"units: not a string"});
  expectError(R"({"format": "lafair-sketch", "strokes": [], "constructions": [1]})", {"constructions[0]: not an object"});
  expectError(withStroke("7"), {"strokes[0]: not an object"});
  expectError(withStroke("{}"), {"strokes[0]: missing \"points\""});
  expectError(withStroke(R"({"points": [[0, 0], [1]]})"), {"strokes[0].points[1]: expected [x, y]"});
  expectError(withStroke(R"({"points": [[0, 0], [1, "y"]]})"), {"strokes[0].points[1][1]: not a number"});
  expectError(withStroke(R"({"points": [[0, 0]], "t": 5})"), {"strokes[0].t: not an array"});
  expectError(withStroke(R"({"points": [[0, 0]], "pressure": [true]})"), {"strokes[0].pressure[0]: not a number"});
  expectError(withStroke(R"({"points": [[0, 0]], "tilt": [3]})"), {"strokes[0].tilt[0]: expected [x, y]"});
  expectError(withStroke(R"({"points": [[0, 0]], "profile": 1})"), {"strokes[0].profile: not true or false"});
  expectError(withStroke(R"({"points": [], "alpha_overrides": []})"), {"strokes[0].alpha_overrides: not an object"});
}

TEST(SketchFile, OverrideKeysAndValuesAreCheckedNotThrownThrough) {
  // std::stoi threw std::invalid_argument on "x" and std::out_of_range on the big one.
  for (const std::string key : {"x", "", "1.5", "-1", " 1", "1x", "99999999999999999999"})
    expectError(withStroke(R"({"points": [], "alpha_overrides": {")" + key + R"(": 1.0}})"),
                {"strokes[0].alpha_overrides[\"" + key + "\"]: key is not a segment or joint index"});
  expectError(withStroke(R"({"points": [], "alpha_overrides": {"0": "steep"}})"),
              {"strokes[0].alpha_overrides[\"0\"]: not a number"});
  expectError(withStroke(R"({"points": [], "alpha_overrides": {"0": null}})"),
              {"strokes[0].alpha_overrides[\"0\"]: not a number"});
  expectError(withStroke(R"({"points": [], "joint_overrides": {"2": [1]}})"),
              {"strokes[0].joint_overrides[\"2\"]: expected [x, y]"});
  expectError(withStroke(R"({"points": [], "apex_overrides": {"q": [1, 2]}})"),
              {"strokes[0].apex_overrides[\"q\"]: key is not"});
  expectError(withStroke(R"({"points": [], "apex_overrides": {"0": [1, {}]}})"),
              {"strokes[0].apex_overrides[\"0\"][1]: not a number"});
}

}  // namespace
}  // namespace la
