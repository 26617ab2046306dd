#include "app/gui/oversketch.h"

#include <algorithm>
#include <cmath>

#include "app/gui/selection.h"

namespace la::gui {
namespace {

// Old samples within this many reaches of a join (along the old stroke) are dropped: the
// new stroke starts up to one reach beside the old one, and over two reaches that step
// turns by at most atan(1/2) = 27 degrees, well under what the clean-up calls a corner.
// A new stroke that meets the old one at a real angle still makes a corner.
constexpr double kBlendReaches = 2.0;

struct Polyline {
  std::vector<StrokeSample> samples;
  std::vector<double> s;  // arc length at each sample
  double length = 0.0;    // a closed polyline's includes the closing step
  bool closed = false;
};

Polyline polylineOf(const DocumentStroke& old) {
  Polyline out;
  out.samples = oversketchPolyline(old);
  out.closed = old.fit && old.fit->curve.closed;
  double s = 0.0;
  for (std::size_t i = 0; i < out.samples.size(); ++i) {
    if (i > 0) s += (out.samples[i].p - out.samples[i - 1].p).norm();
    out.s.push_back(s);
  }
  out.length = s + (out.closed && !out.samples.empty() ? (out.samples.front().p - out.samples.back().p).norm() : 0.0);
  return out;
}

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b, double* fraction) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  if (fraction) *fraction = t;
  return (a + t * ab - p).norm();
}

// The point of the polyline nearest p: its arc length and distance.
OversketchJoin project(const Polyline& line, const Vec2& p) {
  OversketchJoin best{0.0, INFINITY};
  const std::size_t n = line.samples.size();
  const std::size_t steps = line.closed ? n : n - 1;
  for (std::size_t i = 0; i < steps; ++i) {
    const std::size_t j = (i + 1) % n;
    double f = 0.0;
    const double d = distanceToSegment(p, line.samples[i].p, line.samples[j].p, &f);
    const double step = (line.samples[j].p - line.samples[i].p).norm();
    if (d < best.distance) best = {line.s[i] + f * step, d};
  }
  return best;
}

// Distance from p to the fitted curve (what the user sees), or infinity without a fit.
double distanceToCurve(const std::vector<Vec2>& outline, const Vec2& p) {
  double best = INFINITY;
  for (std::size_t i = 1; i < outline.size(); ++i)
    best = std::min(best, distanceToSegment(p, outline[i - 1], outline[i], nullptr));
  return best;
}

// The join of end point p, if p is within reach of the curve or the raw polyline.
std::optional<OversketchJoin> joinOf(const Polyline& line, const std::vector<Vec2>& outline, const Vec2& p,
                                     double reach) {
  OversketchJoin j = project(line, p);
  j.distance = std::min(j.distance, distanceToCurve(outline, p));
  if (j.distance <= reach) return j;
  return std::nullopt;
}

// Appends samples, keeping time stamps increasing across the parts (the parts were drawn
// at different times, and a reversed part runs backwards in time); where a part has no
// time stamps the result has none.
void appendPart(std::vector<StrokeSample>& out, std::vector<StrokeSample> part, bool reverse) {
  if (reverse) std::reverse(part.begin(), part.end());
  for (std::size_t i = 0; i < part.size(); ++i) {
    StrokeSample q = part[i];
    if (!out.empty()) {
      const double dt = i > 0 ? std::abs(part[i].t - part[i - 1].t)
                              : (out.size() > 1 ? out.back().t - out[out.size() - 2].t : 1.0);
      q.t = out.back().t + (std::isfinite(dt) ? dt : NAN);
    }
    out.push_back(q);
  }
}

// The old samples whose arc length, measured forward from `from` (wrapping on a closed
// polyline), lies in (blend, span - blend), in that order.
std::vector<StrokeSample> keptArc(const Polyline& line, double from, double span, double blend, std::size_t* first,
                                  std::size_t* last) {
  std::vector<std::pair<double, std::size_t>> kept;
  for (std::size_t i = 0; i < line.samples.size(); ++i) {
    double u = line.s[i] - from;
    if (line.closed) u = std::fmod(u + line.length, line.length);
    if (u > blend && u < span - blend) kept.emplace_back(u, i);
  }
  std::sort(kept.begin(), kept.end());
  std::vector<StrokeSample> out;
  for (const auto& [u, i] : kept) out.push_back(line.samples[i]);
  if (first) *first = kept.empty() ? 0 : kept.front().second;
  if (last) *last = kept.empty() ? 0 : kept.back().second + 1;
  return out;
}

}  // namespace

