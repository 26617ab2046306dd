#include "app/gui/construction.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <utility>
#include <stdexcept>

#include "core/alp_curve_json.h"
#include "core/alp_hermite.h"
#include "core/compound_rhythm.h"
#include "core/curve_json.h"
#include "core/three_point_segment.h"
#include "core/triple_la_hermite.h"

namespace la::gui {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kSamplesPerSegment = 160;

nlohmann::json solveToJson(const SolveReport& report) {
  return {{"status", toString(report.status)}, {"iterations", report.iterations}, {"residual", report.residual},
          {"message", report.message}};
}

nlohmann::json pointsToJson(const std::vector<Vec2>& points) {
  nlohmann::json j = nlohmann::json::array();
  for (const Vec2& q : points) j.push_back({q.x(), q.y()});
  return j;
}

void addSamples(ConstructionResult& r, const CurveSamples& samples) {
  for (std::size_t i = 0; i < samples.size(); ++i) {
    r.points.push_back(samples.point[i]);
    r.normals.push_back(Vec2(-samples.tangent[i].y(), samples.tangent[i].x()));
    r.kappa.push_back(samples.kappa[i]);
    r.s.push_back(samples.s[i]);
  }
}

// The drawing and export parts of a result made of LA segments.
void fillFromCurve(ConstructionResult& r, const Curve& curve, const SolveReport& report, nlohmann::json solve) {
  r.ok = true;
  r.message = report.message;
  r.curve = curve;
  CurveSamples samples;
  double s0 = 0.0;
  for (const CurvePiece& piece : curve.pieces) {
    r.joints.push_back(s0);
    piece.segment.sample(kSamplesPerSegment, samples, s0);
    s0 += piece.segment.length();
  }
  addSamples(r, samples);
  r.json = curveToJson(curve);
  solve.update(solveToJson(report));
  r.json["solve"] = std::move(solve);
}

ConstructionResult failed(const SolveReport& report) {
  ConstructionResult r;
  r.message = std::string(toString(report.status)) + ": " + report.message;
  r.json = {{"error", r.message}};
  return r;
}

ConstructionResult solveSegment(const Construction& c) {
  const SegmentSolve s = solveThreePointSegment(c.parameter("alpha"), c.handles[0], c.handles[1], c.handles[2]);
  if (!s.report.usable()) return failed(s.report);
  ConstructionResult r;
  Curve curve;
  curve.pieces.push_back({*s.segment, false});
  fillFromCurve(r, curve, s.report, {{"construction", "segment"}, {"control_points", pointsToJson(c.handles)}});
  return r;
}

ConstructionResult solveCompound(const Construction& c) {
  const double joint_deg = c.parameter("joint_angle");
  const double joint_theta = std::isnan(joint_deg) ? kNaN : joint_deg * std::numbers::pi / 180.0;
  const CompoundRhythmSolve s = solveCompoundRhythm(c.parameter("alpha0"), c.parameter("alpha1"),
                                                    {c.handles[0], c.handles[1], c.handles[2], c.handles[3]}, joint_theta);
  if (!s.report.usable()) return failed(s.report);
  ConstructionResult r;
  fillFromCurve(r, *s.curve, s.report,
                {{"construction", "compound"}, {"control_points", pointsToJson(c.handles)}, {"joint_theta", s.joint_theta}});
  return r;
}

// The end conditions of the Hermite-type kinds: P0 = handle 0 heading towards handle 1,
// P1 = handle 3 arriving from handle 2; curvatures given relative to the chord. The end
// angle is taken within half a turn of the start's, the winding a designer means.
std::optional<std::pair<HermiteEnd, HermiteEnd>> hermiteEnds(const Construction& c) {
  const double chord = (c.handles[3] - c.handles[0]).norm();
  if (!(chord > 0.0) || c.handles[1] == c.handles[0] || c.handles[3] == c.handles[2]) return std::nullopt;
  HermiteEnd a, b;
  a.point = c.handles[0];
  a.theta = angleOf(c.handles[1] - c.handles[0]);
  a.kappa = c.parameter("kappa_start") / chord;
  b.point = c.handles[3];
  b.theta = a.theta + wrapAngle(angleOf(c.handles[3] - c.handles[2]) - a.theta);
  b.kappa = c.parameter("kappa_end") / chord;
  return std::pair{a, b};
}

ConstructionResult noEnds() {
  return failed({SolveStatus::kBadInput, 0, kNaN, "the ends coincide, or a tangent handle sits on its end point"});
}

ConstructionResult solveHermite(const Construction& c) {
  const auto ends = hermiteEnds(c);
  if (!ends) return noEnds();
  const TripleLaHermiteSolve s = solveTripleLaHermite(c.parameter("alpha"), ends->first, ends->second);
  if (!s.report.usable()) return failed(s.report);
  ConstructionResult r;
  fillFromCurve(r, *s.curve, s.report, {{"construction", "hermite"}, {"control_points", pointsToJson(c.handles)}});
  return r;
}

ConstructionResult solveAlp(const Construction& c) {
  const auto ends = hermiteEnds(c);
  if (!ends) return noEnds();
  AlpShape shape;
  shape.degree = static_cast<int>(std::lround(c.parameter("degree")));
  shape.p = c.parameter("p");
  shape.rational = c.parameter("rational") > 0.5;
  shape.w_e = c.parameter("w_e");
  shape.p_w = c.parameter("p_w");
  const int continuity = c.parameter("g2") > 0.5 ? 2 : 1;
  const AlpSolve s = solveAlpHermite(ends->first, ends->second, continuity, shape);
  if (!s.report.usable()) return failed(s.report);
  ConstructionResult r;
  r.ok = true;
  r.alp = *s.curve;
  r.message = s.report.message + (s.check.has_inflection ? "; inflection inside" : "") +
              (s.check.monotone ? "; curvature monotone" : "; " + std::to_string(s.check.extrema.size()) + " curvature extrema");
  CurveSamples samples;
  s.curve->sample(kSamplesPerSegment * 2, samples);
  addSamples(r, samples);
  r.joints = {0.0};
  r.json = alpCurveToJson(*s.curve, s.check);
  nlohmann::json solve = {{"construction", "alp"}, {"control_points", pointsToJson(c.handles)}, {"continuity", continuity}};
  solve.update(solveToJson(s.report));
  r.json["solve"] = std::move(solve);
  return r;
}

}  // namespace

