#include "core/curve_json.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/atomic_file.h"

namespace la {
namespace {

using nlohmann::json;

constexpr const char* kInfinity = "inf";
constexpr const char* kNegativeInfinity = "-inf";

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw CurveFormatError(where.empty() ? what : where + ": " + what);
}

// "curves[2]" + "segments[5]" -> "curves[2].segments[5]"; an empty parent is the root.
std::string child(const std::string& where, const std::string& name) {
  return where.empty() ? name : where + "." + name;
}

std::string indexed(const std::string& where, const std::string& key, std::size_t index) {
  return child(where, key + "[" + std::to_string(index) + "]");
}

std::string quoted(const std::string& key) { return "\"" + key + "\""; }

// Type names of nlohmann::json ("string", "array", ...) for "got ..." in messages.
std::string typeName(const json& value) { return value.type_name(); }

const json& requireKey(const json& object, const std::string& key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) fail(where, "missing key " + quoted(key));
  return *it;
}

double requireNumber(const json& object, const std::string& key, const std::string& where) {
  const json& value = requireKey(object, key, where);
  if (!value.is_number())
    fail(where, quoted(key) + " must be a number, got " + typeName(value) + " " + value.dump());
  return value.get<double>();
}

// An optional boolean key; false when absent.
bool optionalFlag(const json& object, const std::string& key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) return false;
  if (!it->is_boolean())
    fail(where, quoted(key) + " must be true or false, got " + typeName(*it) + " " + it->dump());
  return it->get<bool>();
}

void requireObject(const json& value, const std::string& what, const std::string& where) {
  if (!value.is_object()) fail(where, "expected " + what + " object, got " + typeName(value));
}

json alphaToJson(double alpha) {
  if (std::isinf(alpha)) return alpha > 0.0 ? kInfinity : kNegativeInfinity;
  return alpha;
}

double alphaFromJson(const json& segment, const std::string& where) {
  const json& value = requireKey(segment, "alpha", where);
  if (value.is_number()) return value.get<double>();
  if (value.is_string()) {
    const auto& text = value.get_ref<const std::string&>();
    if (text == kInfinity) return std::numeric_limits<double>::infinity();
    if (text == kNegativeInfinity) return -std::numeric_limits<double>::infinity();
  }
  fail(where, "\"alpha\" must be a number, \"inf\" or \"-inf\", got " + typeName(value) + " " +
                  value.dump());
}

// Line and column (both from 1) of byte `offset` (from 0) of `text`; an offset at or
// past the end is the position just after the last character.
std::pair<std::size_t, std::size_t> lineAndColumn(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return {line, offset - line_start + 1};
}

// nlohmann's message without its "[json.exception.parse_error.101] parse error at
// line 3, column 13: " prefix (we state the position ourselves).
std::string parserMessage(const std::string& what) {
  const std::size_t intro = what.find("parse error");
  if (intro == std::string::npos) return what;
  const std::size_t colon = what.find(": ", intro);
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

json parseJson(std::string_view text, const std::string& source_name) {
  const std::string prefix = source_name.empty() ? "" : source_name + ": ";
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte counts the characters read, the offending one included (the end of the
    // input counts as one character): the offending one is at offset byte - 1.
    const auto [line, column] = lineAndColumn(text, e.byte == 0 ? 0 : e.byte - 1);
    throw CurveFormatError(prefix + "line " + std::to_string(line) + ", column " +
                           std::to_string(column) + ": " + parserMessage(e.what()));
  } catch (const json::exception& e) {
    // Valid syntax the library cannot represent, e.g. a number beyond the double range.
    throw CurveFormatError(prefix + e.what());
  }
}

// One entry of a document: a curve, or {"error": "why"}.
CurveOrError entryFromJson(const json& entry, const std::string& where) {
  requireObject(entry, "a curve or error", where);
  if (const auto it = entry.find("error"); it != entry.end()) {
    if (!it->is_string())
      fail(where, "\"error\" must be a string, got " + typeName(*it) + " " + it->dump());
    return {std::nullopt, it->get<std::string>()};
  }
  return {curveFromJson(entry, where), ""};
}

}  // namespace

void stampCurvesFormat(nlohmann::json& document) { document["format"] = kCurvesFormat; }

json segmentToJson(const LaSegment& segment, bool corner) {
  json result = {
      {"alpha", alphaToJson(segment.alpha())},
      {"length", segment.length()},
      {"start", {segment.start().x(), segment.start().y()}},
      {"theta0", segment.theta0()},
      {"kappa_start", segment.kappaStart()},
      {"kappa_end", segment.kappaEnd()},
  };
  if (corner) result["corner"] = true;
  return result;
}

