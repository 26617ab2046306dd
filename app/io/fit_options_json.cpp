#include "app/io/fit_options_json.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace la {

nlohmann::json fitOptionsToJson(const FitOptions& o) {
  return {{"tolerance", o.tolerance_fraction},
          {"tolerance_abs", o.tolerance},
          {"max_extrema", o.segmentation.max_extrema},
          {"significance", o.segmentation.significance},
          {"g2", toString(o.g2)},
          {"g2_threshold", o.g2_threshold},
          {"corners", o.cleanup.detect_corners},
          {"close", o.cleanup.detect_closed},
          {"assume_closed", o.cleanup.assume_closed},
          {"polish", o.polish},
          {"time_budget_ms", o.time_budget_ms}};
}

FitOptions fitOptionsFromJson(const nlohmann::json& j) {
  if (!j.is_object()) throw std::invalid_argument("fit options: not an object");
  auto number = [&](const char* key, double fallback, bool positive) {
    if (!j.contains(key)) return fallback;
    if (!j.at(key).is_number()) throw std::invalid_argument(std::string("fit options: \"") + key + "\" is not a number");
    const double v = j.at(key).get<double>();
    if (!std::isfinite(v) || v < 0.0 || (positive && v == 0.0))
      throw std::invalid_argument(std::string("fit options: \"") + key + "\" out of range: " + std::to_string(v));
    return v;
  };
  auto flag = [&](const char* key, bool fallback) {
    if (!j.contains(key)) return fallback;
    if (!j.at(key).is_boolean()) throw std::invalid_argument(std::string("fit options: \"") + key + "\" is not true or false");
    return j.at(key).get<bool>();
  };
  FitOptions o;
  o.tolerance_fraction = number("tolerance", o.tolerance_fraction, true);
  o.tolerance = number("tolerance_abs", o.tolerance, false);
  if (j.contains("max_extrema")) {
    if (!j.at("max_extrema").is_number_integer() || j.at("max_extrema").get<int>() < -1)
      throw std::invalid_argument("fit options: \"max_extrema\" is not an integer of at least -1");
    o.segmentation.max_extrema = j.at("max_extrema").get<int>();
  }
  o.segmentation.significance = number("significance", o.segmentation.significance, false);
  if (j.contains("g2") && !j.at("g2").is_string())
    throw std::invalid_argument("fit options: \"g2\" is not newton, bisection or off: " + j.at("g2").dump());
  const std::string g2 = j.value("g2", std::string(toString(o.g2)));
  if (g2 == toString(G2Method::kNewton)) o.g2 = G2Method::kNewton;
  else if (g2 == toString(G2Method::kBisection)) o.g2 = G2Method::kBisection;
  else if (g2 == toString(G2Method::kOff)) o.g2 = G2Method::kOff;
  else throw std::invalid_argument("fit options: \"g2\" is not newton, bisection or off: " + g2);
  o.g2_threshold = number("g2_threshold", o.g2_threshold, true);
  o.cleanup.detect_corners = flag("corners", o.cleanup.detect_corners);
  o.cleanup.detect_closed = flag("close", o.cleanup.detect_closed);
  o.cleanup.assume_closed = flag("assume_closed", o.cleanup.assume_closed);
  o.polish = flag("polish", o.polish);
  o.time_budget_ms = number("time_budget_ms", o.time_budget_ms, false);
  return o;
}

}  // namespace la
