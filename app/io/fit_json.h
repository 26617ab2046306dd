#pragma once
// A fitted stroke as JSON: the curve in the shared format (DESIGN.md section 5) plus
// "quality" (DESIGN.md section 6), "timings_ms" and, on request, "stages" (raw and
// cleaned points, the B-spline, the split points with their kind, each piece's alpha
// and LCG R^2). lafit writes it; the GUI's document keeps it.

#include "fitting/pipeline.h"
#include "nlohmann/json.hpp"

namespace la {

nlohmann::json qualityToJson(const QualityFigures& q);
nlohmann::json fitResultToJson(const FitResult& result, const Stroke& raw, bool with_stages);

}  // namespace la
