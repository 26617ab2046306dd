#pragma once
// The user's edits of a fitted curve (the app's steering): a segment's alpha, a joint's
// position, the apex of a segment's control triangle. Each solves G2 again over the
// corner-to-corner part it touches (stage 6's joint rotation, fitting/g2_joints.h), the
// other parts unchanged, and measures the quality figures again.

#include <optional>
#include <string>

#include "fitting/pipeline.h"

namespace la {

/// Q1 of a segment's control triangle, where its end tangents meet ahead of both ends;
/// nullopt for a straight segment or one turning by pi or more, which has none (the
/// edits below work on control triangles).
std::optional<Vec2> controlApex(const LaSegment& segment);

/// Why segment `piece` of a fitted curve cannot take another alpha (withSegmentAlpha), or
/// "" where it can: its alpha is fixed by an inflection end or it is straight, or it has
/// no control triangle.
std::string whyAlphaIsFixed(const FitResult& fit, std::size_t piece);

/// The user steering one segment: gives segment `piece` of a fitted curve the alpha
/// `alpha` and solves G2 again over its corner-to-corner part (joint positions kept,
/// joint tangents free; the other segments keep their alphas). Returns the updated
/// result, or std::nullopt with `why` set if that piece is an inflection piece (its
/// alpha is fixed by the inflection) or no G2 chain exists with that alpha.
std::optional<FitResult> withSegmentAlpha(const FitResult& fit, std::size_t piece, double alpha,
                                          const FitOptions& options, std::string* why = nullptr);

/// The user dragging a joint: moves joint `joint` (the start of segment `joint`; the
/// open curve's end is joint n, n the number of segments) to `position` and solves G2
/// again over its corner-to-corner part (alphas kept, tangents free). A corner moves
/// both parts that meet there and stays a corner. std::nullopt with `why` if no G2
/// chain exists there.
std::optional<FitResult> withJointMoved(const FitResult& fit, std::size_t joint, const Vec2& position,
                                        const FitOptions& options, std::string* why = nullptr);

/// The user dragging the apex of segment `piece`'s control triangle (Q1, where its end
/// tangents meet) to `apex`: the tangents at both its ends point along the triangle's
/// new sides and stay so; G2 is solved again over its part with those two joints
/// sliding along their tangent lines (so the apex stays where it was put) and the
/// other joints' tangents free. std::nullopt with `why` if no G2 chain exists.
std::optional<FitResult> withApexMoved(const FitResult& fit, std::size_t piece, const Vec2& apex,
                                       const FitOptions& options, std::string* why = nullptr);

}  // namespace la