std::vector<StrokeSample> oversketchPolyline(const DocumentStroke& old) {
  if (!old.fit || !old.fit->curve.closed) return old.raw.samples;
  std::vector<StrokeSample> loop;
  for (std::size_t i : old.fit->cleaned.source)
    if (i < old.raw.samples.size()) loop.push_back(old.raw.samples[i]);
  return loop;
}

std::optional<Oversketch> oversketch(const DocumentStroke& old, const Stroke& drawn, double reach) {
  const Polyline line = polylineOf(old);
  if (drawn.samples.size() < 2 || line.samples.size() < 2 || !(line.length > 0.0)) return std::nullopt;
  const std::vector<Vec2> outline = old.fit ? strokeOutline(old) : std::vector<Vec2>{};
  Oversketch out;
  out.start = joinOf(line, outline, drawn.samples.front().p, reach);
  out.end = joinOf(line, outline, drawn.samples.back().p, reach);
  if (!out.start && !out.end) return std::nullopt;
  const double blend = kBlendReaches * reach, L = line.length;
  const std::vector<StrokeSample>& fresh = drawn.samples;
  std::vector<StrokeSample>& raw = out.raw.samples;
  out.raw.profile = old.raw.profile;
  std::size_t unused = 0;

  if (line.closed) {
    if (!out.start || !out.end) return std::nullopt;
    const double a = out.start->s, b = out.end->s;
    const double forward = std::fmod(b - a + L, L);  // from a to b along the loop
    // The new stroke replaces the shorter arc; the kept arc runs on from its far join.
    out.reversed = forward > 0.5 * L;
    const double kept_from = out.reversed ? a : b, kept_span = L - (out.reversed ? L - forward : forward);
    appendPart(raw, fresh, out.reversed);
    appendPart(raw, keptArc(line, kept_from, kept_span, blend, &out.kept_after, &out.kept_before), false);
    return out;
  }

  const double end_zone = blend + reach;  // a join this near an end is at that end
  auto at_start = [&](double s) { return s <= end_zone; };
  auto at_end = [&](double s) { return s >= L - end_zone; };
  // the old samples before s - blend, and after s + blend (open: keptArc does not wrap)
  auto before = [&](double s) { return keptArc(line, -blend - 1.0, s + blend + 1.0, blend, &unused, &out.kept_before); };
  auto after = [&](double s) { return keptArc(line, s, L - s + blend + 1.0, blend, &out.kept_after, &unused); };
  if (out.start && out.end) {
    double a = out.start->s, b = out.end->s;
    if ((at_end(a) && at_start(b)) || (at_start(a) && at_end(b))) {  // joins the two ends: closes it
      out.closes = true;
      out.reversed = at_start(a);
      appendPart(raw, before(out.reversed ? b : a), false);
      appendPart(raw, fresh, out.reversed);
      out.kept_after = line.samples.size();
      return out;
    }
    out.reversed = a > b;
    if (out.reversed) std::swap(a, b);
    appendPart(raw, before(a), false);
    appendPart(raw, fresh, out.reversed);
    appendPart(raw, after(b), false);
    return out;
  }
  // One join: from there to the nearer end of the old stroke goes.
  const bool from_start = out.start.has_value();
  const double j = from_start ? out.start->s : out.end->s;
  const bool keep_head = j >= 0.5 * L;  // the join is nearer the end: the head stays
  // (the new stroke runs away from the join: the old stroke continues into it where its
  // start joins and the head stays, or where its end joins and the tail stays)
  out.reversed = keep_head != from_start;
  if (keep_head) {
    appendPart(raw, before(j), false);
    appendPart(raw, fresh, out.reversed);
    out.kept_after = line.samples.size();
  } else {
    appendPart(raw, fresh, out.reversed);
    appendPart(raw, after(j), false);
    out.kept_before = 0;
  }
  return out;
}

std::optional<OversketchTarget> findOversketch(const Document& document, const Stroke& drawn, double reach) {
  std::optional<OversketchTarget> best;
  auto rank = [](const Oversketch& o) {  // two joins first, then the nearer
    const double d = (o.start ? o.start->distance : 0.0) + (o.end ? o.end->distance : 0.0);
    return std::make_pair(o.start && o.end ? 0 : 1, d);
  };
  for (std::size_t k = 0; k < document.strokes().size(); ++k) {
    std::optional<Oversketch> o = oversketch(document.strokes()[k], drawn, reach);
    if (o && (!best || rank(*o) < rank(best->splice))) best = OversketchTarget{k, std::move(*o)};
  }
  return best;
}

}  // namespace la::gui
