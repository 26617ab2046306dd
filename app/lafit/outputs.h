#pragma once
// Writes a command's curves to the files named by -o/--svg/--csv/--dxf, atomically.

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/lafit/cli_args.h"
#include "core/alp_curve.h"
#include "core/curve_json.h"
#include "core/geometry.h"
#include "nlohmann/json.hpp"

namespace la::cli {

/// Options every producing command accepts, for Args' `valued` set.
inline const std::set<std::string> kOutputOptions = {"-o", "--svg", "--csv", "--dxf"};
inline const std::set<std::string> kOutputFlags = {"--comb", "--y-up"};

/// A producing command's arguments: its own options and flags plus the output ones and
/// --help. On --help it prints `help` and returns std::nullopt (the command exits 0).
std::optional<Args> producingCommandArgs(const std::vector<std::string>& argv, const std::set<std::string>& valued,
                                         const std::set<std::string>& flags, const char* help);

/// `document` is the JSON written with -o (the shared curve format plus whatever the
/// command adds); `curves` and `points` feed the drawing formats.
void writeOutputs(const Args& args, const nlohmann::json& document, const std::vector<Curve>& curves,
                  const std::vector<std::vector<Vec2>>& points);

/// The same for ALP curves (app/io/curve_export.h's alpCurvesTo*); the CSV has
/// `csv_samples` samples per curve.
void writeAlpOutputs(const Args& args, const nlohmann::json& document, const std::vector<AlpCurve>& curves,
                     const std::vector<std::vector<Vec2>>& points, int csv_samples = 201);

}  // namespace la::cli
