#include "core/alp_curve_json.h"

#include <stdexcept>
#include <vector>

#include "core/curve_json.h"

namespace la {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw CurveFormatError(where.empty() ? what : where + ": " + what);
}

const json& requireKey(const json& object, const std::string& key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) fail(where, "missing key \"" + key + "\"");
  return *it;
}

double requireNumber(const json& object, const std::string& key, const std::string& where) {
  const json& value = requireKey(object, key, where);
  if (!value.is_number()) fail(where, "\"" + key + "\" must be a number, got " + value.dump());
  return value.get<double>();
}

std::vector<double> requireNumbers(const json& object, const std::string& key, const std::string& where) {
  const json& value = requireKey(object, key, where);
  if (!value.is_array()) fail(where, "\"" + key + "\" must be an array of numbers, got " + value.dump());
  std::vector<double> out;
  for (const json& v : value) {
    if (!v.is_number()) fail(where, "\"" + key + "\" must be an array of numbers, got " + value.dump());
    out.push_back(v.get<double>());
  }
  return out;
}

}  // namespace

json alpCurveToJson(const AlpCurve& curve, const AlpCurvatureCheck& check) {
  return {{"type", "alp"},
          {"degree", curve.degree()},
          {"control_kappa", curve.controlKappa()},
          {"weights", curve.weights()},
          {"length", curve.length()},
          {"start", {curve.start().x(), curve.start().y()}},
          {"theta0", curve.theta0()},
          {"checks",
           {{"has_inflection", check.has_inflection},
            {"monotone", check.monotone},
            {"inflections", check.inflections},
            {"extrema", check.extrema}}}};
}

AlpCurve alpCurveFromJson(const json& object, const std::string& where) {
  if (!object.is_object()) fail(where, "expected an ALP curve object, got " + std::string(object.type_name()));
  const json& type = requireKey(object, "type", where);
  if (!type.is_string() || type.get<std::string>() != "alp") fail(where, "\"type\" must be \"alp\", got " + type.dump());
  const std::vector<double> kappa = requireNumbers(object, "control_kappa", where);
  const json& degree = requireKey(object, "degree", where);
  if (!degree.is_number_integer() || degree.get<long long>() + 1 != static_cast<long long>(kappa.size()))
    fail(where, "\"degree\" " + degree.dump() + " does not match " + std::to_string(kappa.size()) +
                    " control curvatures");
  std::vector<double> weights;
  if (object.contains("weights")) weights = requireNumbers(object, "weights", where);
  const std::vector<double> start = requireNumbers(object, "start", where);
  if (start.size() != 2) fail(where, "\"start\" must be [x, y]");
  try {
    return AlpCurve(kappa, weights, requireNumber(object, "length", where), Vec2(start[0], start[1]),
                    requireNumber(object, "theta0", where));
  } catch (const std::invalid_argument& e) {
    fail(where, e.what());
  }
}

}  // namespace la
