#pragma once
// What each fuzz target runs on one input (tests/fuzz/*_fuzz.cpp), shared with the
// regression test (tests/fuzz_regression_test.cpp) so that a kept crash input runs
// through exactly the code that found it.
//
// Each entry returns normally when the input was read (and, for fitting, fitted) or
// refused with the error the reader documents: PointFileError (app/io/point_file.h),
// CurveFormatError (core/curve_json.h), SketchFileError (app/io/sketch_file.h),
// StrokeError (fitting/stroke.h). Any other exception escapes (libFuzzer reports it
// as a crash), and so does FuzzFinding, thrown when a result breaks an invariant.

#include <stdexcept>
#include <string_view>

namespace la::fuzz {

/// A result that breaks an invariant of the code under test.
struct FuzzFinding : std::logic_error {
  using std::logic_error::logic_error;
};

/// The point-file readers: CSV/TXT and airfoil .dat (the same text as both).
void pointFile(std::string_view data);
/// The SVG reader.
void svg(std::string_view data);
/// The stroke JSON reader and the curves JSON reader (the same text as both).
void json(std::string_view data);
/// The sketch file reader (app/io/sketch_file.h).
void sketch(std::string_view data);
/// fitStroke on the first strokes the readers make of the input (format by its first
/// character), a few hundred samples each, with a time budget; its curve must be finite.
void fit(std::string_view data);

}  // namespace la::fuzz
