#pragma once
// What the marks on a fitted curve mean, one symbol each (the canvas draws them, the comb
// dock's legend names them with the same function): an end of an open curve, a G2 joint,
// an inflection (curvature changes sign), a curvature extremum (|curvature| stops rising
// or falling: fitting/quality.h's extremumJoints, so the marks agree with the extrema the
// status bar counts) and a corner (a G0 joint).

#include <QPainter>
#include <QPointF>
#include <QString>
#include <array>
#include <vector>

#include "core/curve.h"

namespace la::gui {

enum class MarkerKind { kEnd, kJoint, kInflection, kExtremum, kCorner };

inline constexpr std::array<MarkerKind, 5> kMarkerKinds{MarkerKind::kEnd, MarkerKind::kJoint, MarkerKind::kInflection,
                                                        MarkerKind::kExtremum, MarkerKind::kCorner};

QString markerName(MarkerKind kind);

struct CurveMarker {
  Vec2 at;
  MarkerKind kind;
};

/// A mark at every joint and at the ends of an open curve. Where two meanings meet, the
/// stronger is shown: corner, then inflection, then extremum. `diagonal` is the size the
/// curvature trends are judged against (QualityFigures::diagonal).
std::vector<CurveMarker> curveMarkers(const Curve& curve, double diagonal);

/// The symbol of `kind` centred on `at` (widget pixels), in the painter's pen.
void drawMarker(QPainter& p, MarkerKind kind, const QPointF& at);

}  // namespace la::gui
