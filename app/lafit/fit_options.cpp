#include "app/lafit/fit_options.h"

namespace la::cli {

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
  o.time_budget_ms = args.number("--time-budget", 0.0);
  if (!(o.time_budget_ms >= 0.0)) throw UsageError("--time-budget must be at least 0 (ms; 0: no limit)");
  return o;
}

}  // namespace la::cli
