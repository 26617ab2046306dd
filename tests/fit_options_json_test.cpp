// app/io/fit_options_json.h: the one reader and writer of fit options (sketch files,
// lafit's output): every option survives a round trip, a missing key takes the
// default, a wrong type or range is refused with the key named.

#include "app/io/fit_options_json.h"

#include <gtest/gtest.h>

#include <string>

namespace la {
namespace {

std::string errorOf(const nlohmann::json& j) {
  try {
    fitOptionsFromJson(j);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(FitOptionsJson, EveryOptionSurvivesARoundTrip) {
  FitOptions o;
  o.tolerance_fraction = 0.0123;
  o.tolerance = 2.5;
  o.segmentation.max_extrema = 3;
  o.segmentation.significance = 0.35;
  o.g2 = G2Method::kBisection;
  o.g2_threshold = 1e-8;
  o.cleanup.detect_corners = false;
  o.cleanup.detect_closed = false;
  o.cleanup.assume_closed = true;
  o.polish = false;
  o.time_budget_ms = 40.0;
  const FitOptions back = fitOptionsFromJson(nlohmann::json::parse(fitOptionsToJson(o).dump()));
  EXPECT_EQ(back.tolerance_fraction, o.tolerance_fraction);
  EXPECT_EQ(back.tolerance, o.tolerance);
  EXPECT_EQ(back.segmentation.max_extrema, o.segmentation.max_extrema);
  EXPECT_EQ(back.segmentation.significance, o.segmentation.significance);
  EXPECT_EQ(back.g2, o.g2);
  EXPECT_EQ(back.g2_threshold, o.g2_threshold);
  EXPECT_EQ(back.cleanup.detect_corners, o.cleanup.detect_corners);
  EXPECT_EQ(back.cleanup.detect_closed, o.cleanup.detect_closed);
  EXPECT_EQ(back.cleanup.assume_closed, o.cleanup.assume_closed);
  EXPECT_EQ(back.polish, o.polish);
  EXPECT_EQ(back.time_budget_ms, o.time_budget_ms);
}

TEST(FitOptionsJson, AMissingKeyTakesTheDefault) {
  const FitOptions defaults;
  const FitOptions o = fitOptionsFromJson(nlohmann::json{{"max_extrema", 1}});
  EXPECT_EQ(o.segmentation.max_extrema, 1);
  EXPECT_EQ(o.tolerance_fraction, defaults.tolerance_fraction);
  EXPECT_EQ(o.time_budget_ms, defaults.time_budget_ms);
  EXPECT_EQ(o.g2, defaults.g2);
}

TEST(FitOptionsJson, AWrongValueIsRefusedWithItsKey) {
  EXPECT_NE(errorOf({{"tolerance", "big"}}).find("\"tolerance\""), std::string::npos);
  EXPECT_NE(errorOf({{"tolerance", 0.0}}).find("\"tolerance\""), std::string::npos);
  EXPECT_NE(errorOf({{"time_budget_ms", -1.0}}).find("\"time_budget_ms\""), std::string::npos);
  EXPECT_NE(errorOf({{"max_extrema", 1.5}}).find("\"max_extrema\""), std::string::npos);
  EXPECT_NE(errorOf({{"g2", "fast"}}).find("\"g2\""), std::string::npos);
  EXPECT_NE(errorOf({{"g2", true}}).find("\"g2\""), std::string::npos);  // (found by the sketch fuzzer)
  EXPECT_NE(errorOf({{"polish", 1}}).find("\"polish\""), std::string::npos);
  EXPECT_NE(errorOf(nlohmann::json::array()).find("not an object"), std::string::npos);
}

}  // namespace
}  // namespace la
