#pragma once
// The fit options as JSON, one reader and one writer for every file that keeps them:
// the app's sketch file ("options") and lafit's output (the options a fit was made with).
// A key that is missing takes the default (files written before it existed).

#include "fitting/pipeline.h"
#include "nlohmann/json.hpp"

namespace la {

nlohmann::json fitOptionsToJson(const FitOptions& options);

/// Throws std::invalid_argument naming the key whose value has the wrong type or range.
FitOptions fitOptionsFromJson(const nlohmann::json& json);

}  // namespace la
