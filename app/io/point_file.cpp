// Readers of stroke and profile files (DESIGN.md section 5). Four small parsers share
// one number scanner and one error style, "<file>:<line>: <what>":
//
//  - CSV / TXT. A data line holds 2 to 4 numbers, x y [t [pressure]]; fields are
//    separated by a run of spaces or tabs that may hold one ',' or ';' (so "1,2",
//    "1 2", "1;2" and "1 , 2" all read, but "1,,2" is an empty field and an error),
//    the same kind throughout a line ("1,5;2,5" is refused: decimal commas). Lines
//    end with LF, CRLF or a lone CR. '#' starts a comment (a whole line or the rest
//    of one). The first non-comment line may be a header (all its fields non-numeric:
//    a first line mixing numbers and text is an error, not a header); if every header name
//    is known (x, y, t / time / timestamp, p / pressure, each once) the columns are
//    taken by name, otherwise by position. A blank line ends a stroke (runs of blank
//    lines count once). The lines "START" and "BREAK" of the Omniglot stroke files
//    are understood (START ignored, BREAK ends a stroke), so their originals read too.
//    NaN or infinite values are errors, not unknowns: a file has no business holding
//    them, and the stroke clean-up would only drop them silently.
//  - Airfoil .dat (Selig): a name line, then "x y" lines, trailing edge over the upper
//    surface to the leading edge and back; blank lines are ignored and the file is one
//    stroke, a profile (Stroke::profile: corners only at its ends, the trailing edge).
//    A file without a name line reads the same. Lednicer files (a name line, then a
//    line of two point counts) are refused with a message saying so, rather than read
//    as a profile with a bogus first point.
//  - JSON: {"strokes": [{"points": [[x, y], ...], "t": [...], "pressure": [...]}]};
//    t and pressure are optional, must have one entry per point, and may hold null
//    for an unknown value (nlohmann writes NaN as null); "profile": true marks a
//    profile (Stroke::profile). Unknown keys are ignored. A stroke with no points is
//    kept, so stroke indices match the file. Syntax errors
//    give line and column; schema errors name the stroke and the key
//    ("strokes[2].t: 3 values for 5 points"); nlohmann does not keep positions of
//    values, so those have no line.
//  - SVG: a hand-written scanner, not an XML parser. It skips comments, CDATA,
//    processing instructions, the DOCTYPE (with its internal subset), the contents of
//    <script> and <style>, and everything inside <defs>, <clipPath>, <mask>,
//    <symbol>, <marker> and <pattern> (not drawn as they stand). Of the rest it reads
//    only <path d>, <polyline points> and <polygon points>; other shapes (rect,
//    circle, line, ...) are ignored. Transforms (on the element or its groups),
//    viewBox scaling and units are ignored: coordinates are taken as written, in
//    user units. Each subpath is one stroke. Curves and straight pieces alike are
//    flattened to points on the exact curve, spread evenly in arc length, at most
//    kMaxSpacingFraction of the element's bounding-box diagonal apart, and at least
//    kMinCurvePieces pieces per curve segment. Arcs go through the endpoint-to-centre
//    conversion of SVG 1.1 Appendix F.6.5 (radii scaled up per F.6.6 when too small,
//    a zero radius makes a line). Z (and a <polygon>) closes a subpath: the closing
//    edge is sampled like any line but the start point is not repeated (a last point
//    equal to the start is dropped), so the stroke ends one spacing short of its start
//    and the clean-up recognises it as closed. A subpath that is only a moveto draws
//    nothing and gives no stroke. Bad path data gives the line of the bad data (the
//    element's line if the attribute held character references); so do coordinates
//    beyond double range (a relative step past 1.8e308) and drawings whose distances
//    overflow (sizes beyond about 1e154), which cannot be flattened. An arc whose
//    radii exceed 1e8 times its half chord is drawn, if it is the small arc, as its
//    chord (F.6.5 loses every digit of it from so far a centre).

#include "app/io/point_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

