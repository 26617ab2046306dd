#pragma once
// ALP curves (core/alp_curve.h) in JSON. ALP curves are not LA segments, so the
// shared intrinsic-segment format (DESIGN.md section 5) cannot hold them; this is
// their own object, enough to rebuild the curve:
//   {"type": "alp", "degree": n, "control_kappa": [k_0, ..., k_n],
//    "weights": [w_0, ..., w_n] (empty for a polynomial), "length": L,
//    "start": [x, y], "theta0": t,
//    "checks": {"has_inflection": b, "monotone": b, "inflections": [s...], "extrema": [s...]}}
// Numbers round-trip exactly (see core/curve_json.h). "checks" is derived data for
// people and other tools: the reader ignores it (checkCurvature recomputes it), as it
// ignores unknown keys.

#include <string>

#include <nlohmann/json.hpp>

#include "core/alp_curve.h"
#include "core/alp_hermite.h"

namespace la {

nlohmann::json alpCurveToJson(const AlpCurve& curve, const AlpCurvatureCheck& check);

/// The curve of an object written by alpCurveToJson. Throws CurveFormatError
/// (core/curve_json.h) with a message starting with `where` (if not empty) when a key
/// is missing or of the wrong type, "type" is not "alp", "degree" does not match the
/// control curvatures, or the values do not make an AlpCurve.
AlpCurve alpCurveFromJson(const nlohmann::json& json, const std::string& where = "");

}  // namespace la
