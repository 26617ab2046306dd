#include "app/io/curve_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/bezier_approximation.h"

namespace la {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

struct Box {
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool empty() const { return !(lo.x() <= hi.x()); }
};

Box boxOf(const std::vector<ExportCurve>& curves, const std::vector<std::vector<Vec2>>& points) {
  Box box;
  for (const ExportCurve& c : curves)
    for (const ExportPiece& piece : c.pieces) {
      CurveSamples smp;
      piece.curve->sample(16, smp);
      for (const Vec2& p : smp.point) box.add(p);
    }
  for (const auto& stroke : points)
    for (const Vec2& p : stroke) box.add(p);
  return box;
}

std::vector<CubicBezier> beziersOf(const ExportCurve& curve, double tolerance) {
  std::vector<CubicBezier> out;
  for (const ExportPiece& piece : curve.pieces) {
    const BezierApproximation a = approximateWithBeziers(*piece.curve, tolerance);
    out.insert(out.end(), a.pieces.begin(), a.pieces.end());
  }
  return out;
}

}  // namespace

std::vector<ExportCurve> exportChains(const std::vector<Curve>& curves, std::vector<LaSegmentView>& views) {
  std::size_t count = 0;
  for (const Curve& c : curves) count += c.pieces.size();
  views.clear();
  views.reserve(count);  // no reallocation: the chains keep pointers into it
  std::vector<ExportCurve> out;
  for (const Curve& c : curves) {
    ExportCurve e;
    e.closed = c.closed;
    for (const CurvePiece& piece : c.pieces) {
      views.emplace_back(piece.segment);
      e.pieces.push_back({&views.back(), piece.corner});
    }
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<ExportCurve> exportChains(const std::vector<AlpCurve>& curves) {
  std::vector<ExportCurve> out;
  for (const AlpCurve& c : curves) out.push_back({{{&c, false}}, false});
  return out;
}

double drawingDiagonal(const std::vector<Curve>& curves, const std::vector<std::vector<Vec2>>& points) {
  std::vector<LaSegmentView> views;
  return exportDrawingDiagonal(exportChains(curves, views), points);
}

std::string curvesToSvg(const std::vector<Curve>& curves, const std::vector<std::vector<Vec2>>& points,
                        const SvgOptions& options) {
  std::vector<LaSegmentView> views;
  return exportCurvesToSvg(exportChains(curves, views), points, options);
}

std::string curvesToDxf(const std::vector<Curve>& curves, double relative_tolerance) {
  std::vector<LaSegmentView> views;
  return exportCurvesToDxf(exportChains(curves, views), relative_tolerance);
}

std::string curvesToCsv(const std::vector<Curve>& curves, const CurveSampling& sampling) {
  std::vector<LaSegmentView> views;
  return exportCurvesToCsv(exportChains(curves, views), sampling);
}

std::string alpCurvesToSvg(const std::vector<AlpCurve>& curves, const std::vector<std::vector<Vec2>>& points,
                           const SvgOptions& options) {
  return exportCurvesToSvg(exportChains(curves), points, options);
}

std::string alpCurvesToDxf(const std::vector<AlpCurve>& curves, double relative_tolerance) {
  return exportCurvesToDxf(exportChains(curves), relative_tolerance);
}

std::string alpCurvesToCsv(const std::vector<AlpCurve>& curves, const CurveSampling& sampling) {
  return exportCurvesToCsv(exportChains(curves), sampling);
}

double exportDrawingDiagonal(const std::vector<ExportCurve>& curves, const std::vector<std::vector<Vec2>>& points) {
  const Box box = boxOf(curves, points);
  if (box.empty()) return 1.0;
  const double d = (box.hi - box.lo).norm();
  return d > 0.0 ? d : 1.0;
}

std::string exportCurvesToSvg(const std::vector<ExportCurve>& curves, const std::vector<std::vector<Vec2>>& points,
                              const SvgOptions& options) {
  Box box = boxOf(curves, points);
  if (box.empty()) box.add(Vec2::Zero());
  const double diag = std::max((box.hi - box.lo).norm(), 1e-300);
  const double tolerance =
      options.bezier_tolerance_absolute > 0 ? options.bezier_tolerance_absolute : options.bezier_tolerance * diag;
  const double margin = 0.05 * diag;
  const double width = options.stroke_width > 0 ? options.stroke_width : 0.002 * diag;
  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" viewBox=\"" << num(box.lo.x() - margin) << ' '
      << num(box.lo.y() - margin) << ' ' << num(box.hi.x() - box.lo.x() + 2 * margin) << ' '
      << num(box.hi.y() - box.lo.y() + 2 * margin) << "\" width=\"800\" height=\""
      << num(800.0 * (box.hi.y() - box.lo.y() + 2 * margin) / (box.hi.x() - box.lo.x() + 2 * margin)) << "\">\n"
      << "<desc>cubic Bezier paths within " << num(tolerance) << " of the fitted curves</desc>\n";
  // y-up data: mirror about the box's middle line so it shows the right way up
  svg << "<g" << (options.y_up ? " transform=\"matrix(1 0 0 -1 0 " + num(box.lo.y() + box.hi.y()) + ")\"" : std::string())
      << ">\n";
  if (options.show_points) {
    svg << "<g id=\"points\" inkscape:label=\"points\" inkscape:groupmode=\"layer\" fill=\"#999\">\n";
    for (const auto& stroke : points)
      for (const Vec2& p : stroke)
        svg << "<circle cx=\"" << num(p.x()) << "\" cy=\"" << num(p.y()) << "\" r=\"" << num(1.5 * width) << "\"/>\n";
    svg << "</g>\n";
  }
  if (options.show_comb) {
    // Teeth along the left normal scaled by kappa; the largest |kappa| gets comb_scale * diag.
    double kmax = 0.0;
    for (const ExportCurve& c : curves)
      for (const ExportPiece& piece : c.pieces) kmax = std::max(kmax, piece.curve->maxAbsKappa());
    const double scale = kmax > 0 ? options.comb_scale * diag / kmax : 0.0;
    svg << "<g id=\"comb\" inkscape:label=\"comb\" inkscape:groupmode=\"layer\" stroke=\"#d33\" stroke-width=\"" << num(0.5 * width) << "\" fill=\"none\">\n";
    for (const ExportCurve& c : curves)
      for (const ExportPiece& piece : c.pieces) {
        CurveSamples smp;
        piece.curve->sample(std::max(2, options.comb_teeth_per_segment), smp);
        std::ostringstream envelope;
        for (std::size_t i = 0; i < smp.size(); ++i) {
          const Vec2 n(-smp.tangent[i].y(), smp.tangent[i].x());
          const Vec2 tip = smp.point[i] - scale * smp.kappa[i] * n;  // comb drawn outside the bend
          svg << "<line x1=\"" << num(smp.point[i].x()) << "\" y1=\"" << num(smp.point[i].y()) << "\" x2=\""
              << num(tip.x()) << "\" y2=\"" << num(tip.y()) << "\"/>\n";
          envelope << (i == 0 ? "M" : " L") << num(tip.x()) << ' ' << num(tip.y());
        }
        svg << "<path d=\"" << envelope.str() << "\"/>\n";
      }
    svg << "</g>\n";
  }
  svg << "<g id=\"curves\" inkscape:label=\"curves\" inkscape:groupmode=\"layer\" stroke=\"#1565c0\" stroke-width=\"" << num(width) << "\" fill=\"none\">\n";
  for (const ExportCurve& c : curves) {
    if (c.pieces.empty()) continue;
    std::ostringstream d;
    const auto beziers = beziersOf(c, tolerance);
    d << "M" << num(beziers.front().p0.x()) << ' ' << num(beziers.front().p0.y());
    for (const CubicBezier& b : beziers)
      d << " C" << num(b.p1.x()) << ' ' << num(b.p1.y()) << ' ' << num(b.p2.x()) << ' ' << num(b.p2.y()) << ' '
        << num(b.p3.x()) << ' ' << num(b.p3.y());
    if (c.closed) d << " Z";
    svg << "<path d=\"" << d.str() << "\"/>\n";
  }
  svg << "</g>\n</g>\n</svg>\n";
  return svg.str();
}

std::string exportCurvesToDxf(const std::vector<ExportCurve>& curves, double relative_tolerance) {
  DxfOptions options;
  options.relative_tolerance = relative_tolerance;
  return exportCurvesToDxf(curves, {}, options);
}

std::string exportCurvesToDxf(const std::vector<ExportCurve>& curves, const std::vector<std::vector<Vec2>>& points,
                              const DxfOptions& options) {
  const double tol = options.absolute_tolerance > 0 ? options.absolute_tolerance
                                                   : options.relative_tolerance * exportDrawingDiagonal(curves, {});
  std::ostringstream dxf;
  auto pair = [&](int code, const std::string& value) { dxf << code << '\n' << value << '\n'; };
  pair(0, "SECTION");
  pair(2, "HEADER");
  pair(9, "$ACADVER");
  pair(1, "AC1015");
  pair(9, "$INSUNITS");
  pair(70, std::to_string(static_cast<int>(options.units)));
  pair(0, "ENDSEC");
  if (!options.units_comment.empty()) pair(999, options.units_comment);
  // The layers the entities name: curves and points apart, so a CAD user can hide either.
  pair(0, "SECTION");
  pair(2, "TABLES");
  pair(0, "TABLE");
  pair(2, "LAYER");
  pair(70, "2");
  for (const auto& [name, color] : {std::pair<const char*, const char*>{"CURVES", "5"}, {"POINTS", "8"}}) {
    pair(0, "LAYER");
    pair(2, name);
    pair(70, "0");
    pair(62, color);  // ACI colour: blue curves, grey points
    pair(6, "CONTINUOUS");
  }
  pair(0, "ENDTAB");
  pair(0, "ENDSEC");
  pair(0, "SECTION");
  pair(2, "ENTITIES");
  for (const ExportCurve& c : curves) {
    if (c.pieces.empty()) continue;
    const auto beziers = beziersOf(c, tol);
    // A Bezier chain is a cubic B-spline with interior knots of multiplicity 3.
    const int n = static_cast<int>(beziers.size());
    std::vector<Vec2> control{beziers.front().p0};
    for (const CubicBezier& b : beziers) {
      control.push_back(b.p1);
      control.push_back(b.p2);
      control.push_back(b.p3);
    }
    std::vector<double> knots{0, 0, 0, 0};
    for (int i = 1; i < n; ++i) knots.insert(knots.end(), {double(i), double(i), double(i)});
    knots.insert(knots.end(), {double(n), double(n), double(n), double(n)});
    pair(0, "SPLINE");
    pair(8, "CURVES");
    pair(100, "AcDbEntity");
    pair(100, "AcDbSpline");
    pair(70, c.closed ? "9" : "8");  // 8 planar, +1 closed
    pair(71, "3");
    pair(72, std::to_string(knots.size()));
    pair(73, std::to_string(control.size()));
    pair(74, "0");
    for (double k : knots) pair(40, num(k));
    for (const Vec2& p : control) {
      pair(10, num(p.x()));
      pair(20, num(p.y()));
      pair(30, "0");
    }
  }
  for (const auto& stroke : points)
    for (const Vec2& p : stroke) {
      pair(0, "POINT");
      pair(8, "POINTS");
      pair(100, "AcDbEntity");
      pair(100, "AcDbPoint");
      pair(10, num(p.x()));
      pair(20, num(p.y()));
      pair(30, "0");
    }
  pair(0, "ENDSEC");
  pair(0, "EOF");
  return dxf.str();
}

std::string exportCurvesToCsv(const std::vector<ExportCurve>& curves, const CurveSampling& sampling) {
  std::ostringstream csv;
  csv << "x,y,s,theta,kappa\n";
  bool first = true;
  for (const ExportCurve& c : curves) {
    if (!first) csv << '\n';
    first = false;
    double s0 = 0.0;
    for (std::size_t j = 0; j < c.pieces.size(); ++j) {
      const ArcLengthCurve& seg = *c.pieces[j].curve;
      CurveSamples smp;
      seg.sample(std::max(2, sampling.per_segment), smp, s0);
      // the first sample of a later segment repeats the joint, unless it is a corner
      const std::size_t from = (j == 0 || c.pieces[j].corner) ? 0 : 1;
      for (std::size_t i = from; i < smp.size(); ++i)
        csv << num(smp.point[i].x()) << ',' << num(smp.point[i].y()) << ',' << num(smp.s[i]) << ','
            << num(smp.theta[i]) << ',' << num(smp.kappa[i]) << '\n';
      s0 += seg.length();
    }
  }
  return csv.str();
}

}  // namespace la
