#pragma once
// Readers of the stroke and profile files lafit and the GUI import (DESIGN.md section 5):
//  - CSV / TXT: one point per line `x,y[,t[,pressure]]` (commas, spaces, tabs or
//    semicolons), `#` comments and one header line allowed, a blank line between strokes;
//  - airfoil `.dat` (Selig): a name line, then `x y` lines; one profile;
//  - the project's stroke JSON: {"strokes": [{"points": [[x, y], ...], "t": [...],
//    "pressure": [...]}, ...]} (t and pressure optional);
//  - SVG: <path> (M/L/H/V/C/S/Q/T/A/Z, absolute and relative) and <polyline>/<polygon>
//    elements, flattened to points; each subpath is a stroke.
// Malformed input throws PointFileError naming the file, the line and what is wrong.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "fitting/stroke.h"

namespace la {

struct PointFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Reads every stroke of the file; the format is chosen by extension (.csv .txt .dat
/// .json .svg; anything else is read as CSV/TXT).
std::vector<Stroke> readStrokes(const std::filesystem::path& path);

/// The same from text already in memory; `name` is used in messages and its extension
/// picks the format.
std::vector<Stroke> parseStrokes(const std::string& text, const std::string& name);

}  // namespace la
