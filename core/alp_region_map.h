#pragma once
// The region of end curvatures (kappa_s, kappa_e) for which a G2 ALP curve with
// monotone curvature and no inflection exists, for one G1 condition (seed 000
// section 5.3 and fig. 5; seed 004 fig. 3).
//
// The G1 condition is normalized: chord from (0, 0) to (1, 0), tangent angles
// theta_start at the start and theta_end at the end (the turning is
// theta_end - theta_start as given), so curvatures are in units of 1 / chord. Each
// cell of a size x size grid over [kappa_min, kappa_max]^2 (cell centres) is the
// individual solve solveAlpHermite(start, end, 2, shape) of that cell's end
// curvatures, classified by its curvature check: no warm start from neighbours, so
// a cell says exactly what an interactive solve with those curvatures would give.
// Like the paper's figures it is experimental: a cell marked kNoSolution means the
// solver found none, not that none exists.

#include <cstdint>
#include <string>
#include <vector>

#include "core/alp_hermite.h"

namespace la {

enum class AlpRegionCell : std::uint8_t {
  kMonotone,            // solved; curvature monotone, no inflection (the region)
  kInflection,          // solved; monotone but with an inflection
  kNotMonotone,         // solved; no inflection but a curvature extremum
  kInflectionAndExtremum,
  kNoSolution,          // the solve failed (status in the map's statuses)
};

const char* toString(AlpRegionCell cell);  // "monotone", "inflection", "not_monotone", ...

struct AlpRegionRequest {
  double theta_start = 0.0;  // tangent angle at (0, 0), radians
  double theta_end = 0.0;    // tangent angle at (1, 0), radians
  AlpShape shape;            // degree (>= 3 for G2), p, and the rational weights if wanted
  double kappa_min = -4.0;   // range of both axes, curvature times chord
  double kappa_max = 4.0;
  int size = 41;             // cells per axis (>= 1)
  AlpOptions options;
};

struct AlpRegionMap {
  AlpRegionRequest request;
  std::vector<double> kappa_s;     // cell centres along the first axis (size values)
  std::vector<double> kappa_e;     // ... and the second
  // cells[j * size + i] is (kappa_s[i], kappa_e[j]); likewise statuses.
  std::vector<AlpRegionCell> cells;
  std::vector<SolveStatus> statuses;
  int count(AlpRegionCell cell) const;
  AlpRegionCell at(int i, int j) const { return cells[static_cast<std::size_t>(j) * kappa_s.size() + i]; }
};

/// The map; throws std::invalid_argument for size < 1, a range that is empty or not
/// finite, or angles that are not finite (bad shapes show as kNoSolution cells with
/// status kBadInput).
AlpRegionMap computeAlpRegionMap(const AlpRegionRequest& request);

/// The G2 solve of one cell: the normalized G1 condition with these end curvatures.
AlpSolve solveAlpRegionCell(const AlpRegionRequest& request, double kappa_s, double kappa_e);

/// CSV, one line per cell: `kappa_s,kappa_e,cell,status` (cell as toString, status as
/// toString(SolveStatus)), after `#` comment lines with the request.
std::string alpRegionMapToCsv(const AlpRegionMap& map);

/// SVG image: one square per cell (grey: the region, light colours: solved but with
/// an inflection and/or an extremum, white: no solution), axes labelled kappa_s
/// (horizontal) and kappa_e (vertical, up), ticks at the ends and at 0, a legend.
std::string alpRegionMapToSvg(const AlpRegionMap& map);

}  // namespace la
