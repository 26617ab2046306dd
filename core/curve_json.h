#pragma once
// Curves in the shared intrinsic-segment JSON format (DESIGN.md section 5).
//
// A segment is
//   {"alpha": a, "length": L, "start": [x, y], "theta0": t, "kappa_start": k0,
//    "kappa_end": k1}
// plus "corner": true when it starts at a deliberate G0 corner. An infinite alpha
// (circle or line) is the string "inf" or "-inf", since JSON has no infinity. A
// curve is {"segments": [...], "closed": bool}; a document holds one curve, or
// several as {"curves": [curve or {"error": "why"}, ...]}, one entry per input stroke.
// Documents name their version at the top: "format": "lafair-curves/1"; one without it
// (written before the key existed, or by another tool) is read as version 1, one of a
// later version is refused with both versions named.
//
// Numbers round-trip exactly: nlohmann::json writes a double with the shortest
// digits that read back to the same bits (Grisu2, at most 17 significant digits)
// and reads with a correctly rounded strtod. Keys are written in alphabetical order
// (nlohmann::json keeps objects sorted); readers must not depend on key order.
//
// Reading is strict about what it needs and ignores everything else: keys a writer
// adds for people or other tools (metrics, samples, stages) are skipped. Each
// segment must satisfy LaSegment's constructor; continuity between segments is not
// checked here. Malformed input throws CurveFormatError with a message that starts
// with where the problem is: "curves[2].segments[5]: missing key \"length\"", or for
// a JSON syntax error "<file>: line N, column M: <parser message>".

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/curve.h"
#include "core/la_segment.h"

namespace la {

/// A curve file that is not valid JSON or not in the shared format.
class CurveFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One entry of a curves document: the curve of a stroke, or why it has none.
struct CurveOrError {
  std::optional<Curve> curve;
  std::string error;  // why there is no curve; ignored (not written) when curve is set
};

/// The version of the format this code writes and reads.
inline constexpr const char* kCurvesFormat = "lafair-curves/1";

/// Names the format at the top of a document (a single curve or {"curves": ...}).
void stampCurvesFormat(nlohmann::json& document);

nlohmann::json segmentToJson(const LaSegment& segment, bool corner = false);

/// `where` locates the object in the document for error messages, e.g.
/// "curves[2].segments[5]". Ignores "corner" (see curveFromJson) and unknown keys.
LaSegment segmentFromJson(const nlohmann::json& json, const std::string& where);

/// {"segments": [...], "closed": bool}.
nlohmann::json curveToJson(const Curve& curve);

/// Needs a non-empty "segments" array; "closed" and each segment's "corner" are
/// optional (default false) but must be booleans when present. `where` may be
/// empty (a single-curve document): locations then start at "segments[i]".
Curve curveFromJson(const nlohmann::json& json, const std::string& where);

/// Parses a document: {"curves": [...]} with curve and {"error": "why"} entries,
/// or a single curve {"segments": ...} (also accepted as {"curve": {...}}, and a
/// single {"error": "why"}, as shared/tools/lacheck.py does), giving one entry.
/// Error messages start with "<source_name>: ".
std::vector<CurveOrError> parseCurvesDocument(std::string_view text,
                                              const std::string& source_name);

/// readFile + parseCurvesDocument with the path as source name. Throws
/// std::runtime_error when the file cannot be read, CurveFormatError when its
/// contents are malformed.
std::vector<CurveOrError> readCurvesFile(const std::filesystem::path& path);

/// Always the {"curves": [...]} form, indented by 2, ending in a newline.
std::string curvesDocumentToString(const std::vector<CurveOrError>& curves);

/// curvesDocumentToString written with writeFileAtomically.
void writeCurvesFile(const std::filesystem::path& path, const std::vector<CurveOrError>& curves);

}  // namespace la
