#include "fitting/user_edits.h"

#include <cmath>
#include <functional>
#include <numbers>

#include "fitting/chain.h"
#include "fitting/fit_context.h"

namespace la {

namespace {

// Re-solves G2 over the corner-to-corner part holding `piece`, its chain taken from
// the fitted segments, after `edit` changed the chain (index of the piece in the chain;
// it returns why the edit makes no sense, or "").
std::optional<FitResult> resolvePart(const FitResult& fit, std::size_t piece, const FitOptions& options,
                                     const std::function<std::string(Chain&, std::size_t)>& edit, std::string* why) {
  const int part = fit.pieces[piece].part;
  std::size_t first = piece, last = piece;
  while (first > 0 && fit.pieces[first - 1].part == part) --first;
  while (last + 1 < fit.pieces.size() && fit.pieces[last + 1].part == part) ++last;
  Chain chain;
  chain.closed = fit.curve.closed && first == 0 && last + 1 == fit.curve.pieces.size() &&
                 !fit.curve.pieces.front().corner;
  for (std::size_t i = first; i <= last; ++i) {
    const LaSegment& seg = fit.curve.pieces[i].segment;
    chain.joints.push_back(seg.start());
    chain.angles.push_back(i == first ? seg.theta0() : chain.angles.back() + wrapAngle(seg.theta0() - chain.angles.back()));
    // (a circular arc re-solved between moved ends is no arc: it takes the options'
    // largest alpha, the family's nearest to a circle's, as its law)
    const bool arc = seg.isCircular() && !seg.isStraight();
    chain.pieces.push_back({fit.pieces[i].kind, arc ? options.max_alpha : seg.alpha()});
  }
  const LaSegment& end = fit.curve.pieces[last].segment;
  chain.joints.push_back(chain.closed ? chain.joints.front() : end.end());
  chain.angles.push_back(chain.angles.back() + wrapAngle(end.theta(end.length()) - chain.angles.back()));
  if (std::string refused = edit(chain, piece - first); !refused.empty()) {
    if (why) *why = refused;
    return std::nullopt;
  }
  const G2Options g2 = g2OptionsOf(options, fit.quality.diagonal);
  const G2Result res = makeG2(chain, g2);
  if (res.segments.empty() || !res.report.usable()) {
    if (why) *why = "no G2 curve through that change: " + res.report.message;
    return std::nullopt;
  }
  FitResult out = fit;
  for (std::size_t i = first; i <= last; ++i) {
    out.curve.pieces[i].segment = res.segments[i - first];
    out.pieces[i].alpha = res.segments[i - first].alpha();
  }
  out.g2 = res.report;
  out.quality = measureQuality(out.curve, out.cleaned.points);
  return out;
}

}  // namespace

std::optional<Vec2> controlApex(const LaSegment& segment) {
  if (segment.isStraight() || !(std::abs(segment.turning()) < std::numbers::pi)) return std::nullopt;
  const Vec2 a = segment.start(), b = segment.end(), u = segment.tangent(0.0), v = segment.tangent(segment.length());
  const double det = cross(u, v);
  if (det == 0.0) return std::nullopt;
  // a + s u = b - t v, both s and t positive
  const double s = cross(b - a, v) / det, t = cross(u, b - a) / det;
  if (!(s > 0.0 && t > 0.0)) return std::nullopt;
  return Vec2(a + s * u);
}

std::string whyAlphaIsFixed(const FitResult& fit, std::size_t piece) {
  if (piece >= fit.pieces.size() || piece >= fit.curve.pieces.size()) return "no such segment";
  if (fit.pieces[piece].kind != PieceKind::kThreePoint || std::isinf(fit.curve.pieces[piece].segment.alpha()))
    return "this segment's alpha is fixed (an inflection end or a straight piece)";
  if (!controlApex(fit.curve.pieces[piece].segment)) return "this segment turns by pi or more: it has no control triangle";
  return "";
}

std::optional<FitResult> withSegmentAlpha(const FitResult& fit, std::size_t piece, double alpha,
                                          const FitOptions& options, std::string* why) {
  if (std::string fixed = whyAlphaIsFixed(fit, piece); !fixed.empty()) {
    if (why) *why = fixed;
    return std::nullopt;
  }
  return resolvePart(fit, piece, options, [&](Chain& c, std::size_t i) {
    c.pieces[i].alpha = alpha;
    return std::string();
  }, why);
}

std::optional<FitResult> withJointMoved(const FitResult& fit, std::size_t joint, const Vec2& position,
                                        const FitOptions& options, std::string* why) {
  const std::size_t n = fit.curve.pieces.size();
  if (joint > n || (joint == n && fit.curve.closed) || n == 0 || fit.pieces.size() != n || !allFinite(position)) {
    if (why) *why = "no such joint";
    return std::nullopt;
  }
  FitResult out = fit;
  // The part that ends here: the open curve's last part, or the part before a corner
  // (parts meet only at corners, G0, so each is solved on its own).
  const bool corner = joint < n && fit.curve.pieces[joint].corner;
  if (joint == n || (corner && (joint > 0 || fit.curve.closed))) {
    auto ended = resolvePart(out, joint == 0 ? n - 1 : joint - 1, options, [&](Chain& c, std::size_t i) {
      c.joints[i + 1] = position;
      return std::string();
    }, why);
    if (!ended) return std::nullopt;
    out = std::move(*ended);
  }
  if (joint == n) return out;
  return resolvePart(out, joint, options, [&](Chain& c, std::size_t i) {
    c.joints[i] = position;
    if (c.closed && i == 0) c.joints.back() = position;
    return std::string();
  }, why);
}

std::optional<FitResult> withApexMoved(const FitResult& fit, std::size_t piece, const Vec2& apex,
                                       const FitOptions& options, std::string* why) {
  if (piece >= fit.pieces.size() || piece >= fit.curve.pieces.size() || !allFinite(apex)) {
    if (why) *why = "no such segment";
    return std::nullopt;
  }
  if (!controlApex(fit.curve.pieces[piece].segment)) {
    if (why) *why = "this segment has no control triangle (straight, or turning by pi or more)";
    return std::nullopt;
  }
  return resolvePart(fit, piece, options, [&](Chain& c, std::size_t i) -> std::string {
    const std::size_t n = c.size();
    const Vec2 a = c.joints[i], b = c.joints[i + 1];
    if ((apex - a).norm() == 0.0 || (b - apex).norm() == 0.0) return "the apex must differ from the segment's ends";
    c.sliding.assign(c.joints.size(), false);
    // Each end's tangent now points along the triangle's side (kept within a turn of the
    // old angle); an end that has a curvature equation slides along that side.
    auto fix = [&](std::size_t j, const Vec2& direction) {
      const double angle = c.angles[j] + wrapAngle(std::atan2(direction.y(), direction.x()) - c.angles[j]);
      if (c.closed && (j == 0 || j == n)) {  // joint 0 is joint n, one turn apart
        const double shift = angle - c.angles[j];
        c.angles[0] += shift;
        c.angles[n] += shift;
        c.sliding[0] = c.sliding[n] = true;
      } else {
        c.angles[j] = angle;
        c.sliding[j] = j > 0 && j < n;
      }
    };
    fix(i, apex - a);
    fix(i + 1, b - apex);
    return std::string();
  }, why);
}

}  // namespace la
