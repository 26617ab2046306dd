#pragma once
// The rows `data_benchmark --rows=FILE` writes (one CSV row per fitted stroke: its data
// set, where it is, its fit time and figures) and what is read off them: nearest-rank
// percentiles, and per stroke the fastest time over several runs. data_benchmark writes
// them; compare_rows reads them back to weigh one build against another (the machine's
// speed drifts from run to run, so a time is the fastest of interleaved runs, and the
// model selection's paths move single strokes that the distributions hide).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace la::test {

struct StrokeRow {
  std::string data_set;
  std::string stroke;  // file (relative to the data folder) and stroke index
  double ms = 0.0;     // fit time
  int segments = 0;
  int extrema_dense = 0;
  double deviation = 0.0;  // max_dev / tolerance
  double radius = 0.0;     // min_radius / tolerance
};

inline constexpr const char* kRowsHeader = "data_set,stroke,ms,segments,extrema_dense,max_dev_over_tol,min_radius_over_tol";

// A CSV field, quoted (RFC 4180: a quote inside doubled).
inline std::string quoted(const std::string& field) {
  std::string out = "\"";
  for (char c : field) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

// One row, newline included (figures to 6 significant digits, as compared).
inline std::string rowCsv(const StrokeRow& r) {
  char figures[96];
  std::snprintf(figures, sizeof figures, ",%.3f,%d,%d,%.6g,%.6g\n", r.ms, r.segments, r.extrema_dense, r.deviation, r.radius);
  return quoted(r.data_set) + "," + quoted(r.stroke) + figures;
}

// The fields of one CSV line (quoted or not); what is wrong with it, or nullptr.
inline const char* csvFields(const std::string& line, std::vector<std::string>& fields) {
  fields.assign(1, "");
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ',') {
      fields.emplace_back();
    } else if (c == '"' && fields.back().empty()) {
      for (++i;; ++i) {
        if (i >= line.size()) return "a quoted field is not closed";
        if (line[i] != '"') fields.back() += line[i];
        else if (i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
        else break;
      }
      if (i + 1 < line.size() && line[i + 1] != ',') return "text after a quoted field";
    } else {
      fields.back() += c;
    }
  }
  return nullptr;
}

// `text`, all of it, as an int or a double into `out`; false if it is not one.
template <typename T>
bool wholeNumber(const std::string& text, T& out) {
  std::size_t used = 0;
  try {
    if constexpr (std::is_same_v<T, int>) out = std::stoi(text, &used);
    else out = std::stod(text, &used);
  } catch (const std::logic_error&) {
    return false;
  }
  return used == text.size();
}

// The rows of a --rows file's text; throws std::runtime_error naming `file`, the line and
// what is wrong with it.
inline std::vector<StrokeRow> readRows(const std::string& text, const std::string& file) {
  std::vector<StrokeRow> rows;
  std::vector<std::string> f;
  std::size_t line_number = 0;
  auto fail = [&](const std::string& what) {
    throw std::runtime_error(file + ":" + std::to_string(line_number) + ": " + what);
  };
  auto number = [&](const std::string& field, const char* name, auto& out) {
    if (!wholeNumber(field, out)) fail(std::string(name) + " is not a number: \"" + field + "\"");
  };
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string line = text.substr(start, end - start);
    start = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_number == 1) {
      if (line != kRowsHeader) fail(std::string("not a data_benchmark --rows file (its header is \"") + kRowsHeader + "\")");
      continue;
    }
    if (line.empty()) continue;
    if (const char* wrong = csvFields(line, f)) fail(wrong);
    if (f.size() != 7) fail("7 fields expected, " + std::to_string(f.size()) + " found");
    StrokeRow r{f[0], f[1]};
    number(f[2], "ms", r.ms);
    number(f[3], "segments", r.segments);
    number(f[4], "extrema_dense", r.extrema_dense);
    number(f[5], "max_dev_over_tol", r.deviation);
    number(f[6], "min_radius_over_tol", r.radius);
    rows.push_back(std::move(r));
  }
  if (line_number == 0) throw std::runtime_error(file + ": empty");
  return rows;
}

// Nearest rank: the smallest value with at least the fraction p of the values at or below
// it (the 1e-9 keeps a product such as 0.9 * 10 from rounding up to the next rank).
inline double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size()) - 1e-9));
  return values[std::max<std::size_t>(rank, 1) - 1];
}

// Whether two rows of one stroke have the same figures (all but the time: a fit is
// deterministic).
inline bool sameFigures(const StrokeRow& a, const StrokeRow& b) {
  return a.segments == b.segments && a.extrema_dense == b.extrema_dense && a.deviation == b.deviation && a.radius == b.radius;
}

// Several runs of one build: per stroke (in the first run's order, then any that only
// later runs have) its row with the fastest time, and the strokes whose figures differ
// between runs.
struct FastestRows {
  std::vector<StrokeRow> rows;
  std::vector<std::string> differing;
};

inline FastestRows fastestOf(const std::vector<std::vector<StrokeRow>>& runs) {
  FastestRows out;
  std::map<std::pair<std::string, std::string>, std::size_t> index;
  for (const std::vector<StrokeRow>& run : runs)
    for (const StrokeRow& r : run) {
      const auto [it, fresh] = index.try_emplace({r.data_set, r.stroke}, out.rows.size());
      if (fresh) {
        out.rows.push_back(r);
        continue;
      }
      StrokeRow& kept = out.rows[it->second];
      if (!sameFigures(kept, r) && std::find(out.differing.begin(), out.differing.end(), r.stroke) == out.differing.end())
        out.differing.push_back(r.stroke);
      kept.ms = std::min(kept.ms, r.ms);
    }
  return out;
}

}  // namespace la::test