namespace la {
namespace {

/// Largest distance between consecutive flattened SVG points, as a fraction of the
/// element's bounding-box diagonal. The chord of a piece h long deviates from a curve of
/// radius rho by h^2 / (8 rho): for a KanjiVG stroke (diagonal ~85 units, h ~0.4) and a
/// tight hook (rho ~2) that is 0.01 unit, far below pen noise, while a stroke still gets
/// only a few hundred points for the fitter.
constexpr double kMaxSpacingFraction = 0.005;
/// Fewest pieces a curve segment (C, S, Q, T, A) is cut into, however short, so the
/// fitter sees its bend; straight pieces may be a single piece.
constexpr int kMinCurvePieces = 4;
/// Parameter steps of the first chord-length table of a segment (refined to four per
/// output piece when more pieces are needed), and of the bounding-box estimate.
constexpr int kLengthTableSteps = 64;
constexpr int kBoxSamplesPerSegment = 16;
/// Below this (half chord / radius)^2 of an SVG arc, the small arc is drawn as its chord
/// (radii more than 1e8 times the half chord; the sagitta is under 1e-8 of the chord).
constexpr double kArcAsChordLambda = 1e-16;
/// Longest excerpt of the offending text quoted in a message.
constexpr std::size_t kQuoteLength = 24;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ------------------------------------------------------------------ shared helpers

[[noreturn]] void failAt(const std::string& name, std::size_t line, const std::string& what) {
  throw PointFileError(name + ":" + std::to_string(line) + ": " + what);
}

[[noreturn]] void failFile(const std::string& name, const std::string& what) {
  throw PointFileError(name + ": " + what);
}

/// The end of a message about a limit of ReadLimits: its value and the flag that raises it.
std::string limitNote(std::size_t limit, const char* flag) {
  return " (the limit is " + std::to_string(limit) + "; lafit " + flag + " raises it)";
}

/// An excerpt of input for a message: at most kQuoteLength bytes, not cutting a UTF-8
/// character, with control characters shown as '?' (a NUL would end the message where
/// it stands, an ESC would drive the terminal).
std::string quote(std::string_view text) {
  std::size_t length = std::min(text.size(), kQuoteLength);
  while (length > 0 && length < text.size() && (static_cast<unsigned char>(text[length]) & 0xC0) == 0x80) --length;
  std::string out(text.substr(0, length));
  for (char& c : out) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    else if (static_cast<unsigned char>(c) < 0x20 || c == '\x7F') c = '?';
  }
  if (text.size() > length) out += "...";
  return out;
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

/// Whether text[i] ends a line: a '\n', or a '\r' not followed by one (a lone CR).
bool endsLine(std::string_view text, std::size_t i) {
  return text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'));
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// Whether a decimal number that std::from_chars found out of range is too large (true)
/// or too small (false) for a double. Its decimal order of magnitude is the exponent
/// plus the place of the first non-zero digit; the exponent is only needed as far as
/// its sign and whether it outweighs the digits, so it saturates instead of overflowing.
bool overflowsDouble(std::string_view s) {
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) s.remove_prefix(1);
  const std::size_t e = s.find_first_of("eE");
  const std::string_view mantissa = s.substr(0, e);
  long long exponent = 0;
  if (e != std::string_view::npos) {
    std::string_view digits = s.substr(e + 1);
    const bool negative = !digits.empty() && digits.front() == '-';
    if (!digits.empty() && (digits.front() == '-' || digits.front() == '+')) digits.remove_prefix(1);
    for (const char c : digits) exponent = std::min<long long>(exponent * 10 + (c - '0'), 1'000'000'000'000LL);
    if (negative) exponent = -exponent;
  }
  const std::size_t point = std::min(mantissa.find('.'), mantissa.size());
  const std::size_t first_digit = mantissa.find_first_not_of("0.");
  if (first_digit == std::string_view::npos) return false;  // zero: never out of range
  // Digits before the point from the first non-zero one; negative when it is after the point.
  const long long place = first_digit < point ? static_cast<long long>(point - first_digit)
                                              : -static_cast<long long>(first_digit - point) + 1;
  return exponent + place > 0;
}

/// A whole field as a double, or nullopt if it is not one number. Locale-independent
/// (std::from_chars): the GUI may run under a locale with a decimal comma. Accepts a
/// leading '+', and "nan" / "inf" (the caller rejects those with a clearer message).
/// A magnitude beyond double range reads as +-inf or +-0, as strtod would give.
std::optional<double> parseNumber(std::string_view s) {
  if (!s.empty() && s.front() == '+') {
    s.remove_prefix(1);
    if (!s.empty() && (s.front() == '+' || s.front() == '-')) return std::nullopt;
  }
  if (s.empty()) return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    // Not only "1e999": 400 digits without an exponent overflow too.
    const double magnitude = overflowsDouble(s) ? std::numeric_limits<double>::infinity() : 0.0;
    return s.front() == '-' ? -magnitude : magnitude;
  }
  if (ec != std::errc{}) return std::nullopt;
  return value;
}

/// The text split into lines at "\n", "\r\n" or a lone "\r" (classic Mac OS files,
/// and some spreadsheet exports: read as one line, their points would run together
/// into one row of many numbers), after a UTF-8 byte order mark if there is one. Line
/// i of the result is line i + 1 of the file.
std::vector<std::string_view> splitLines(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find_first_of("\r\n", start);
    if (end == std::string_view::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + (text.substr(end).starts_with("\r\n") ? 2 : 1);
  }
  return lines;
}

// ------------------------------------------------------------------ CSV / TXT / .dat

enum class FieldSplit { kOk, kEmptyField, kMixedSeparators };

/// Splits a data line into fields. A separator is a run of spaces and tabs holding at
/// most one ',' or ';'. Fails on an empty field (",1", "1,,2", "1,"), and on a line
/// whose separators are not all alike (blank only, with ',' or with ';'): that is how
/// decimal commas look ("1,5;2,5" or "1,5 2,5"), which would otherwise read as four
/// numbers, x y t pressure, and give a wrong curve without a word.
FieldSplit splitFields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  std::size_t i = 0;
  const auto skipBlank = [&] {
    while (i < line.size() && isSpace(line[i])) ++i;
  };
  const auto isSeparator = [](char c) { return c == ',' || c == ';' || isSpace(c); };
  char line_separator = 0;  // ',', ';' or ' ' for the first separator of the line
  skipBlank();
  while (i < line.size()) {
    const std::size_t start = i;
    while (i < line.size() && !isSeparator(line[i])) ++i;
    if (i == start) return FieldSplit::kEmptyField;  // a ',' or ';' where a field should start
    fields.push_back(line.substr(start, i - start));
    skipBlank();
    if (i == line.size()) break;
    char separator = ' ';
    if (line[i] == ',' || line[i] == ';') {
      separator = line[i];
      ++i;
      skipBlank();
      if (i == line.size()) return FieldSplit::kEmptyField;  // trailing separator
    }
    if (line_separator != 0 && separator != line_separator) return FieldSplit::kMixedSeparators;
    line_separator = separator;
  }
  return FieldSplit::kOk;
}

enum Column { kX = 0, kY = 1, kT = 2, kPressure = 3 };

/// Column of each quantity if every header name is a known one (each at most once, x
/// and y present); nullopt otherwise.
std::optional<std::array<int, 4>> columnsFromHeader(const std::vector<std::string_view>& header) {
  std::array<int, 4> column{-1, -1, -1, -1};
  for (std::size_t i = 0; i < header.size(); ++i) {
    const std::string name = lower(header[i]);
    int quantity = -1;
    if (name == "x") quantity = kX;
    else if (name == "y") quantity = kY;
    else if (name == "t" || name == "time" || name == "timestamp") quantity = kT;
    else if (name == "p" || name == "pressure") quantity = kPressure;
    if (quantity < 0 || column[quantity] >= 0) return std::nullopt;
    column[quantity] = static_cast<int>(i);
  }
  if (column[kX] < 0 || column[kY] < 0) return std::nullopt;
  return column;
}

