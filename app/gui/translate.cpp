#include "app/gui/translate.h"

namespace la::gui {
namespace {

CubicBSpline translated(const CubicBSpline& spline, const Vec2& d) {
  std::vector<Vec2> control = spline.control();
  if (spline.isPeriodic()) {  // its stored control points repeat the first three: rebuild from the distinct ones
    control.resize(static_cast<std::size_t>(spline.freeControlCount()));
    for (Vec2& q : control) q += d;
    return CubicBSpline::periodic(spline.breaks(), control);
  }
  for (Vec2& q : control) q += d;
  return CubicBSpline(spline.knots(), std::move(control));
}

}  // namespace

FitResult translated(const FitResult& fit, const Vec2& d) {
  FitResult out = fit;
  for (CurvePiece& piece : out.curve.pieces) {
    const LaSegment& s = piece.segment;
    piece.segment = LaSegment(s.alpha(), s.length(), s.start() + d, s.theta0(), s.kappaStart(), s.kappaEnd());
  }
  out.splines.clear();
  for (const CubicBSpline& spline : fit.splines) out.splines.push_back(translated(spline, d));
  for (Vec2& q : out.cleaned.points) q += d;
  return out;
}

void translateStroke(DocumentStroke& stroke, const Vec2& d) {
  for (StrokeSample& sample : stroke.raw.samples) sample.p += d;
  if (stroke.fit) stroke.fit = translated(*stroke.fit, d);
  for (auto& [joint, position] : stroke.joint_overrides) position += d;
  for (auto& [piece, apex] : stroke.apex_overrides) apex += d;
  stroke.touch();
}

}  // namespace la::gui
