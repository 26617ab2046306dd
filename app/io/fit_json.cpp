#include "app/io/fit_json.h"

#include <cmath>

#include "core/curve_json.h"

namespace la {
namespace {

nlohmann::json points(const std::vector<Vec2>& pts) {
  nlohmann::json a = nlohmann::json::array();
  for (const Vec2& p : pts) a.push_back({p.x(), p.y()});
  return a;
}

// JSON has no NaN or infinity: write null (or "inf" where the format says so).
nlohmann::json number(double v) {
  if (std::isnan(v)) return nullptr;
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

nlohmann::json reportToJson(const SolveReport& r) {
  return {{"status", toString(r.status)}, {"iterations", r.iterations}, {"residual", number(r.residual)},
          {"message", r.message}};
}

}  // namespace

nlohmann::json qualityToJson(const QualityFigures& q) {
  return {{"max_dev", q.max_dev},
          {"rms_dev", q.rms_dev},
          {"max_dev_relative", q.diagonal > 0 ? q.max_dev / q.diagonal : 0.0},
          {"g0_gap", q.g0_gap},
          {"g1_gap", q.g1_gap},
          {"g2_gap", q.g2_gap},
          {"extrema", q.extrema},
          {"inflections", q.inflections},
          {"extrema_dense", q.extrema_dense},
          {"extrema_per_part", q.extrema_per_part},
          {"max_extrema_per_part", q.max_extrema_per_part},
          {"max_abs_kappa", q.max_abs_kappa},
          {"min_radius", number(q.min_radius)},
          {"segments", q.segments},
          {"corners", q.corners},
          {"diagonal", q.diagonal}};
}

nlohmann::json fitResultToJson(const FitResult& r, const Stroke& raw, bool with_stages) {
  nlohmann::json j = curveToJson(r.curve);
  nlohmann::json quality = qualityToJson(r.quality);
  nlohmann::json r2 = nlohmann::json::array();
  for (const PieceReport& p : r.pieces) r2.push_back(number(p.lcg_r2));
  quality["lcg_r2"] = r2;
  quality["tolerance"] = r.tolerance;
  quality["tolerance_requested"] = r.requested_tolerance;  // (below `tolerance` where the noise floor raised it)
  quality["max_dev_all_points"] = r.max_dev_all_points;   // (max_dev: over the points the clean-up kept)
  quality["left_out_fraction"] = r.cleaned.left_out_fraction;
  nlohmann::json left_out = nlohmann::json::array();
  for (const LeftOutPoint& l : r.cleaned.left_out) left_out.push_back({{"sample", l.sample}, {"why", toString(l.why)}});
  j["quality"] = quality;
  j["left_out"] = left_out;
  j["timings_ms"] = {{"cleanup", r.timings.cleanup_ms},   {"smoothing", r.timings.smoothing_ms},
                     {"segmentation", r.timings.segmentation_ms}, {"alpha", r.timings.alpha_ms},
                     {"g2", r.timings.g2_ms},             {"polish", r.timings.polish_ms},
                     {"quality", r.timings.quality_ms},
                     {"total", r.timings.total_ms},       {"points", raw.samples.size()}};
  j["solvers"] = {{"smoothing", reportToJson(r.smoothing)}, {"g2", reportToJson(r.g2)}};
  if (!r.warnings.empty()) j["warnings"] = r.warnings;
  if (!with_stages) return j;

  nlohmann::json stages;
  std::vector<Vec2> raw_points;
  for (const StrokeSample& s : raw.samples) raw_points.push_back(s.p);
  stages["raw"] = points(raw_points);
  stages["cleaned"] = {{"points", points(r.cleaned.points)},
                       {"corners", r.cleaned.corners},
                       {"closed", r.cleaned.closed},
                       {"trimmed_start", r.cleaned.trimmed_start},
                       {"trimmed_end", r.cleaned.trimmed_end},
                       {"removed_overlap", r.cleaned.removed_overlap},
                       {"source", r.cleaned.source},
                       {"removed_invalid", r.cleaned.removed_invalid},
                       {"removed_duplicates", r.cleaned.removed_duplicates},
                       {"removed_resampled", r.cleaned.removed_resampled}};
  nlohmann::json splines = nlohmann::json::array();
  for (const CubicBSpline& s : r.splines)
    splines.push_back({{"degree", 3}, {"periodic", s.isPeriodic()}, {"knots", s.knots()}, {"control", points(s.control())}});
  stages["splines"] = splines;
  nlohmann::json splits = nlohmann::json::array();
  for (std::size_t part = 0; part < r.splits.size(); ++part)
    for (const SplitPoint& sp : r.splits[part])
      splits.push_back({{"part", part}, {"t", sp.t}, {"kind", toString(sp.kind)}, {"kappa", sp.kappa}});
  stages["splits"] = splits;
  nlohmann::json pieces = nlohmann::json::array();
  for (const PieceReport& p : r.pieces)
    pieces.push_back({{"part", p.part},
                      {"kind", toString(p.kind)},
                      {"start", toString(p.start_kind)},
                      {"end", toString(p.end_kind)},
                      {"lcg_alpha", number(p.lcg_alpha)},
                      {"lcg_r2", number(p.lcg_r2)},
                      {"alpha", number(p.alpha)},
                      {"alpha_moved", p.alpha_moved}});
  stages["pieces"] = pieces;
  j["stages"] = stages;
  return j;
}

}  // namespace la
