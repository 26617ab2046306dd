#include "core/alp_region_map.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace la {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

const char* colourOf(AlpRegionCell cell) {
  switch (cell) {
    case AlpRegionCell::kMonotone: return "#808080";
    case AlpRegionCell::kInflection: return "#f4c7c3";
    case AlpRegionCell::kNotMonotone: return "#c6dafc";
    case AlpRegionCell::kInflectionAndExtremum: return "#e1c6f4";
    case AlpRegionCell::kNoSolution: return "#ffffff";
  }
  return "#ffffff";
}

const char* describe(AlpRegionCell cell) {
  switch (cell) {
    case AlpRegionCell::kMonotone: return "monotone, no inflection";
    case AlpRegionCell::kInflection: return "inflection";
    case AlpRegionCell::kNotMonotone: return "curvature extremum";
    case AlpRegionCell::kInflectionAndExtremum: return "inflection and extremum";
    case AlpRegionCell::kNoSolution: return "no solution found";
  }
  return "";
}

}  // namespace

const char* toString(AlpRegionCell cell) {
  switch (cell) {
    case AlpRegionCell::kMonotone: return "monotone";
    case AlpRegionCell::kInflection: return "inflection";
    case AlpRegionCell::kNotMonotone: return "not_monotone";
    case AlpRegionCell::kInflectionAndExtremum: return "inflection_and_extremum";
    case AlpRegionCell::kNoSolution: return "no_solution";
  }
  return "?";
}

int AlpRegionMap::count(AlpRegionCell cell) const {
  int c = 0;
  for (AlpRegionCell x : cells) c += x == cell;
  return c;
}

AlpSolve solveAlpRegionCell(const AlpRegionRequest& request, double kappa_s, double kappa_e) {
  const HermiteEnd start{Vec2(0.0, 0.0), request.theta_start, kappa_s};
  const HermiteEnd end{Vec2(1.0, 0.0), request.theta_end, kappa_e};
  return solveAlpHermite(start, end, 2, request.shape, request.options);
}

AlpRegionMap computeAlpRegionMap(const AlpRegionRequest& request) {
  if (request.size < 1) throw std::invalid_argument("computeAlpRegionMap: size must be at least 1");
  if (!std::isfinite(request.kappa_min) || !std::isfinite(request.kappa_max) ||
      !(request.kappa_max > request.kappa_min))
    throw std::invalid_argument("computeAlpRegionMap: need finite kappa_min < kappa_max");
  if (!std::isfinite(request.theta_start) || !std::isfinite(request.theta_end))
    throw std::invalid_argument("computeAlpRegionMap: tangent angles must be finite");
  AlpRegionMap map;
  map.request = request;
  const int size = request.size;
  const double step = (request.kappa_max - request.kappa_min) / size;
  for (int i = 0; i < size; ++i) map.kappa_s.push_back(request.kappa_min + (i + 0.5) * step);
  map.kappa_e = map.kappa_s;
  map.cells.reserve(static_cast<std::size_t>(size) * size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const AlpSolve s = solveAlpRegionCell(request, map.kappa_s[i], map.kappa_e[j]);
      map.statuses.push_back(s.report.status);
      if (!s.report.usable()) {
        map.cells.push_back(AlpRegionCell::kNoSolution);
      } else if (s.check.has_inflection) {
        map.cells.push_back(s.check.monotone ? AlpRegionCell::kInflection : AlpRegionCell::kInflectionAndExtremum);
      } else {
        map.cells.push_back(s.check.monotone ? AlpRegionCell::kMonotone : AlpRegionCell::kNotMonotone);
      }
    }
  return map;
}

std::string alpRegionMapToCsv(const AlpRegionMap& map) {
  const AlpRegionRequest& r = map.request;
  std::ostringstream csv;
  csv << "# ALP G2 region map (seed 000 section 5.3): chord (0,0)-(1,0), theta_start " << num(r.theta_start)
      << " rad, theta_end " << num(r.theta_end) << " rad\n"
      << "# degree " << r.shape.degree << ", p " << num(r.shape.p);
  if (r.shape.rational) csv << ", rational w_e " << num(r.shape.w_e) << " p_w " << num(r.shape.p_w);
  csv << ", " << map.kappa_s.size() << "x" << map.kappa_e.size() << " cells over [" << num(r.kappa_min) << ", "
      << num(r.kappa_max) << "]\n";
  csv << "kappa_s,kappa_e,cell,status\n";
  const std::size_t size = map.kappa_s.size();
  for (std::size_t j = 0; j < map.kappa_e.size(); ++j)
    for (std::size_t i = 0; i < size; ++i)
      csv << num(map.kappa_s[i]) << ',' << num(map.kappa_e[j]) << ',' << toString(map.cells[j * size + i]) << ','
          << toString(map.statuses[j * size + i]) << '\n';
  return csv.str();
}

