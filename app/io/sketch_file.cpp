#include "app/io/sketch_file.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "app/io/fit_options_json.h"

namespace la {
namespace {

using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Every check of the reader throws through this one: "<file>: <where>: <what>".
class Reader {
 public:
  explicit Reader(const std::string& name) : m_name(name) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw SketchFileError(m_name + ": " + (where.empty() ? "" : where + ": ") + what);
  }

  const json& member(const json& object, const char* key, const std::string& where) const {
    if (!object.contains(key)) fail(where, std::string("missing \"") + key + "\"");
    return object.at(key);
  }

  double finite(const json& value, const std::string& where) const {
    if (!value.is_number()) fail(where, "not a number");
    const double v = value.get<double>();
    if (!std::isfinite(v)) fail(where, "not a finite number");
    return v;
  }

  // A number, or null for unknown (NaN).
  double orUnknown(const json& value, const std::string& where) const { return value.is_null() ? kNaN : finite(value, where); }

  Vec2 point(const json& value, const std::string& where) const {
    if (!value.is_array() || value.size() != 2) fail(where, "expected [x, y]");
    return Vec2(finite(value[0], where + "[0]"), finite(value[1], where + "[1]"));
  }

  // An override key: a segment or joint index in decimal ("0", "12"), nothing else.
  int index(const std::string& key, const std::string& where) const {
    int value = -1;
    const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), value);
    if (key.empty() || error != std::errc() || end != key.data() + key.size() || value < 0)
      fail(where + "[\"" + key + "\"]", "key is not a segment or joint index");
    return value;
  }

  // An optional list beside the points: absent or null is an empty list.
  const json& list(const json& stroke, const char* key, const std::string& where) const {
    static const json empty = json::array();
    if (!stroke.contains(key) || stroke.at(key).is_null()) return empty;
    const json& value = stroke.at(key);
    if (!value.is_array()) fail(where + "." + key, "not an array");
    return value;
  }

  const json& object(const json& stroke, const char* key, const std::string& where) const {
    static const json empty = json::object();
    if (!stroke.contains(key)) return empty;
    const json& value = stroke.at(key);
    if (!value.is_object()) fail(where + "." + key, "not an object");
    return value;
  }

  SketchStroke stroke(const json& item, const std::string& where) const {
    if (!item.is_object()) fail(where, "not an object");
    const json& points = member(item, "points", where);
    if (!points.is_array()) fail(where + ".points", "not an array of [x, y]");
    const json& t = list(item, "t", where);
    const json& pressure = list(item, "pressure", where);
    const json& tilt = list(item, "tilt", where);
    SketchStroke s;
    s.raw.samples.resize(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const std::string at = "[" + std::to_string(k) + "]";
      StrokeSample& sample = s.raw.samples[k];
      sample.p = point(points[k], where + ".points" + at);
      if (k < t.size()) sample.t = orUnknown(t[k], where + ".t" + at);
      if (k < pressure.size()) sample.pressure = orUnknown(pressure[k], where + ".pressure" + at);
      if (k < tilt.size()) {
        const json& pair = tilt[k];
        if (!pair.is_array() || pair.size() != 2) fail(where + ".tilt" + at, "expected [x, y] (null for unknown)");
        sample.tilt_x = orUnknown(pair[0], where + ".tilt" + at + "[0]");
        sample.tilt_y = orUnknown(pair[1], where + ".tilt" + at + "[1]");
      }
    }
    if (item.contains("profile")) {
      if (!item.at("profile").is_boolean()) fail(where + ".profile", "not true or false");
      s.raw.profile = item.at("profile").get<bool>();
    }
    const std::string alphas = where + ".alpha_overrides";
    for (const auto& [key, value] : object(item, "alpha_overrides", where).items())
      s.alpha_overrides[index(key, alphas)] = finite(value, alphas + "[\"" + key + "\"]");
    for (const auto& [field, overrides] : {std::pair{"joint_overrides", &s.joint_overrides}, std::pair{"apex_overrides", &s.apex_overrides}}) {
      const std::string place = where + "." + field;
      for (const auto& [key, value] : object(item, field, where).items())
        (*overrides)[index(key, place)] = point(value, place + "[\"" + key + "\"]");
    }
    return s;
  }

 private:
  const std::string& m_name;
};

