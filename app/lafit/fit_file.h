#pragma once
// Fits every stroke of one input file: the work behind `lafit fit` and each file of
// `lafit batch`. A stroke that cannot be fitted gets an error entry; the others are
// still fitted.

#include <filesystem>
#include <string>
#include <vector>

#include "app/io/point_file.h"
#include "fitting/pipeline.h"
#include "nlohmann/json.hpp"

namespace la::cli {

struct FileFit {
  std::vector<Stroke> strokes;
  std::vector<std::optional<FitResult>> results;  // empty where the stroke failed
  std::vector<std::string> errors;                // why, per stroke ("" if fitted)
  nlohmann::json document;  // one curve object, or {"curves": [...]} for several strokes
  std::vector<Curve> curves() const;
  std::vector<std::vector<Vec2>> points() const;  // cleaned points of fitted strokes, raw of failed ones
  int failed() const;
};

/// Throws PointFileError for an unreadable file. The strokes are fitted on `jobs`
/// threads (the results do not depend on it).
FileFit fitFile(const std::filesystem::path& input, const FitOptions& options, const ReadLimits& limits,
                bool with_stages, int jobs = 1);

}  // namespace la::cli
