// Tests of the ALP G2 region map (core/alp_region_map.h): every cell agrees with the
// individual solve of its curvatures, the map contains the obvious member (the
// circular arc of a symmetric condition), and the CSV/SVG writers say what they hold.

#include "core/alp_region_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace la {
namespace {

AlpRegionRequest smallRequest() {
  AlpRegionRequest r;
  r.theta_start = 0.5;
  r.theta_end = -0.5;  // symmetric C turning right: the circular arc has kappa = -2 sin(0.5) = -0.959
  r.shape.degree = 3;
  r.kappa_min = -3.0;
  r.kappa_max = 1.0;
  r.size = 8;
  return r;
}

TEST(AlpRegionMap, CellsAgreeWithIndividualSolves) {
  const AlpRegionRequest r = smallRequest();
  const AlpRegionMap map = computeAlpRegionMap(r);
  ASSERT_EQ(map.cells.size(), 64u);
  for (int j = 0; j < r.size; ++j)
    for (int i = 0; i < r.size; ++i) {
      const double ks = map.kappa_s[i], ke = map.kappa_e[j];
      EXPECT_NEAR(ks, r.kappa_min + (i + 0.5) * 0.5, 1e-15);
      const HermiteEnd a{Vec2(0, 0), r.theta_start, ks}, b{Vec2(1, 0), r.theta_end, ke};
      const AlpSolve s = solveAlpHermite(a, b, 2, r.shape);
      const AlpRegionCell cell = map.at(i, j);
      EXPECT_EQ(map.statuses[j * r.size + i], s.report.status) << ks << ", " << ke;
      if (!s.report.usable()) {
        EXPECT_EQ(cell, AlpRegionCell::kNoSolution);
        continue;
      }
      const bool region = !s.check.has_inflection && s.check.monotone;
      EXPECT_EQ(cell == AlpRegionCell::kMonotone, region) << ks << ", " << ke << ": " << toString(cell);
      EXPECT_EQ(cell == AlpRegionCell::kInflection || cell == AlpRegionCell::kInflectionAndExtremum,
                s.check.has_inflection);
      // and the cell's curve really meets the G2 conditions
      EXPECT_LE((s.curve->end() - b.point).norm(), 1e-9);
      EXPECT_NEAR(s.curve->kappa(0.0), ks, 1e-12);
      EXPECT_NEAR(s.curve->kappa(s.curve->length()), ke, 1e-12);
    }
  int total = 0;
  for (AlpRegionCell c : {AlpRegionCell::kMonotone, AlpRegionCell::kInflection, AlpRegionCell::kNotMonotone,
                          AlpRegionCell::kInflectionAndExtremum, AlpRegionCell::kNoSolution})
    total += map.count(c);
  EXPECT_EQ(total, 64);
}

TEST(AlpRegionMap, ContainsTheCircularArcAndExcludesTheFar) {
  // One cell centred on the arc's curvature (kappa_s = kappa_e = -2 sin 0.5): the arc
  // itself is a monotone solution without inflection.
  AlpRegionRequest r = smallRequest();
  const double k = -2.0 * std::sin(0.5);
  r.kappa_min = k - 0.05;
  r.kappa_max = k + 0.05;
  r.size = 1;
  const AlpRegionMap map = computeAlpRegionMap(r);
  EXPECT_EQ(map.at(0, 0), AlpRegionCell::kMonotone);
  // opposite-signed end curvatures of a C-shaped condition force a sign change
  const AlpSolve s = solveAlpRegionCell(smallRequest(), -1.0, 1.0);
  EXPECT_TRUE(s.report.usable()) << s.report.message;
  if (s.report.usable()) {
    EXPECT_TRUE(s.check.has_inflection);
  }
}

TEST(AlpRegionMap, WritersDescribeTheMap) {
  const AlpRegionMap map = computeAlpRegionMap(smallRequest());
  const std::string csv = alpRegionMapToCsv(map);
  std::istringstream in(csv);
  std::string line;
  int data = 0;
  bool header = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line == "kappa_s,kappa_e,cell,status") {
      header = true;
      continue;
    }
    ++data;
  }
  EXPECT_TRUE(header);
  EXPECT_EQ(data, 64);
  const std::string svg = alpRegionMapToSvg(map);
  EXPECT_NE(svg.find("kappa_s</text>"), std::string::npos);
  EXPECT_NE(svg.find("kappa_e</text>"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  std::size_t rects = 0;
  for (std::size_t at = svg.find("<rect x="); at != std::string::npos; at = svg.find("<rect x=", at + 1)) ++rects;
  EXPECT_EQ(rects, 64u + 1u + 5u) << "cells, frame, legend";
}

TEST(AlpRegionMap, RejectsBadRequests) {
  AlpRegionRequest r = smallRequest();
  r.size = 0;
  EXPECT_THROW(computeAlpRegionMap(r), std::invalid_argument);
  r = smallRequest();
  r.kappa_max = r.kappa_min;
  EXPECT_THROW(computeAlpRegionMap(r), std::invalid_argument);
  r = smallRequest();
  r.theta_end = NAN;
  EXPECT_THROW(computeAlpRegionMap(r), std::invalid_argument);
  r = smallRequest();
  r.shape.degree = 2;  // too small for G2: every cell is bad input
  r.size = 2;
  const AlpRegionMap map = computeAlpRegionMap(r);
  for (SolveStatus s : map.statuses) EXPECT_EQ(s, SolveStatus::kBadInput);
  EXPECT_EQ(map.count(AlpRegionCell::kNoSolution), 4);
}

}  // namespace
}  // namespace la