std::vector<Stroke> parseDelimited(std::string_view text, const std::string& name, bool airfoil,
                                   const ReadLimits& limits) {
  std::vector<Stroke> strokes;
  Stroke current;
  std::size_t line_number = 0;
  const auto endStroke = [&] {
    if (current.samples.empty()) return;
    if (strokes.size() == limits.max_strokes)
      failAt(name, line_number, "more than " + std::to_string(limits.max_strokes) + " strokes" +
                                    limitNote(limits.max_strokes, "--max-strokes"));
    strokes.push_back(std::move(current));
    current = Stroke{};
  };
  bool header_seen = false;
  bool data_seen = false;
  std::optional<std::array<int, 4>> named_columns;  // from a recognised header
  std::size_t header_size = 0;
  std::vector<std::string_view> fields;
  std::vector<double> values;

  const std::vector<std::string_view> lines = splitLines(text);
  for (std::size_t index = 0; index < lines.size(); ++index) {
    line_number = index + 1;
    std::string_view line = lines[index];
    if (trim(line).empty()) {
      if (!airfoil) endStroke();
      continue;
    }
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) continue;  // a comment line: not a stroke break
    if (!airfoil && line == "START") continue;
    if (!airfoil && line == "BREAK") {
      endStroke();
      continue;
    }
    switch (splitFields(line, fields)) {
      case FieldSplit::kOk: break;
      case FieldSplit::kEmptyField: failAt(name, line_number, "empty field in '" + quote(line) + "'");
      case FieldSplit::kMixedSeparators:
        failAt(name, line_number,
               "mixed separators in '" + quote(line) +
                   "' (decimal commas? numbers must use '.', fields one kind of separator)");
    }

    values.clear();
    std::optional<std::string_view> bad_field;
    for (const std::string_view field : fields) {
      if (const std::optional<double> v = parseNumber(field)) values.push_back(*v);
      else if (!bad_field) bad_field = field;
    }
    if (bad_field) {
      // A CSV header is all names: a first line with numbers among its fields is damaged
      // data ("13.0x,0.5"), and skipping it as a header would lose a point unsaid. An
      // airfoil's name line is free text ("NACA 2412").
      if (!header_seen && !data_seen && (airfoil || values.empty())) {
        header_seen = true;
        if (!airfoil) {
          named_columns = columnsFromHeader(fields);
          header_size = fields.size();
        }
        continue;
      }
      failAt(name, line_number, "non-numeric field '" + quote(*bad_field) + "'");
    }

    const std::size_t count = values.size();
    if (airfoil) {
      if (count != 2) failAt(name, line_number, "expected 2 numbers (x y), found " + std::to_string(count));
      // Lednicer: a name line, then the point counts of the two surfaces (e.g. "17. 17.").
      if (header_seen && !data_seen && values[0] >= 2.0 && values[1] >= 2.0 &&
          values[0] == std::floor(values[0]) && values[1] == std::floor(values[1]))
        failAt(name, line_number,
               "looks like the point-count line of a Lednicer airfoil file; only Selig files "
               "(a name line, then x y from the trailing edge round to the trailing edge) are read");
    } else if (named_columns) {
      // Trailing columns may be left out, but not x and y.
      const std::size_t needed = static_cast<std::size_t>(std::max((*named_columns)[kX], (*named_columns)[kY])) + 1;
      if (count < needed || count > header_size)
        failAt(name, line_number,
               "expected " + std::to_string(needed) + " to " + std::to_string(header_size) +
                   " numbers (columns as in the header), found " + std::to_string(count));
    } else if (count < 2 || count > 4) {
      failAt(name, line_number, "expected 2 to 4 numbers (x y [t [pressure]]), found " + std::to_string(count));
    }

    const auto column = [&](int quantity) { return named_columns ? (*named_columns)[quantity] : quantity; };
    const auto present = [&](int quantity) { return column(quantity) >= 0 && static_cast<std::size_t>(column(quantity)) < count; };
    const auto value = [&](int quantity) { return present(quantity) ? values[column(quantity)] : kNaN; };
    StrokeSample sample;
    sample.p = Vec2(value(kX), value(kY));
    sample.t = value(kT);
    sample.pressure = value(kPressure);
    if (std::isnan(sample.p.x()) || std::isnan(sample.p.y())) failAt(name, line_number, "NaN coordinate");
    if (!allFinite(sample.p)) failAt(name, line_number, "infinite coordinate");
    // Absent columns are NaN; a column that is present must hold a finite number.
    if (present(kT) && !std::isfinite(sample.t)) failAt(name, line_number, "NaN or infinite time stamp");
    if (present(kPressure) && !std::isfinite(sample.pressure)) failAt(name, line_number, "NaN or infinite pressure");
    if (current.samples.size() == limits.max_points_per_stroke)
      failAt(name, line_number, "stroke " + std::to_string(strokes.size() + 1) + " has more than " +
                                    std::to_string(limits.max_points_per_stroke) + " points" +
                                    limitNote(limits.max_points_per_stroke, "--max-points"));
    current.samples.push_back(sample);
    data_seen = true;
  }
  endStroke();
  if (strokes.empty()) failFile(name, "no points");
  return strokes;
}

// ------------------------------------------------------------------ JSON

/// Offset of the first bracket nested deeper than `max_depth` in JSON text (outside
/// strings), if any: checked before parsing, whose cost and recursion grow with depth.
std::optional<std::size_t> tooDeep(std::string_view text, std::size_t max_depth) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

std::vector<Stroke> parseJson(const std::string& text, const std::string& name, const ReadLimits& limits) {
  using nlohmann::json;
  // "<file>:<line>:<column>" of a 0-based offset in the text.
  const auto positionOf = [&](std::size_t offset) {
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < offset; ++i)
      if (endsLine(text, i)) ++line, line_start = i + 1;
    return name + ":" + std::to_string(line) + ":" + std::to_string(offset - line_start + 1);
  };
  if (const auto deep = tooDeep(text, limits.max_nesting))
    throw PointFileError(positionOf(*deep) + ": JSON nested deeper than " + std::to_string(limits.max_nesting) +
                         " levels" + limitNote(limits.max_nesting, "--max-nesting"));
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based offset of the last character read (past the end at EOF).
    const std::size_t offset = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    std::string what = e.what();
    // Keep nlohmann's description, not its own "[json.exception...] ... column N:" prefix.
    if (const std::size_t at = what.find("column "); at != std::string::npos)
      if (const std::size_t colon = what.find(": ", at); colon != std::string::npos) what = what.substr(colon + 2);
    throw PointFileError(positionOf(offset) + ": JSON " + what);
  } catch (const json::out_of_range& e) {
    // A number beyond double range ("1e400"): nlohmann throws this one without a
    // position, only the number, so the first place it stands on its own is named.
    const std::string what = e.what();
    const std::size_t open = what.find('\'');
    const std::size_t close = what.rfind('\'');
    if (open == std::string::npos || close <= open) failFile(name, "JSON number out of range");
    const std::string number = what.substr(open + 1, close - open - 1);
    const auto partOfNumber = [](char c) { return isDigit(c) || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-'; };
    for (std::size_t at = text.find(number); at != std::string::npos; at = text.find(number, at + 1)) {
      const std::size_t end = at + number.size();
      if ((at == 0 || !partOfNumber(text[at - 1])) && (end == text.size() || !partOfNumber(text[end])))
        throw PointFileError(positionOf(at) + ": JSON number out of range: " + number);
    }
    failFile(name, "JSON number out of range: " + number);
  }

  if (!doc.is_object() || !doc.contains("strokes") || !doc["strokes"].is_array())
    failFile(name, "expected an object with a \"strokes\" array");
  const json& list = doc["strokes"];
  if (list.size() > limits.max_strokes)
    failFile(name, std::to_string(list.size()) + " strokes, more than " + std::to_string(limits.max_strokes) +
                       limitNote(limits.max_strokes, "--max-strokes"));
  std::vector<Stroke> strokes;
  std::size_t total = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = "strokes[" + std::to_string(i) + "]";
    const json& item = list[i];
    if (!item.is_object()) failFile(name, where + ": expected an object with \"points\"");
    if (!item.contains("points") || !item["points"].is_array())
      failFile(name, where + ".points: missing or not an array of [x, y]");
    const json& points = item["points"];
    if (points.size() > limits.max_points_per_stroke)
      failFile(name, where + ".points: " + std::to_string(points.size()) + " points, more than " +
                         std::to_string(limits.max_points_per_stroke) +
                         limitNote(limits.max_points_per_stroke, "--max-points"));
    Stroke stroke;
    stroke.samples.resize(points.size());
    for (std::size_t j = 0; j < points.size(); ++j) {
      const json& p = points[j];
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
        failFile(name, where + ".points[" + std::to_string(j) + "]: expected [x, y], two numbers");
      stroke.samples[j].p = Vec2(p[0].get<double>(), p[1].get<double>());
      if (!allFinite(stroke.samples[j].p))
        failFile(name, where + ".points[" + std::to_string(j) + "]: NaN or infinite coordinate");
    }
    for (const std::string key : {"t", "pressure"}) {
      if (!item.contains(key) || item[key].is_null()) continue;
      const json& array = item[key];
      const std::string at = where + "." + key;
      if (!array.is_array()) failFile(name, at + ": expected an array of numbers");
      if (array.size() != points.size())
        failFile(name, at + ": " + std::to_string(array.size()) + " values for " + std::to_string(points.size()) +
                           " points");
      for (std::size_t j = 0; j < array.size(); ++j) {
        double v = kNaN;  // null: unknown
        if (array[j].is_number()) v = array[j].get<double>();
        else if (!array[j].is_null())
          failFile(name, at + "[" + std::to_string(j) + "]: expected a number or null");
        stroke.samples[j].*(key == "t" ? &StrokeSample::t : &StrokeSample::pressure) = v;
      }
    }
    if (item.contains("profile")) {
      if (!item["profile"].is_boolean()) failFile(name, where + ".profile: expected true or false");
      stroke.profile = item["profile"].get<bool>();
    }
    total += stroke.samples.size();
    strokes.push_back(std::move(stroke));
  }
  if (total == 0) failFile(name, "no points");
  return strokes;
}

