#pragma once
// Readers of the stroke and profile files lafit and the GUI import (DESIGN.md section 5):
//  - CSV / TXT: one point per line `x,y[,t[,pressure]]` (commas, spaces, tabs or
//    semicolons), `#` comments and one header line allowed (known names x, y, t/time,
//    p/pressure pick the columns; any other header is skipped and columns stay
//    positional), a blank line between strokes (lines end with LF, CRLF or CR; one
//    kind of separator per line, so decimal commas are refused); Omniglot's START /
//    BREAK lines are understood. NaN or infinite values are errors;
//  - airfoil `.dat` (Selig): a name line, then `x y` lines; one profile (blank lines
//    ignored; Lednicer files are refused with a message saying so), read with
//    Stroke::profile set: its only corner is its trailing edge;
//  - the project's stroke JSON: {"strokes": [{"points": [[x, y], ...], "t": [...],
//    "pressure": [...], "profile": true}, ...]} (t, pressure and profile optional, t
//    and pressure one entry per point, null for unknown);
//  - SVG: <path> (M/L/H/V/C/S/Q/T/A/Z, absolute and relative) and <polyline>/<polygon>
//    elements, flattened to points on the exact curves at most 0.5% of the element's
//    bounding-box diagonal apart; each subpath is a stroke. A closed subpath (Z,
//    <polygon>) does not repeat its start point. Transforms, viewBox and units are
//    ignored (coordinates as written), as are other shapes and anything in <defs>.
// Input over a limit (ReadLimits) throws PointFileError naming the limit and its flag.
// Malformed input throws PointFileError naming the file, the line and what is wrong:
// "<file>:<line>: <what>" ("<file>:<line>:<column>: ..." for JSON syntax, "<file>: ..."
// for JSON schema errors, which name the stroke and key, and for "no points").
// Details of each format are at the top of point_file.cpp.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "fitting/stroke.h"

namespace la {

struct PointFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a reader takes before it refuses the file: checked as the file is read, before
/// the work its size would cost (a 75 KB SVG path of back-and-forth curves flattens to
/// millions of points). The message names the limit and lafit's flag that raises it.
struct ReadLimits {
  std::size_t max_points_per_stroke = 1'000'000;  // lafit --max-points
  std::size_t max_strokes = 100'000;              // lafit --max-strokes
  std::size_t max_svg_points = 200'000;           // points one SVG element flattens to; lafit --max-svg-points
  std::size_t max_nesting = 256;                  // JSON arrays/objects, SVG elements; lafit --max-nesting
};

/// Reads every stroke of the file; the format is chosen by extension, ignoring case
/// (.csv .txt .dat .json .svg; anything else is read as CSV/TXT). Strokes come in file
/// order; a missing or unreadable file throws "cannot open <path>: <reason>".
std::vector<Stroke> readStrokes(const std::filesystem::path& path, const ReadLimits& limits = {});

/// The same from text already in memory; `name` is used in messages and its extension
/// picks the format.
std::vector<Stroke> parseStrokes(const std::string& text, const std::string& name, const ReadLimits& limits = {});

}  // namespace la