std::string alpRegionMapToSvg(const AlpRegionMap& map) {
  const AlpRegionRequest& r = map.request;
  const int size = static_cast<int>(map.kappa_s.size());
  // Plot area in pixels: 600 x 600 with room for the axes, labels and legend.
  constexpr double kPlot = 600.0, kLeft = 70.0, kTop = 40.0, kLegend = 340.0;
  const double cell = kPlot / size;
  const double range = r.kappa_max - r.kappa_min;
  auto x = [&](double k) { return kLeft + (k - r.kappa_min) / range * kPlot; };
  auto y = [&](double k) { return kTop + kPlot - (k - r.kappa_min) / range * kPlot; };
  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(kLeft + kPlot + kLegend) << "\" height=\""
      << num(kTop + kPlot + 60) << "\" font-family=\"sans-serif\" font-size=\"14\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << num(kLeft) << "\" y=\"24\">ALP G2 region: n = " << r.shape.degree << ", p = " << num(r.shape.p)
      << (r.shape.rational ? ", rational w_e = " + num(r.shape.w_e) + ", p_w = " + num(r.shape.p_w) : std::string())
      << "; theta_start " << num(r.theta_start * 180.0 / M_PI) << " deg, theta_end "
      << num(r.theta_end * 180.0 / M_PI) << " deg</text>\n";
  svg << "<g id=\"cells\" shape-rendering=\"crispEdges\">\n";
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const AlpRegionCell c = map.at(i, j);
      svg << "<rect x=\"" << num(kLeft + i * cell) << "\" y=\"" << num(kTop + kPlot - (j + 1) * cell) << "\" width=\""
          << num(cell) << "\" height=\"" << num(cell) << "\" fill=\"" << colourOf(c) << "\"><title>kappa_s "
          << num(map.kappa_s[i]) << ", kappa_e " << num(map.kappa_e[j]) << ": " << describe(c) << "</title></rect>\n";
    }
  svg << "</g>\n";
  // Frame, zero lines, ticks and axis labels.
  svg << "<g id=\"axes\" stroke=\"black\" fill=\"none\">\n<rect x=\"" << num(kLeft) << "\" y=\"" << num(kTop)
      << "\" width=\"" << num(kPlot) << "\" height=\"" << num(kPlot) << "\"/>\n";
  if (r.kappa_min < 0.0 && r.kappa_max > 0.0)
    svg << "<line x1=\"" << num(x(0)) << "\" y1=\"" << num(kTop) << "\" x2=\"" << num(x(0)) << "\" y2=\""
        << num(kTop + kPlot) << "\" stroke-dasharray=\"4 3\"/>\n<line x1=\"" << num(kLeft) << "\" y1=\"" << num(y(0))
        << "\" x2=\"" << num(kLeft + kPlot) << "\" y2=\"" << num(y(0)) << "\" stroke-dasharray=\"4 3\"/>\n";
  svg << "</g>\n<g id=\"labels\">\n";
  std::vector<double> ticks{r.kappa_min, r.kappa_max};
  if (r.kappa_min < 0.0 && r.kappa_max > 0.0) ticks.push_back(0.0);
  for (double t : ticks) {
    svg << "<text x=\"" << num(x(t)) << "\" y=\"" << num(kTop + kPlot + 18) << "\" text-anchor=\"middle\">" << num(t)
        << "</text>\n";
    svg << "<text x=\"" << num(kLeft - 6) << "\" y=\"" << num(y(t) + 5) << "\" text-anchor=\"end\">" << num(t)
        << "</text>\n";
  }
  svg << "<text x=\"" << num(kLeft + kPlot / 2) << "\" y=\"" << num(kTop + kPlot + 44)
      << "\" text-anchor=\"middle\" font-style=\"italic\">kappa_s</text>\n";
  svg << "<text x=\"20\" y=\"" << num(kTop + kPlot / 2) << "\" text-anchor=\"middle\" font-style=\"italic\" "
      << "transform=\"rotate(-90 20 " << num(kTop + kPlot / 2) << ")\">kappa_e</text>\n";
  // Legend.
  const AlpRegionCell order[] = {AlpRegionCell::kMonotone, AlpRegionCell::kInflection, AlpRegionCell::kNotMonotone,
                                 AlpRegionCell::kInflectionAndExtremum, AlpRegionCell::kNoSolution};
  double ly = kTop + 10;
  for (AlpRegionCell c : order) {
    svg << "<rect x=\"" << num(kLeft + kPlot + 20) << "\" y=\"" << num(ly) << "\" width=\"16\" height=\"16\" fill=\""
        << colourOf(c) << "\" stroke=\"black\"/>\n<text x=\"" << num(kLeft + kPlot + 44) << "\" y=\"" << num(ly + 13)
        << "\">" << describe(c) << " (" << map.count(c) << ")</text>\n";
    ly += 26;
  }
  svg << "</g>\n</svg>\n";
  return svg.str();
}

}  // namespace la