// ------------------------------------------------------------------ SVG geometry

/// One piece of a subpath, evaluated at u in [0, 1].
struct Segment {
  enum class Kind { kLine, kQuad, kCubic, kArc };
  Kind kind = Kind::kLine;
  std::array<Vec2, 4> p{};  // control points: line p0 p1, quad p0 p1 p2, cubic p0..p3
  // Arc in centre form: centre + R(phi) (rx cos theta, ry sin theta), theta from theta1
  // over dtheta; p[0] and p[1] hold the exact end points.
  Vec2 centre = Vec2::Zero();
  double rx = 0.0, ry = 0.0, cos_phi = 1.0, sin_phi = 0.0, theta1 = 0.0, dtheta = 0.0;

  Vec2 endPoint() const {
    switch (kind) {
      case Kind::kLine: return p[1];
      case Kind::kQuad: return p[2];
      case Kind::kCubic: return p[3];
      case Kind::kArc: return p[1];
    }
    return p[1];
  }

  Vec2 at(double u) const {
    if (u >= 1.0) return endPoint();
    const double v = 1.0 - u;
    switch (kind) {
      case Kind::kLine: return v * p[0] + u * p[1];
      case Kind::kQuad: return v * v * p[0] + 2.0 * u * v * p[1] + u * u * p[2];
      case Kind::kCubic: return v * v * v * p[0] + 3.0 * u * v * v * p[1] + 3.0 * u * u * v * p[2] + u * u * u * p[3];
      case Kind::kArc: {
        if (u <= 0.0) return p[0];
        const double theta = theta1 + u * dtheta;
        const double x = rx * std::cos(theta), y = ry * std::sin(theta);
        return centre + Vec2(cos_phi * x - sin_phi * y, sin_phi * x + cos_phi * y);
      }
    }
    return p[0];
  }
};

struct Subpath {
  Vec2 start = Vec2::Zero();
  std::vector<Segment> segments;
  bool closed = false;
  bool drawn = false;  // any command after the moveto
};

Segment lineSegment(const Vec2& a, const Vec2& b) {
  Segment s;
  s.kind = Segment::Kind::kLine;
  s.p[0] = a;
  s.p[1] = b;
  return s;
}

/// SVG 1.1 Appendix F.6.5 (endpoint to centre parametrisation) with the out-of-range
/// radii handling of F.6.6. nullopt if the end points coincide (the arc is omitted).
std::optional<Segment> arcSegment(const Vec2& from, double rx, double ry, double phi_degrees, bool large_arc,
                                  bool sweep, const Vec2& to) {
  if (from == to) return std::nullopt;
  rx = std::abs(rx);
  ry = std::abs(ry);
  if (rx == 0.0 || ry == 0.0) return lineSegment(from, to);
  // Reduced first: 1e308 degrees times pi would overflow, and NaN would drop the arc.
  const double phi = std::fmod(phi_degrees, 360.0) * std::numbers::pi / 180.0;
  Segment s;
  s.kind = Segment::Kind::kArc;
  s.p[0] = from;
  s.p[1] = to;
  s.cos_phi = std::cos(phi);
  s.sin_phi = std::sin(phi);
  // Step 1: (x1', y1'), the half chord in the ellipse's axes (F.6.5.1).
  const Vec2 half = 0.5 * (from - to);
  const double x1 = s.cos_phi * half.x() + s.sin_phi * half.y();
  const double y1 = -s.sin_phi * half.x() + s.cos_phi * half.y();
  // F.6.6.2: scale radii up uniformly when no ellipse of these radii reaches. Written
  // with ratios, not squared radii, which overflow for radii above 1e154.
  const double lambda = (x1 / rx) * (x1 / rx) + (y1 / ry) * (y1 / ry);
  // Radii over 1e8 times the chord: the short arc is its chord to 1e-9 of its length,
  // and the centre so far away that points evaluated from it would lose every digit.
  if (lambda < kArcAsChordLambda && !large_arc) return lineSegment(from, to);
  if (!(lambda > 0.0)) return std::nullopt;  // a large arc round an ellipse no double reaches
  if (lambda > 1.0) {
    rx *= std::sqrt(lambda);
    ry *= std::sqrt(lambda);
  }
  // Step 2: (cx', cy') (F.6.5.2). Its radicand (rx^2 ry^2 - rx^2 y1^2 - ry^2 x1^2) /
  // (rx^2 y1^2 + ry^2 x1^2) is (1 - lambda) / lambda, clamped at 0 against rounding
  // (and 0 once the radii were scaled up).
  double factor = lambda >= 1.0 ? 0.0 : std::sqrt(std::max(0.0, (1.0 - lambda) / lambda));
  if (large_arc == sweep) factor = -factor;
  const double cx1 = factor * (y1 / ry) * rx;
  const double cy1 = -factor * (x1 / rx) * ry;
  // Step 3: the centre (F.6.5.3).
  const Vec2 mid = 0.5 * (from + to);
  s.centre = Vec2(s.cos_phi * cx1 - s.sin_phi * cy1, s.sin_phi * cx1 + s.cos_phi * cy1) + mid;
  // Step 4: theta1 and dtheta (F.6.5.5, F.6.5.6).
  const Vec2 u((x1 - cx1) / rx, (y1 - cy1) / ry);
  const Vec2 v((-x1 - cx1) / rx, (-y1 - cy1) / ry);
  s.theta1 = angleOf(u);
  double dtheta = signedAngle(u, v);
  if (!sweep && dtheta > 0.0) dtheta -= 2.0 * std::numbers::pi;
  if (sweep && dtheta < 0.0) dtheta += 2.0 * std::numbers::pi;
  s.dtheta = dtheta;
  s.rx = rx;
  s.ry = ry;
  return s;
}