LaSegment segmentFromJson(const json& segment, const std::string& where) {
  requireObject(segment, "a segment", where);
  const double alpha = alphaFromJson(segment, where);
  const double length = requireNumber(segment, "length", where);
  const json& start = requireKey(segment, "start", where);
  if (!(start.is_array() && start.size() == 2 && start[0].is_number() && start[1].is_number()))
    fail(where, "\"start\" must be an array [x, y] of two numbers, got " + start.dump());
  const double theta0 = requireNumber(segment, "theta0", where);
  const double kappa_start = requireNumber(segment, "kappa_start", where);
  const double kappa_end = requireNumber(segment, "kappa_end", where);
  try {
    return LaSegment(alpha, length, Vec2(start[0].get<double>(), start[1].get<double>()), theta0,
                     kappa_start, kappa_end);
  } catch (const std::invalid_argument& e) {
    fail(where, e.what());
  }
}

json curveToJson(const Curve& curve) {
  json segments = json::array();
  for (const CurvePiece& piece : curve.pieces)
    segments.push_back(segmentToJson(piece.segment, piece.corner));
  return {{"segments", std::move(segments)}, {"closed", curve.closed}};
}

Curve curveFromJson(const json& object, const std::string& where) {
  requireObject(object, "a curve", where);
  const json& segments = requireKey(object, "segments", where);
  if (!segments.is_array())
    fail(where, "\"segments\" must be an array, got " + typeName(segments));
  if (segments.empty()) fail(where, "\"segments\" is empty");
  Curve curve;
  curve.closed = optionalFlag(object, "closed", where);
  curve.pieces.reserve(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const std::string location = indexed(where, "segments", i);
    LaSegment segment = segmentFromJson(segments[i], location);
    curve.pieces.push_back({std::move(segment), optionalFlag(segments[i], "corner", location)});
  }
  return curve;
}

std::vector<CurveOrError> parseCurvesDocument(std::string_view text,
                                              const std::string& source_name) {
  const json document = parseJson(text, source_name);
  try {
    requireObject(document, "a curves document", "");
    if (const auto format = document.find("format"); format != document.end()) {
      if (!format->is_string()) fail("", "\"format\" must be a string, got " + typeName(*format));
      const std::string name = format->get<std::string>();
      if (name != kCurvesFormat) {
        const std::string family = "lafair-curves/";
        fail("", name.starts_with(family) ? "format " + name + " is newer than this reader's " + kCurvesFormat
                                          : "format " + name + " is not " + kCurvesFormat);
      }
    }
    std::vector<CurveOrError> result;
    if (const auto it = document.find("curves"); it != document.end()) {
      if (!it->is_array()) fail("", "\"curves\" must be an array, got " + typeName(*it));
      result.reserve(it->size());
      for (std::size_t i = 0; i < it->size(); ++i)
        result.push_back(entryFromJson((*it)[i], indexed("", "curves", i)));
    } else if (const auto single = document.find("curve"); single != document.end()) {
      result.push_back(entryFromJson(*single, "curve"));
    } else if (document.contains("segments") || document.contains("error")) {
      result.push_back(entryFromJson(document, ""));
    } else {
      fail("", "expected a \"curves\" array or a single curve with \"segments\"");
    }
    return result;
  } catch (const CurveFormatError& e) {
    if (source_name.empty()) throw;
    throw CurveFormatError(source_name + ": " + e.what());
  }
}

std::vector<CurveOrError> readCurvesFile(const std::filesystem::path& path) {
  return parseCurvesDocument(readFile(path), path.string());
}

std::string curvesDocumentToString(const std::vector<CurveOrError>& curves) {
  json entries = json::array();
  for (const CurveOrError& entry : curves) {
    if (entry.curve)
      entries.push_back(curveToJson(*entry.curve));
    else
      entries.push_back(json::object({{"error", entry.error}}));
  }
  json document = {{"curves", std::move(entries)}};
  stampCurvesFormat(document);
  // Error texts may quote file names or input that are not valid UTF-8: replace
  // such bytes (U+FFFD) rather than fail to write the whole document.
  return document.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

void writeCurvesFile(const std::filesystem::path& path, const std::vector<CurveOrError>& curves) {
  writeFileAtomically(path, curvesDocumentToString(curves));
}

}  // namespace la
