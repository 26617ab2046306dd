#pragma once
// The curves of an SVG written by app/io/curve_export.cpp read back as cubic Beziers,
// the tolerance the file states, and the distance from a point to a path: for the tests
// that check the export stays within that tolerance of the LA curves
// (tests/lafit_cli_test.cpp, tests/gui/export_window_test.cpp). No Qt, so both use it.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/bezier_approximation.h"

namespace la::test {

/// TOL of "<desc>cubic Bezier paths within TOL of the fitted curves</desc>"; NaN if the
/// file does not state it.
inline double statedBezierTolerance(const std::string& svg) {
  const std::string before = "cubic Bezier paths within ";
  const std::size_t at = svg.find(before);
  if (at == std::string::npos || svg.find(" of the fitted curves", at) == std::string::npos) return NAN;
  return std::strtod(svg.c_str() + at + before.size(), nullptr);
}

/// Every <path d="..."/> of the curves group, in order, as its cubics: the writer's
/// "M x y", then "C x1 y1 x2 y2 x y" per cubic, then "Z" for a closed curve. Z is read
/// as a straight cubic back to the start, so the line it draws is checked too (a point
/// when the path ends at its start, as it should). A path with anything else comes back
/// empty.
inline std::vector<std::vector<CubicBezier>> curvePathsOf(const std::string& svg) {
  std::vector<std::vector<CubicBezier>> paths;
  const std::size_t group = svg.find("<g id=\"curves\"");
  if (group == std::string::npos) return paths;
  const std::size_t group_end = svg.find("</g>", group);
  const std::string tag = "<path d=\"";
  for (std::size_t at = svg.find(tag, group); at < group_end; at = svg.find(tag, at)) {
    at += tag.size();
    const std::string d = svg.substr(at, svg.find('"', at) - at);
    std::vector<CubicBezier>& path = paths.emplace_back();
    Vec2 start = Vec2::Zero(), pen = Vec2::Zero();
    char op = 0;
    std::vector<double> v;  // the numbers of the current command so far
    for (const char* c = d.c_str(); *c;) {
      if (std::isspace(static_cast<unsigned char>(*c))) {
        ++c;
      } else if (*c == 'M' || *c == 'C') {
        op = *c++;
        v.clear();
      } else if (*c == 'Z') {
        ++c;
        path.push_back({pen, pen + (start - pen) / 3, pen + 2 * (start - pen) / 3, start});
        pen = start;
      } else {
        char* end = nullptr;
        v.push_back(std::strtod(c, &end));
        if (end == c || op == 0) {  // not a number, or numbers before any command
          path.clear();
          break;
        }
        c = end;
        if (op == 'M' && v.size() == 2) {
          start = pen = Vec2(v[0], v[1]);
          v.clear();
        } else if (op == 'C' && v.size() == 6) {
          path.push_back({pen, Vec2(v[0], v[1]), Vec2(v[2], v[3]), Vec2(v[4], v[5])});
          pen = path.back().p3;
          v.clear();
        }
      }
    }
  }
  return paths;
}

/// Distance from `p` to the nearest of the cubics. Each is sampled coarsely, then the
/// nearest sample refined by ternary search: the result is the distance to a point on
/// the path, so sampling can only make it larger, never hide a miss.
inline double distanceToBeziers(const std::vector<CubicBezier>& path, const Vec2& p) {
  double best = INFINITY;
  for (const CubicBezier& b : path) {
    // A cubic lies within its control points' box: one whose box is farther than the
    // best so far cannot be nearer.
    const Vec2 box_lo = b.p0.cwiseMin(b.p1).cwiseMin(b.p2).cwiseMin(b.p3);
    const Vec2 box_hi = b.p0.cwiseMax(b.p1).cwiseMax(b.p2).cwiseMax(b.p3);
    if ((p - p.cwiseMax(box_lo).cwiseMin(box_hi)).norm() >= best) continue;
    constexpr int kCoarse = 64;
    int k_best = 0;
    double d_best = INFINITY;
    for (int k = 0; k <= kCoarse; ++k) {
      const double d = (b.point(static_cast<double>(k) / kCoarse) - p).norm();
      if (d < d_best) d_best = d, k_best = k;
    }
    double lo = std::max(0.0, (k_best - 1.0) / kCoarse), hi = std::min(1.0, (k_best + 1.0) / kCoarse);
    for (int i = 0; i < 60; ++i) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      if ((b.point(m1) - p).norm() < (b.point(m2) - p).norm()) hi = m2;
      else lo = m1;
    }
    best = std::min({best, d_best, (b.point(0.5 * (lo + hi)) - p).norm()});
  }
  return best;
}

}  // namespace la::test