const char* toString(ConstructionKind kind) {
  switch (kind) {
    case ConstructionKind::kSegment: return "segment";
    case ConstructionKind::kCompound: return "compound";
    case ConstructionKind::kHermite: return "hermite";
    case ConstructionKind::kAlp: return "alp";
  }
  return "unknown";
}

std::optional<ConstructionKind> constructionKindFromString(const std::string& name) {
  for (ConstructionKind k : {ConstructionKind::kSegment, ConstructionKind::kCompound, ConstructionKind::kHermite,
                             ConstructionKind::kAlp})
    if (name == toString(k)) return k;
  return std::nullopt;
}

const char* displayName(ConstructionKind kind) {
  switch (kind) {
    case ConstructionKind::kSegment: return "LA segment (3 control points)";
    case ConstructionKind::kCompound: return "Compound-rhythm LA curve (4 control points)";
    case ConstructionKind::kHermite: return "Triple-LA G2 Hermite curve";
    case ConstructionKind::kAlp: return "ALP curve (explicit Bezier curvature)";
  }
  return "unknown";
}

const std::vector<ParameterSpec>& parameterSpecs(ConstructionKind kind) {
  using Type = ParameterSpec::Type;
  static const ParameterSpec kappa_start{"kappa_start", "start curvature", "curvature at P0 times the chord |P1 - P0|; left turn positive",
                                         -10.0, 10.0, 1.0};
  static const ParameterSpec kappa_end{"kappa_end", "end curvature", "curvature at P1 times the chord |P1 - P0|", -10.0, 10.0, 2.0};
  static const std::vector<ParameterSpec> segment = {
      {"alpha", "alpha", "slope of the LCG: -1 clothoid, 1 log spiral, 2 involute", -3.0, 3.0, -1.0}};
  static const std::vector<ParameterSpec> compound = {
      {"alpha0", "alpha, first piece", "LCG slope of the piece from Q0 to the joint", -3.0, 3.0, 0.5},
      {"alpha1", "alpha, second piece", "LCG slope of the piece from the joint to Q3", -3.0, 3.0, -0.5},
      {"joint_angle", "joint tangent (deg)", "tangent direction at the joint; auto: from mid(Q0,Q1) to mid(Q2,Q3)", -180.0,
       180.0, 0.0, 1, true}};
  static const std::vector<ParameterSpec> hermite = {
      {"alpha", "alpha", "LCG slope of all three pieces (-1: a triple clothoid)", -3.0, 3.0, -1.0}, kappa_start, kappa_end};
  static const std::vector<ParameterSpec> alp = {
      {"degree", "degree n", "degree of the Bezier curvature function (G2 needs n >= 3)", 1.0, 9.0, 3.0, 0},
      {"g2", "G2 (end curvatures)", "meet the end curvatures too; off: G1, end tangents only", 0.0, 1.0, 0.0, 0, false,
       Type::kToggle},
      kappa_start, kappa_end,
      {"p", "p", "shape of the free control curvatures (seed 000 eq. 12): 0 linear, within [-1, 1] monotone", -1.0, 1.0,
       0.0},
      {"rational", "rational", "rational curvature function: weights from w_e and p_w", 0.0, 1.0, 0.0, 0, false,
       Type::kToggle},
      {"w_e", "w_e", "weight of the last control curvature (the first is 1)", 0.1, 5.0, 1.0},
      {"p_w", "p_w", "shape of the free weights, as p for the curvatures", -2.0, 2.0, 0.0}};
  switch (kind) {
    case ConstructionKind::kSegment: return segment;
    case ConstructionKind::kCompound: return compound;
    case ConstructionKind::kHermite: return hermite;
    case ConstructionKind::kAlp: return alp;
  }
  return segment;
}