json pointsToJson(const std::map<int, Vec2>& points) {
  json j = json::object();
  for (const auto& [index, q] : points) j[std::to_string(index)] = {q.x(), q.y()};
  return j;
}

}  // namespace

Sketch parseSketch(const std::string& text, const std::string& name) {
  const Reader reader(name);
  json doc;
  try {
    // The callback sees each array and object as it opens, at its depth (0: the top).
    doc = json::parse(text, [&](int depth, json::parse_event_t event, json&) {
      if ((event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) &&
          static_cast<std::size_t>(depth) >= kMaxSketchNesting)
        reader.fail("", "JSON nested deeper than " + std::to_string(kMaxSketchNesting) + " levels");
      return true;
    });
  } catch (const json::exception& e) {  // syntax (with line and column), a number beyond double range
    reader.fail("", std::string("not a JSON document (") + e.what() + ")");
  }
  if (!doc.is_object() || !doc.contains("format") || doc.at("format") != "lafair-sketch")
    reader.fail("", "not a lafair sketch (no \"format\": \"lafair-sketch\")");
  if (doc.contains("version") && doc.at("version") != 1)
    reader.fail("version", "not 1 (" + doc.at("version").dump() + "): a later version of lafair wrote it");

  Sketch sketch;
  if (doc.contains("options")) {
    try {
      sketch.options = fitOptionsFromJson(doc.at("options"));
    } catch (const std::invalid_argument& e) {
      reader.fail("options", e.what());
    }
  }
  if (doc.contains("units")) {
    if (!doc.at("units").is_string()) reader.fail("units", "not a string");
    sketch.units = doc.at("units").get<std::string>();
  }
  const json& strokes = reader.member(doc, "strokes", "");
  if (!strokes.is_array()) reader.fail("strokes", "not an array");
  sketch.strokes.reserve(strokes.size());
  for (std::size_t i = 0; i < strokes.size(); ++i)
    sketch.strokes.push_back(reader.stroke(strokes[i], "strokes[" + std::to_string(i) + "]"));
  if (doc.contains("constructions")) {
    const json& constructions = doc.at("constructions");
    if (!constructions.is_array()) reader.fail("constructions", "not an array");
    for (std::size_t i = 0; i < constructions.size(); ++i)
      if (!constructions[i].is_object()) reader.fail("constructions[" + std::to_string(i) + "]", "not an object");
    sketch.constructions = constructions;
  }
  return sketch;
}

std::string sketchToString(const Sketch& sketch) {
  const auto value = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json strokes = json::array();
  for (const SketchStroke& s : sketch.strokes) {
    json points = json::array(), t = json::array(), pressure = json::array(), tilt = json::array();
    for (const StrokeSample& p : s.raw.samples) {
      points.push_back({p.p.x(), p.p.y()});
      t.push_back(value(p.t));
      pressure.push_back(value(p.pressure));
      tilt.push_back({value(p.tilt_x), value(p.tilt_y)});
    }
    json alphas = json::object();
    for (const auto& [piece, alpha] : s.alpha_overrides) alphas[std::to_string(piece)] = alpha;
    strokes.push_back({{"points", points}, {"t", t}, {"pressure", pressure}, {"tilt", tilt}, {"alpha_overrides", alphas},
                       {"joint_overrides", pointsToJson(s.joint_overrides)},
                       {"apex_overrides", pointsToJson(s.apex_overrides)}});
    if (s.raw.profile) strokes.back()["profile"] = true;
  }
  const json doc = {{"format", "lafair-sketch"}, {"version", 1}, {"options", fitOptionsToJson(sketch.options)},
                    {"strokes", strokes}, {"curves", sketch.curves}, {"constructions", sketch.constructions},
                    {"units", sketch.units}};
  return doc.dump(1) + "\n";
}

}  // namespace la