/// Appends the points of `segment` after its start: evenly spread in (chord-estimated)
/// arc length, at most `max_spacing` apart, at least `min_pieces` pieces, the exact end
/// point last. Each point is evaluated on the segment itself; the chord-length table
/// only chooses the parameters. A segment of zero length adds nothing; one whose length
/// overflows a double adds nothing and returns false.
/// Thrown when an element would flatten to more than ReadLimits::max_svg_points.
struct TooManyPoints {};

bool appendFlattened(const Segment& segment, double max_spacing, std::size_t max_points, std::vector<Vec2>& out) {
  const int min_pieces = segment.kind == Segment::Kind::kLine ? 1 : kMinCurvePieces;
  std::vector<double> cumulative;
  const auto tabulate = [&](int steps) {
    cumulative.assign(static_cast<std::size_t>(steps) + 1, 0.0);
    Vec2 previous = segment.at(0.0);
    for (int k = 1; k <= steps; ++k) {
      const Vec2 q = segment.at(static_cast<double>(k) / steps);
      cumulative[k] = cumulative[k - 1] + (q - previous).norm();
      previous = q;
    }
    return cumulative.back();
  };
  const auto piecesFor = [&](double length) {
    const double by_spacing = max_spacing > 0.0 ? std::ceil(length / max_spacing) : 0.0;
    return std::max(min_pieces, static_cast<int>(std::min(by_spacing, 1e8)));
  };
  int steps = kLengthTableSteps;
  double length = tabulate(steps);
  if (!std::isfinite(length)) return false;  // and NaN pieces below would be undefined
  if (!(length > 0.0)) return true;
  int pieces = piecesFor(length);
  // (before the length table and the points cost memory and time in proportion)
  if (out.size() + static_cast<std::size_t>(pieces) > max_points) throw TooManyPoints{};
  if (segment.kind != Segment::Kind::kLine && 4 * pieces > steps) {
    steps = 4 * pieces;
    length = tabulate(steps);
    pieces = piecesFor(length);
    if (out.size() + static_cast<std::size_t>(pieces) > max_points) throw TooManyPoints{};
  }
  for (int i = 1; i < pieces; ++i) {
    const double target = length * i / pieces;
    const auto above = std::upper_bound(cumulative.begin(), cumulative.end(), target);
    const std::size_t k = std::clamp<std::size_t>(static_cast<std::size_t>(above - cumulative.begin()), 1,
                                                  cumulative.size() - 1) - 1;
    const double step = cumulative[k + 1] - cumulative[k];
    const double fraction = step > 0.0 ? (target - cumulative[k]) / step : 0.0;
    out.push_back(segment.at((static_cast<double>(k) + fraction) / steps));
  }
  out.push_back(segment.endPoint());
  return true;
}

/// The strokes of one SVG element: its drawn subpaths, flattened with a spacing taken
/// from the bounding box of all of them. Returns false (and adds nothing) if the extent
/// of the element, or of one of its segments, overflows a double: no spacing can be
/// derived from it (coordinates near 1e308 that are each finite). Throws TooManyPoints
/// past `max_points` points in all.
bool flattenElement(const std::vector<Subpath>& subpaths, std::size_t max_points, std::vector<Stroke>& strokes) {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = -lo;
  for (const Subpath& sub : subpaths) {
    if (!sub.drawn) continue;
    lo = lo.cwiseMin(sub.start);
    hi = hi.cwiseMax(sub.start);
    for (const Segment& seg : sub.segments)
      for (int k = 1; k <= kBoxSamplesPerSegment; ++k) {
        const Vec2 q = seg.at(static_cast<double>(k) / kBoxSamplesPerSegment);
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
      }
  }
  if (!(lo.x() <= hi.x())) return true;  // nothing drawn
  const double diagonal = (hi - lo).norm();
  if (!std::isfinite(diagonal)) return false;
  const double max_spacing = kMaxSpacingFraction * diagonal;  // 0 for a single point: min pieces only
  const double same_point = 1e-12 * diagonal;

  std::vector<Stroke> element_strokes;
  std::size_t total = 0;
  for (const Subpath& sub : subpaths) {
    if (!sub.drawn) continue;
    std::vector<Vec2> points{sub.start};
    const std::size_t room = max_points - std::min(total, max_points);
    for (const Segment& seg : sub.segments)
      if (!appendFlattened(seg, max_spacing, room, points)) return false;
    if (sub.closed && points.size() > 1) {
      if ((points.back() - sub.start).norm() <= same_point) {
        points.pop_back();  // the path came back to its start itself
      } else {
        if (!appendFlattened(lineSegment(points.back(), sub.start), max_spacing, room + 1, points)) return false;
        points.pop_back();  // the start, already first
      }
    }
    total += points.size();
    Stroke stroke;
    stroke.samples.reserve(points.size());
    for (const Vec2& q : points) stroke.samples.push_back(StrokeSample{q});
    element_strokes.push_back(std::move(stroke));
  }
  for (Stroke& stroke : element_strokes) strokes.push_back(std::move(stroke));
  return true;
}

// ------------------------------------------------------------------ SVG path data