double Construction::parameter(const std::string& key) const {
  if (auto it = parameters.find(key); it != parameters.end()) return it->second;
  for (const ParameterSpec& spec : parameterSpecs(kind))
    if (spec.key == key) return spec.optional ? kNaN : spec.initial;
  return kNaN;
}

Construction Construction::create(ConstructionKind kind, const Vec2& center, double size) {
  Construction c;
  c.kind = kind;
  for (const ParameterSpec& spec : parameterSpecs(kind)) c.parameters[spec.key] = spec.optional ? kNaN : spec.initial;
  auto at = [&](double x, double y) { return Vec2(center + size * Vec2(x, y)); };
  switch (kind) {
    case ConstructionKind::kSegment: c.handles = {at(-1, 0.6), at(0.1, 0.6), at(1, -0.6)}; break;
    case ConstructionKind::kCompound: c.handles = {at(-1, 0.6), at(-0.2, 0.75), at(0.6, 0.3), at(1, -0.6)}; break;
    case ConstructionKind::kHermite:
    case ConstructionKind::kAlp: c.handles = {at(-1, 0), at(-0.5, 0.5), at(0.5, 0.5), at(1, 0)}; break;
  }
  c.solve();
  return c;
}

void Construction::solve() {
  for (const Vec2& q : handles)
    if (!allFinite(q)) {
      result = failed({SolveStatus::kBadInput, 0, kNaN, "a handle is not a finite point"});
      return;
    }
  switch (kind) {
    case ConstructionKind::kSegment: result = solveSegment(*this); return;
    case ConstructionKind::kCompound: result = solveCompound(*this); return;
    case ConstructionKind::kHermite: result = solveHermite(*this); return;
    case ConstructionKind::kAlp: result = solveAlp(*this); return;
  }
  result = failed({SolveStatus::kBadInput, 0, kNaN, "unknown construction"});
}

nlohmann::json Construction::toJson() const {
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [key, value] : parameters) params[key] = std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value);
  return {{"kind", toString(kind)}, {"handles", pointsToJson(handles)}, {"parameters", params}, {"curve", result.json}};
}

Construction Construction::fromJson(const nlohmann::json& json, const std::string& where) {
  Construction c;
  try {
    const std::string name = json.at("kind").get<std::string>();
    const auto kind = constructionKindFromString(name);
    if (!kind) throw std::runtime_error(where + ".kind: unknown construction '" + name + "'");
    c = create(*kind, Vec2(0, 0), 1.0);
    const auto& handles = json.at("handles");
    if (!handles.is_array() || handles.size() != c.handles.size())
      throw std::runtime_error(where + ".handles: expected " + std::to_string(c.handles.size()) + " points for a " + name);
    for (std::size_t i = 0; i < handles.size(); ++i)
      c.handles[i] = Vec2(handles[i].at(0).get<double>(), handles[i].at(1).get<double>());
    const nlohmann::json parameters = json.value("parameters", nlohmann::json::object());
    for (const auto& [key, value] : parameters.items())
      if (c.parameters.count(key)) c.parameters[key] = value.is_null() ? kNaN : value.get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(where + ": " + e.what());
  }
  c.solve();
  return c;
}

}  // namespace la::gui
