#include "app/lafit/fit_options.h"

#include <cmath>

namespace la::cli {
namespace {

std::size_t positiveCount(const Args& args, const std::string& flag, std::size_t fallback) {
  const double value = args.number(flag, static_cast<double>(fallback));
  if (!(value >= 1.0) || value != std::floor(value) || value > 1e15)
    throw UsageError(flag + " takes a whole number of at least 1");
  return static_cast<std::size_t>(value);
}

}  // namespace

FitOptions fitOptionsFrom(const Args& args) {
  FitOptions o;
  o.tolerance_fraction = args.number("--tolerance", o.tolerance_fraction);
  if (!(o.tolerance_fraction > 0.0)) throw UsageError("--tolerance must be positive");
  o.tolerance = args.number("--tolerance-abs", 0.0);
  if (o.tolerance < 0.0) throw UsageError("--tolerance-abs must be positive");
  o.segmentation.max_extrema = args.integer("--max-extrema", -1);
  o.segmentation.significance = args.number("--significance", o.segmentation.significance);
  const std::string g2 = args.get("--g2", "newton");
  if (g2 == "newton") o.g2 = G2Method::kNewton;
  else if (g2 == "bisection") o.g2 = G2Method::kBisection;
  else if (g2 == "off") o.g2 = G2Method::kOff;
  else throw UsageError("--g2 takes newton, bisection or off, got '" + g2 + "'");
  o.g2_threshold = args.number("--g2-threshold", o.g2_threshold);
  if (!(o.g2_threshold > 0.0)) throw UsageError("--g2-threshold must be positive");
  o.cleanup.detect_corners = !args.has("--no-corners");
  o.cleanup.detect_closed = !args.has("--no-close");
  o.cleanup.assume_closed = args.has("--closed");
  if (o.cleanup.assume_closed && !o.cleanup.detect_closed) throw UsageError("--closed and --no-close contradict each other");
  o.polish = !args.has("--paper-only");
  o.time_budget_ms = args.number("--time-budget", 0.0);
  if (!(o.time_budget_ms >= 0.0)) throw UsageError("--time-budget must be at least 0 (ms; 0: no limit)");
  o.max_points = positiveCount(args, "--max-points", o.max_points);
  o.max_polish_segments = positiveCount(args, "--max-polish-segments", o.max_polish_segments);
  return o;
}

ReadLimits readLimitsFrom(const Args& args) {
  ReadLimits limits;
  limits.max_points_per_stroke = positiveCount(args, "--max-points", limits.max_points_per_stroke);
  limits.max_strokes = positiveCount(args, "--max-strokes", limits.max_strokes);
  limits.max_svg_points = positiveCount(args, "--max-svg-points", limits.max_svg_points);
  limits.max_nesting = positiveCount(args, "--max-nesting", limits.max_nesting);
  return limits;
}

}  // namespace la::cli