/// A number in SVG syntax at `pos`: sign, digits, an optional fraction and exponent,
/// read greedily, so "1.5.5" is 1.5 then .5 and "1e-3-2" is 1e-3 then -2. Advances
/// `pos` past it; nullopt (pos unchanged) if there is no finite number there.
std::optional<double> scanSvgNumber(std::string_view data, std::size_t& pos) {
  std::size_t i = pos;
  if (i < data.size() && (data[i] == '+' || data[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < data.size() && isDigit(data[i])) ++i, ++digits;
  if (i < data.size() && data[i] == '.') {
    ++i;
    while (i < data.size() && isDigit(data[i])) ++i, ++digits;
  }
  if (digits == 0) return std::nullopt;
  if (i < data.size() && (data[i] == 'e' || data[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < data.size() && (data[j] == '+' || data[j] == '-')) ++j;
    if (j < data.size() && isDigit(data[j])) {
      while (j < data.size() && isDigit(data[j])) ++j;
      i = j;
    }
  }
  const std::optional<double> value = parseNumber(data.substr(pos, i - pos));
  if (!value || !std::isfinite(*value)) return std::nullopt;
  pos = i;
  return value;
}

/// Reads path data (SVG 1.1 section 8.3) into subpaths. On malformed data throws with
/// the position (offset in `data`) of the first character it could not read.
class PathDataReader {
 public:
  struct Error {
    std::size_t offset;          // in the data
    const char* why = nullptr;   // said after the excerpt, if not plain syntax
  };

  explicit PathDataReader(std::string_view data) : m_data(data) {}

  std::vector<Subpath> read() {
    char command = 0;  // the command whose arguments may repeat implicitly; 0 before the first
    while (true) {
      skipSpace();
      if (m_pos == m_data.size()) break;
      const char c = m_data[m_pos];
      if (std::isalpha(static_cast<unsigned char>(c))) {
        ++m_pos;
        command = c;
      } else {
        // An implicit repetition of the last command, possibly after one comma (which
        // the first number() takes).
        std::size_t next = m_pos;
        if (c == ',') {
          ++next;
          while (next < m_data.size() && isSpace(m_data[next])) ++next;
        }
        if (command == 0 || command == 'Z' || command == 'z' || !startsNumber(next)) throw Error{m_pos};
        if (command == 'M') command = 'L';
        if (command == 'm') command = 'l';
      }
      executeCommand(command);
    }
    finishSubpath();
    return std::move(m_subpaths);
  }

 private:
  void skipSpace() {
    while (m_pos < m_data.size() && isSpace(m_data[m_pos])) ++m_pos;
  }

  bool startsNumber(std::size_t at) const {
    if (at >= m_data.size()) return false;
    const char c = m_data[at];
    return isDigit(c) || c == '.' || c == '-' || c == '+';
  }

  /// Whitespace with at most one comma, then a number.
  double number() {
    separator();
    const std::size_t start = m_pos;
    const std::optional<double> value = scanSvgNumber(m_data, m_pos);
    if (!value) throw Error{start};
    return *value;
  }

  /// An arc flag: a single '0' or '1', which needs no separator after it.
  bool flag() {
    separator();
    if (m_pos < m_data.size() && (m_data[m_pos] == '0' || m_data[m_pos] == '1')) return m_data[m_pos++] == '1';
    throw Error{m_pos};
  }

  void separator() {
    skipSpace();
    if (m_pos < m_data.size() && m_data[m_pos] == ',') {
      ++m_pos;
      skipSpace();
    }
  }

  Vec2 point(bool relative) {
    const std::size_t start = m_pos;
    const double x = number();
    const double y = number();
    return finite(relative ? m_current + Vec2(x, y) : Vec2(x, y), start);
  }

  /// Each number is finite, but a relative step or a reflected control point can still
  /// pass the largest double.
  static Vec2 finite(const Vec2& p, std::size_t offset) {
    if (!allFinite(p)) throw Error{offset, "coordinate out of range"};
    return p;
  }

  void finishSubpath() {
    if (m_open && m_subpath.drawn) m_subpaths.push_back(std::move(m_subpath));
    m_subpath = Subpath{};
    m_open = false;
  }

  /// Before a drawing command: the subpath it extends (a new one at the last start
  /// point right after a Z). Path data must begin with a moveto.
  Subpath& drawing(std::size_t command_offset) {
    if (!m_open) {
      if (!m_started) throw Error{command_offset};
      m_subpath = Subpath{};
      m_subpath.start = m_current;
      m_open = true;
    }
    m_subpath.drawn = true;
    return m_subpath;
  }

  void executeCommand(char command) {
    const std::size_t offset = m_pos > 0 ? m_pos - 1 : 0;
    const bool relative = std::islower(static_cast<unsigned char>(command)) != 0;
    const char previous = m_previous;
    m_previous = static_cast<char>(std::toupper(static_cast<unsigned char>(command)));
    switch (m_previous) {
      case 'M': {
        const Vec2 p = point(relative);
        finishSubpath();
        m_subpath.start = p;
        m_open = true;
        m_started = true;
        m_current = p;
        return;
      }
      case 'Z': {
        if (!m_started) throw Error{offset};
        if (m_open) {
          m_subpath.closed = true;
          m_subpath.drawn = true;
          m_current = m_subpath.start;
          finishSubpath();
        }
        return;
      }
      case 'L': {
        const Vec2 p = point(relative);
        addLine(p, offset);
        return;
      }
      case 'H': {
        const double x = number();
        addLine(finite(Vec2(relative ? m_current.x() + x : x, m_current.y()), offset), offset);
        return;
      }
      case 'V': {
        const double y = number();
        addLine(finite(Vec2(m_current.x(), relative ? m_current.y() + y : y), offset), offset);
        return;
      }
      case 'C':
      case 'S': {
        Vec2 c1;
        if (m_previous == 'C') c1 = point(relative);
        else c1 = finite((previous == 'C' || previous == 'S') ? Vec2(2.0 * m_current - m_last_control) : m_current, offset);
        const Vec2 c2 = point(relative);
        const Vec2 p = point(relative);
        Segment s;
        s.kind = Segment::Kind::kCubic;
        s.p = {m_current, c1, c2, p};
        drawing(offset).segments.push_back(s);
        m_last_control = c2;
        m_current = p;
        return;
      }
      case 'Q':
      case 'T': {
        Vec2 c;
        if (m_previous == 'Q') c = point(relative);
        else c = finite((previous == 'Q' || previous == 'T') ? Vec2(2.0 * m_current - m_last_control) : m_current, offset);
        const Vec2 p = point(relative);
        Segment s;
        s.kind = Segment::Kind::kQuad;
        s.p = {m_current, c, p, p};
        drawing(offset).segments.push_back(s);
        m_last_control = c;
        m_current = p;
        return;
      }
      case 'A': {
        const double rx = number();
        const double ry = number();
        const double phi = number();
        const bool large_arc = flag();
        const bool sweep = flag();
        const Vec2 p = point(relative);
        Subpath& sub = drawing(offset);
        if (const std::optional<Segment> arc = arcSegment(m_current, rx, ry, phi, large_arc, sweep, p))
          sub.segments.push_back(*arc);
        m_current = p;
        return;
      }
      default:
        throw Error{offset};
    }
  }

  void addLine(const Vec2& p, std::size_t offset) {
    drawing(offset).segments.push_back(lineSegment(m_current, p));
    m_current = p;
  }

  std::string_view m_data;
  std::size_t m_pos = 0;
  Vec2 m_current = Vec2::Zero();
  Vec2 m_last_control = Vec2::Zero();  // second control point of the last C/S, control of the last Q/T
  char m_previous = 0;                 // upper-case letter of the last command executed
  bool m_started = false;              // a moveto has been read
  bool m_open = false;                 // m_subpath is in progress
  Subpath m_subpath;
  std::vector<Subpath> m_subpaths;
};

/// The coordinate pairs of a points attribute as one subpath of straight pieces
/// (nullopt if fewer than two pairs: nothing is drawn). Throws PathDataReader::Error.
std::optional<Subpath> readPointList(std::string_view data, bool closed) {
  std::vector<double> numbers;
  std::size_t i = 0;
  const auto skip = [&] {
    while (i < data.size() && isSpace(data[i])) ++i;
  };
  skip();
  std::size_t last_start = 0;
  while (i < data.size()) {
    last_start = i;
    const std::optional<double> value = scanSvgNumber(data, i);
    if (!value) throw PathDataReader::Error{i};
    numbers.push_back(*value);
    skip();
    if (i < data.size() && data[i] == ',') {
      ++i;
      skip();
      if (i == data.size()) throw PathDataReader::Error{i - 1, "trailing comma"};
    }
  }
  if (numbers.size() % 2 != 0) throw PathDataReader::Error{last_start, "odd number of coordinates"};
  if (numbers.size() < 4) return std::nullopt;
  Subpath sub;
  sub.start = Vec2(numbers[0], numbers[1]);
  sub.drawn = true;
  sub.closed = closed;
  Vec2 current = sub.start;
  for (std::size_t k = 2; k + 1 < numbers.size(); k += 2) {
    const Vec2 p(numbers[k], numbers[k + 1]);
    sub.segments.push_back(lineSegment(current, p));
    current = p;
  }
  return sub;
}

// ------------------------------------------------------------------ SVG document

/// A minimal scanner of SVG text: enough of XML to find the shape elements and their
/// attributes without being fooled by comments, CDATA, declarations or quoted '>'.
class SvgScanner {
 public:
  SvgScanner(std::string_view text, const std::string& name, const ReadLimits& limits)
      : m_text(text), m_name(name), m_limits(limits) {
    for (std::size_t i = 0; i < text.size(); ++i)
      if (endsLine(text, i)) m_line_starts.push_back(i + 1);
  }

  std::vector<Stroke> read() {
    std::vector<Stroke> strokes;
    int hidden_depth = 0;  // inside <defs> and friends: not drawn as written
    std::size_t depth = 0;  // open elements
    std::size_t i = 0;
    while ((i = m_text.find('<', i)) != std::string_view::npos) {
      const std::string_view rest = m_text.substr(i);
      if (rest.starts_with("<!--")) {
        i = skipPast(i, "-->", "unterminated comment");
      } else if (rest.starts_with("<![CDATA[")) {
        i = skipPast(i, "]]>", "unterminated CDATA section");
      } else if (rest.starts_with("<?")) {
        i = skipPast(i, "?>", "unterminated processing instruction");
      } else if (rest.starts_with("<!")) {
        i = skipDeclaration(i);
      } else if (rest.starts_with("</")) {
        const std::size_t end = m_text.find('>', i);
        if (end == std::string_view::npos) failAt(m_name, lineOf(i), "unterminated end tag");
        const std::string_view tag = localName(trim(m_text.substr(i + 2, end - i - 2)));
        if (hidden_depth > 0 && isHidden(tag)) --hidden_depth;
        if (depth > 0) --depth;
        i = end + 1;
      } else {
        bool open = false;
        const std::size_t from = i;
        i = readElement(i, hidden_depth, open, strokes);
        if (open && ++depth > m_limits.max_nesting)
          failAt(m_name, lineOf(from), "elements nested deeper than " + std::to_string(m_limits.max_nesting) +
                                           limitNote(m_limits.max_nesting, "--max-nesting"));
        if (strokes.size() > m_limits.max_strokes)
          failAt(m_name, lineOf(from), "more than " + std::to_string(m_limits.max_strokes) + " strokes" +
                                           limitNote(m_limits.max_strokes, "--max-strokes"));
      }
    }
    if (strokes.empty()) failFile(m_name, "no points (no <path>, <polyline> or <polygon> with coordinates)");
    return strokes;
  }

 private:
  struct Attribute {
    std::string_view name;
    std::string_view raw;  // as written, between the quotes
    std::size_t offset;    // of raw in the text
  };

  static std::string_view localName(std::string_view qualified) {
    const std::size_t colon = qualified.rfind(':');
    return colon == std::string_view::npos ? qualified : qualified.substr(colon + 1);
  }

  static bool isHidden(std::string_view tag) {
    return tag == "defs" || tag == "clipPath" || tag == "mask" || tag == "symbol" || tag == "marker" ||
           tag == "pattern";
  }

  std::size_t lineOf(std::size_t offset) const {
    // The number of line starts at or before the offset is its 1-based line.
    return static_cast<std::size_t>(std::upper_bound(m_line_starts.begin(), m_line_starts.end(), offset) -
                                    m_line_starts.begin());
  }

  std::size_t skipPast(std::size_t from, std::string_view terminator, const char* what) const {
    const std::size_t end = m_text.find(terminator, from);
    if (end == std::string_view::npos) failAt(m_name, lineOf(from), what);
    return end + terminator.size();
  }

  /// <!DOCTYPE ...> and the like: up to the '>' outside quotes and the internal subset.
  std::size_t skipDeclaration(std::size_t from) const {
    int depth = 0;
    char quote_char = 0;
    for (std::size_t i = from + 2; i < m_text.size(); ++i) {
      const char c = m_text[i];
      if (quote_char) {
        if (c == quote_char) quote_char = 0;
      } else if (c == '"' || c == '\'') {
        quote_char = c;
      } else if (c == '[') {
        ++depth;
      } else if (c == ']') {
        --depth;
      } else if (c == '>' && depth <= 0) {
        return i + 1;
      } else if (c == '<' && m_text.substr(i).starts_with("<!--")) {
        i = skipPast(i, "-->", "unterminated comment") - 1;
      }
    }
    failAt(m_name, lineOf(from), "unterminated declaration");
  }

  /// A start tag at `from`: reads its attributes and, for a shape outside hidden
  /// containers, its strokes. Returns the offset after the tag (or after the raw
  /// content of <script> / <style>).
  std::size_t readElement(std::size_t from, int& hidden_depth, bool& open, std::vector<Stroke>& strokes) {
    std::size_t i = from + 1;
    const auto nameEnd = [&](std::size_t k) {
      while (k < m_text.size() && !isSpace(m_text[k]) && m_text[k] != '>' && m_text[k] != '/' && m_text[k] != '=')
        ++k;
      return k;
    };
    std::size_t end = nameEnd(i);
    const std::string_view qualified = m_text.substr(i, end - i);
    const std::string_view tag = localName(qualified);
    i = end;
    std::vector<Attribute> attributes;
    bool self_closing = false;
    while (true) {
      while (i < m_text.size() && isSpace(m_text[i])) ++i;
      if (i >= m_text.size()) failAt(m_name, lineOf(from), "unterminated tag <" + std::string(qualified));
      if (m_text[i] == '>') {
        ++i;
        break;
      }
      if (m_text.substr(i).starts_with("/>")) {
        i += 2;
        self_closing = true;
        break;
      }
      end = nameEnd(i);
      if (end == i) failAt(m_name, lineOf(i), "unexpected '" + quote(m_text.substr(i, 1)) + "' in a tag");
      Attribute attribute{m_text.substr(i, end - i), {}, end};
      i = end;
      while (i < m_text.size() && isSpace(m_text[i])) ++i;
      if (i < m_text.size() && m_text[i] == '=') {
        ++i;
        while (i < m_text.size() && isSpace(m_text[i])) ++i;
        if (i < m_text.size() && (m_text[i] == '"' || m_text[i] == '\'')) {
          const std::size_t close = m_text.find(m_text[i], i + 1);
          if (close == std::string_view::npos) failAt(m_name, lineOf(i), "unterminated attribute value");
          attribute.offset = i + 1;
          attribute.raw = m_text.substr(i + 1, close - i - 1);
          i = close + 1;
        } else {  // not XML, but read an unquoted value up to a space or '>'
          std::size_t k = i;
          while (k < m_text.size() && !isSpace(m_text[k]) && m_text[k] != '>') ++k;
          attribute.offset = i;
          attribute.raw = m_text.substr(i, k - i);
          i = k;
        }
      }
      attributes.push_back(attribute);
    }

    open = !self_closing;
    if (!self_closing && (tag == "script" || tag == "style")) {
      const std::string closing = "</" + std::string(qualified);
      const std::size_t close = m_text.find(closing, i);
      if (close == std::string_view::npos) failAt(m_name, lineOf(from), "unterminated <" + std::string(qualified) + ">");
      return close;
    }
    if (isHidden(tag)) {
      if (!self_closing) ++hidden_depth;
      return i;
    }
    if (hidden_depth > 0) return i;

    const bool is_path = tag == "path";
    if (!is_path && tag != "polyline" && tag != "polygon") return i;
    const std::string_view wanted = is_path ? "d" : "points";
    for (const Attribute& attribute : attributes) {
      if (attribute.name != wanted) continue;
      std::string decoded;
      const bool has_references = attribute.raw.find('&') != std::string_view::npos;
      if (has_references) decoded = decodeReferences(attribute.raw, from);
      const std::string_view data = has_references ? std::string_view(decoded) : attribute.raw;
      try {
        std::vector<Subpath> subpaths;
        if (is_path) {
          subpaths = PathDataReader(data).read();
        } else if (std::optional<Subpath> sub = readPointList(data, tag == "polygon")) {
          subpaths.push_back(std::move(*sub));
        }
        if (!flattenElement(subpaths, m_limits.max_svg_points, strokes))
          throw PathDataReader::Error{0, "coordinates too large to flatten: distances overflow a double"};
      } catch (const TooManyPoints&) {
        failAt(m_name, lineOf(from),
               "<" + std::string(qualified) + "> flattens to more than " + std::to_string(m_limits.max_svg_points) +
                   " points" + limitNote(m_limits.max_svg_points, "--max-svg-points"));
      } catch (const PathDataReader::Error& error) {
        const std::size_t line = has_references ? lineOf(from) : lineOf(attribute.offset + error.offset);
        failAt(m_name, line,
               std::string(is_path ? "bad path data" : "bad points data") + " near '" +
                   quote(data.substr(std::min(error.offset, data.size()))) + "' in <" + std::string(qualified) + ">" +
                   (error.why ? std::string(" (") + error.why + ")" : std::string()));
      }
    }
    return i;
  }

  /// Character and predefined entity references of an attribute value.
  std::string decodeReferences(std::string_view raw, std::size_t element) const {
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const std::size_t semicolon = raw.find(';', i);
      if (semicolon == std::string_view::npos) failAt(m_name, lineOf(element), "bad character reference");
      const std::string_view entity = raw.substr(i + 1, semicolon - i - 1);
      if (entity == "lt") out += '<';
      else if (entity == "gt") out += '>';
      else if (entity == "amp") out += '&';
      else if (entity == "quot") out += '"';
      else if (entity == "apos") out += '\'';
      else if (entity.starts_with('#')) {
        const bool hex = entity.size() > 1 && (entity[1] == 'x' || entity[1] == 'X');
        const std::string_view digits = entity.substr(hex ? 2 : 1);
        unsigned code = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
        if (ec != std::errc{} || end != digits.data() + digits.size() || digits.empty())
          failAt(m_name, lineOf(element), "bad character reference '&" + quote(entity) + ";'");
        // Path data is ASCII; anything else is a space here (and then a syntax error
        // if it is not a separator).
        out += code < 128 ? static_cast<char>(code) : ' ';
      } else {
        failAt(m_name, lineOf(element), "unknown entity '&" + quote(entity) + ";'");
      }
      i = semicolon;
    }
    return out;
  }

  std::string_view m_text;
  const std::string& m_name;
  const ReadLimits& m_limits;
  std::vector<std::size_t> m_line_starts{0};
};

std::string readFile(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw PointFileError("cannot open " + name + ": is a directory");
  std::FILE* file = std::fopen(name.c_str(), "rb");
  if (!file) throw PointFileError("cannot open " + name + ": " + std::strerror(errno));
  std::string text;
  std::array<char, 1 << 16> buffer;
  std::size_t got = 0;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), file)) > 0) text.append(buffer.data(), got);
  const bool failed = std::ferror(file) != 0;
  const int error = errno;
  std::fclose(file);
  if (failed) throw PointFileError("cannot read " + name + ": " + std::strerror(error));
  return text;
}

}  // namespace

std::vector<Stroke> readStrokes(const std::filesystem::path& path, const ReadLimits& limits) {
  return parseStrokes(readFile(path), path.string(), limits);
}

std::vector<Stroke> parseStrokes(const std::string& text, const std::string& name, const ReadLimits& limits) {
  const std::string extension = lower(std::filesystem::path(name).extension().string());
  if (extension == ".json") return parseJson(text, name, limits);
  if (extension == ".svg") return SvgScanner(text, name, limits).read();
  if (extension == ".dat") {
    std::vector<Stroke> profiles = parseDelimited(text, name, /*airfoil=*/true, limits);
    for (Stroke& s : profiles) s.profile = true;
    return profiles;
  }
  return parseDelimited(text, name, /*airfoil=*/false, limits);
}

}  // namespace la
