#include "fitting/one_segment.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fitting/model_selection.h"
#include "fitting/spline_chain.h"
#include "fitting/stage7.h"

namespace la {
namespace {

// A part beside a corner (its chain is fitted with its neighbours' across the corner
// after) is tried as one segment only where it turns at least this far: the outer turns
// of a spiral whose tight centre the bound on the radius made a corner (at a loose
// tolerance, a logarithmic spiral of 2.5 turns came out as 18 segments, 1.3 tolerances
// off, where one keeps a twentieth of it). Drawn sides that turn past max_turning are
// rarely one segment: trying each cost 6% of the shared data's time for 8 segments
// fewer and 8 extrema more.
constexpr double kCornerPartTurning = 2.0 * std::numbers::pi;

// The chords' directions along the points (`angle[k]` at arc length s[k]) against an LA
// segment's tangent there, of one alpha and the points' length; the unknowns are log
// |kappa| at its ends (of the turning's sign) and its start tangent. Ceres differentiates
// it numerically: the segment's tangent angle is a closed form, cheap to evaluate.
struct TurningProfile {
  double alpha, length, sign;
  const std::vector<double>* s;
  const std::vector<double>* angle;
  bool operator()(const double* x, double* residual) const {
    try {
      const LaSegment seg(alpha, length, Vec2::Zero(), x[2], sign * std::exp(x[0]), sign * std::exp(x[1]));
      for (std::size_t k = 0; k < s->size(); ++k) residual[k] = seg.theta((*s)[k]) - (*angle)[k];
      return std::all_of(residual, residual + s->size(), [](double r) { return std::isfinite(r); });
    } catch (const std::invalid_argument&) {
      return false;  // (a step to a curvature the law has no segment for: Ceres steps shorter)
    }
  }
};

// The segment of `alpha` and `length` from `start` whose tangent follows the chords'
// directions best (least squares over the profile, from end curvatures `k0`, `k1` and
// start tangent `theta0`), and the profile's sum of squares left; nullopt where Ceres
// finds no usable solution.
std::optional<std::pair<LaSegment, double>> profileSegment(double alpha, double length, const Vec2& start,
                                                           double theta0, double k0, double k1,
                                                           const std::vector<double>& s, const std::vector<double>& angle) {
  const double sign = k0 < 0.0 ? -1.0 : 1.0;
  double x[3] = {std::log(std::abs(k0)), std::log(std::abs(k1)), theta0};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::NumericDiffCostFunction<TurningProfile, ceres::CENTRAL, ceres::DYNAMIC, 3>(
                               new TurningProfile{alpha, length, sign, &s, &angle}, ceres::TAKE_OWNERSHIP,
                               static_cast<int>(s.size())),
                           nullptr, x);
  // (a curvature whose radius is 1e-4 to 1e4 times the length: beyond, no drawn spiral)
  for (int i = 0; i < 2; ++i) {
    problem.SetParameterLowerBound(x, i, std::log(1e-4 / length));
    problem.SetParameterUpperBound(x, i, std::log(1e4 / length));
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 25;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) return std::nullopt;
  try {
    return std::pair{LaSegment(alpha, length, start, x[2], sign * std::exp(x[0]), sign * std::exp(x[1])),
                     summary.final_cost};
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// The segment read off the points: its total turning (the chords of neighbours `span`
// apart followed along it, `span` long enough that noise cannot turn a chord by much),
// its length, the mean curvature over a few chords at each end, and the alphas whose
// segments with those are about as long as the points; then fitted by least squares,
// from each of those starts until one is within the tolerance, else the closest (held at
// the part's corners as so.fit says). Nullopt where it turns no further than
// `least_turning`, or changes direction inside (an LA segment inflects at an end only).
std::optional<ChainFitResult> oneSegment(const Part& part, const SelectionOptions& so, double noise,
                                         double least_turning) {
  constexpr double kChordNoise = 20.0;  // a chord at least this many noise sigmas long
  constexpr double kEnd = 0.03;        // of the chords at each end, for the end curvatures
  // (five unknowns: a step costs little, and a spiral of several turns starts far off)
  constexpr int kOneSegmentIterations = 40;
  constexpr int kRaceIterations = 8;  // of them, for each start (see the race below)
  constexpr std::size_t kOneSegmentStarts = 3;
  constexpr std::size_t kCurvatureWindows = 8;  // for the test of monotone curvature
  constexpr std::size_t kProfileSamples = 48;   // arc lengths the starts' turning is fitted at
  constexpr double kAlphaStep = 0.25;           // of the grid of alphas the starts are made for
  constexpr int kCoarseAlphaSteps = 4;          // of kAlphaStep, of the profile's first search
  const std::vector<Vec2>& p = part.points;
  const std::size_t m = p.size();
  // (`span` from the median step, then from the chords it gives: where the noise is as
  // large as the step, the steps are twice as long as the points' advance, and chords of
  // that span are half as long as meant)
  const int most = static_cast<int>(m / 8 + 1);
  auto meanChord = [&](std::size_t span) {
    double sum = 0.0;
    for (std::size_t i = 0; i + span < m; ++i) sum += (p[i + span] - p[i]).norm();
    return sum / static_cast<double>(std::max<std::size_t>(1, m - std::min(m, span)));
  };
  std::size_t span = static_cast<std::size_t>(ceilWithin(kChordNoise * noise / std::max(medianStep(p), 1e-300), 1, most));
  double chord = meanChord(span);
  if (chord < kChordNoise * noise) {
    span = static_cast<std::size_t>(ceilWithin(static_cast<double>(span) * kChordNoise * noise / std::max(chord, 1e-300), 1, most));
    chord = meanChord(span);
  }
  if (m < 2 * span + 3) return std::nullopt;
  // Chord i runs from p[i] to p[ends[i]], `span` points on and at least kChordNoise noise
  // sigmas long: where the stroke was drawn slowly (a spiral's centre, sampled densely)
  // shorter chords turn with the noise by up to a radian, and followed along they
  // gathered a whole turn too many or too few.
  std::vector<std::size_t> ends;
  for (std::size_t i = 0, j = span; i < m; ++i) {
    j = std::max(j, i + span);
    while (j < m && (p[j] - p[i]).norm() < kChordNoise * noise) ++j;
    if (j >= m) break;
    ends.push_back(j);
  }
  if (ends.size() < 3) return std::nullopt;
  std::vector<double> angle, chord_length;  // of each chord, followed along
  for (std::size_t i = 0; i < ends.size(); ++i) {
    const double a = angleOf(p[ends[i]] - p[i]);
    angle.push_back(angle.empty() ? a : angle.back() + wrapAngle(a - angle.back()));
    chord_length.push_back((p[ends[i]] - p[i]).norm());
  }
  // (how far noise turns chord i: sqrt(2) noise / its length)
  auto noiseTurn = [&](std::size_t i) { return noise / std::max(chord_length[i], 1e-300); };
  // (the length from the chords, each standing for its steps' advance, each step counted
  // once: noise lengthens the polyline between neighbours)
  double chords = 0.0;
  for (std::size_t i = 0; i < ends.size(); ++i) chords += chord_length[i] / static_cast<double>(ends[i] - i);
  const double length = chords * static_cast<double>(m - 1) / static_cast<double>(ends.size());
  // (a chord's direction is its middle's: the first's half a chord in, the last's half a
  // chord short of the end)
  const std::size_t last = angle.size() - 1;
  const double middles = 0.5 * static_cast<double>(last + ends[last]) - 0.5 * static_cast<double>(ends[0]);
  const double turning = (angle.back() - angle.front()) * static_cast<double>(m - 1) / middles;
  if (!(length > 0.0) || !(std::abs(turning) > least_turning)) return std::nullopt;
  const double sign = turning < 0.0 ? -1.0 : 1.0;
  // (a turn back from the furthest direction so far by more than the noise can turn a
  // chord, sqrt(2) noise / chord per chord, at about 11 sigmas: an inflection inside; a
  // smaller one that is real makes the fit miss. The furthest direction so far is itself
  // a maximum of noisy chords: at 8 sigmas a clothoid of one turn with noise of a fifth of
  // its step turned back by 9 and came out as four segments.)
  std::size_t low = 0;
  for (std::size_t i = 0; i < angle.size(); ++i) {
    if ((angle[i] - angle[low]) * sign < -16.0 * std::max(noiseTurn(i), noiseTurn(low))) return std::nullopt;
    if ((angle[i] - angle[low]) * sign > 0.0) low = i;
  }
  // (an LA segment's curvature is monotone: the turning of successive windows of the
  // chords may not rise and fall again, or fall and rise, by more than a quarter of the
  // largest or four times what noise makes of a window's turning, 2 noise / chord at the
  // window's ends, the shortest chord's)
  const std::size_t window = std::max<std::size_t>(3, angle.size() / kCurvatureWindows);
  std::vector<double> kappa;
  double noisiest = 0.0;
  for (std::size_t i = 0; i + window < angle.size(); i += window) {
    kappa.push_back(std::abs(angle[i + window] - angle[i]));
    noisiest = std::max({noisiest, noiseTurn(i), noiseTurn(i + window)});
  }
  const double largest = *std::max_element(kappa.begin(), kappa.end());
  const double reversal = std::max(0.25 * largest, 8.0 * noisiest);
  double top = kappa.front(), bottom = kappa.front();
  int trend = 0;  // +1 rising, -1 falling, once a change beyond `reversal` shows it
  for (double k : kappa) {
    top = std::max(top, k), bottom = std::min(bottom, k);
    if (trend >= 0 && top - k > reversal) {
      if (trend > 0) return std::nullopt;
      trend = -1, bottom = k;
    } else if (trend <= 0 && k - bottom > reversal) {
      if (trend < 0) return std::nullopt;
      trend = 1, top = k;
    }
  }
  // (the mean curvature over the `end` chords at each end and over the next `end`,
  // extrapolated to the end itself; at least a tenth of the mean, of the turning's sign)
  const std::size_t end = std::max<std::size_t>(3, static_cast<std::size_t>(kEnd * angle.size()));
  if (angle.size() < 2 * end + 1) return std::nullopt;
  // (arc length at each point along the polyline, scaled to `length`: noise lengthens the
  // polyline; and at each chord's middle)
  std::vector<double> along(m, 0.0);
  for (std::size_t i = 1; i < m; ++i) along[i] = along[i - 1] + (p[i] - p[i - 1]).norm();
  for (double& a : along) a *= length / along.back();
  auto middle = [&](std::size_t i) { return 0.5 * (along[i] + along[ends[i]]); };
  const double mean = std::abs(turning) / length;
  // (the curvature from chord a to chord b)
  auto kappaOver = [&](std::size_t a, std::size_t b) { return (angle[b] - angle[a]) / std::max(middle(b) - middle(a), 1e-300); };
  auto endKappa = [&](double first, double second) { return sign * std::max(std::abs(1.5 * first - 0.5 * second), 0.1 * mean); };
  const double k0 = endKappa(kappaOver(0, end), kappaOver(end, 2 * end));
  const double k1 = endKappa(kappaOver(last - end, last), kappaOver(last - 2 * end, last - end));
  // (the chords' tangent at the start: the first chord's, turned back by half of its bend)
  const double theta0 = angle.front() - 0.5 * k0 * chord_length.front();
  // (the alphas whose segments come nearest the points' length, the nearest first: a
  // spiral of several turns has local minima where a start lands on the wrong turn)
  // (the kOneSegmentStarts of `starts` that miss least, the least first)
  auto byMiss = [](const auto& a, const auto& b) { return a.first < b.first; };
  auto keepClosest = [&](std::vector<std::pair<double, LaSegment>>& starts) {
    std::sort(starts.begin(), starts.end(), byMiss);
    if (starts.size() > kOneSegmentStarts) starts.erase(starts.begin() + kOneSegmentStarts, starts.end());
  };
  // (the grid of alphas, j = 0 .. grid_steps; none where the range is empty)
  const int grid_steps = std::max(-1, static_cast<int>(std::floor((so.fit.max_alpha - so.fit.min_alpha) / kAlphaStep + 1e-9)));
  auto gridAlpha = [&](int j) { return so.fit.min_alpha + j * kAlphaStep; };
  std::vector<std::pair<double, LaSegment>> starts;
  for (int j = 0; j <= grid_steps; ++j) {
    try {
      const LaSegment seg = LaSegment::withTurning(gridAlpha(j), turning, p.front(), theta0, k0, k1);
      starts.push_back({std::abs(seg.length() - length), seg});
    } catch (const std::invalid_argument&) {
    }
  }
  keepClosest(starts);
  ChainFitOptions co = so.fit;
  co.min_length = so.tolerance;
  co.max_iterations = kOneSegmentIterations;
  // (each point's foot where its arc length puts it: found from scratch, a point could
  // take its foot on the neighbouring turn of a spiral)
  std::vector<ChainFoot> feet(m, {0, 0.0});
  for (std::size_t i = 0; i < m; ++i) feet[i].u = along[i] / along.back();
  // Starts whose tangent follows the chords' directions (end curvatures and start tangent
  // fitted to the chords at kProfileSamples arc lengths, for each alpha of the grid, the
  // closest first): the end chords alone are noisy, and a spiral's fit from a start 20%
  // off in its end curvatures, or a few degrees off in its start tangent, lands on the
  // wrong turn.
  std::vector<double> profile_s, profile_angle;
  for (std::size_t k = 0; k < kProfileSamples; ++k) {
    const std::size_t j = k * last / (kProfileSamples - 1);
    profile_s.push_back(middle(j));  // (a chord's direction is its middle's)
    profile_angle.push_back(angle[j]);
  }
  // (the profile's sum of squares falls and rises once over the grid of alphas on the
  // drawn spirals and the sampled segments: solved every kCoarseAlphaSteps grid steps
  // first, then between the neighbours of the least of those; all 25 alphas of the grid
  // were most of a one-segment fit's time, up to 15 ms on a drawn stroke)
  std::vector<std::pair<double, LaSegment>> profiled;
  std::vector<bool> profiled_at(static_cast<std::size_t>(grid_steps + 1), false);
  auto profileAt = [&](int j) {
    if (j < 0 || j > grid_steps || profiled_at[static_cast<std::size_t>(j)]) return;
    profiled_at[static_cast<std::size_t>(j)] = true;
    if (auto fitted = profileSegment(gridAlpha(j), length, p.front(), theta0, k0, k1, profile_s, profile_angle))
      profiled.push_back({fitted->second, fitted->first});
  };
  for (int j = 0; j < grid_steps; j += kCoarseAlphaSteps) profileAt(j);
  profileAt(grid_steps);
  if (!profiled.empty()) {
    const auto least = std::min_element(profiled.begin(), profiled.end(), byMiss);
    const int coarse = static_cast<int>(std::lround((least->second.alpha() - so.fit.min_alpha) / kAlphaStep));
    for (int j = coarse - kCoarseAlphaSteps + 1; j < coarse + kCoarseAlphaSteps; ++j) profileAt(j);
  }
  keepClosest(profiled);
  starts.insert(starts.begin(), profiled.begin(), profiled.end());
  // (each start as it is, then with its end shot onto the last point: a spiral's far
  // turns follow its end, but a shot from a poor start curvature bends the law wrongly)
  // (a start already among the tries, to rounding, is not tried again: the fit from it is
  // the same. The shots of different starts solve one problem, the end onto the last
  // point, and most land on one segment: on spirals, a third to a half of the tries.)
  std::vector<LaSegment> tries;
  auto add = [&](const LaSegment& guess) {
    auto near = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); };
    for (const LaSegment& t : tries)
      if (near(t.alpha(), guess.alpha()) && near(t.length(), guess.length()) && near(t.kappaStart(), guess.kappaStart()) &&
          near(t.kappaEnd(), guess.kappaEnd()) && t.theta0() == guess.theta0() && t.start() == guess.start())
        return;
    tries.push_back(guess);
  };
  for (const auto& [miss, guess] : starts) {
    add(guess);
    if (const auto shot = shootSegment(turning, p.front(), theta0, k0, k1, guess.alpha(), so.fit.min_alpha, so.fit.max_alpha, p.back()))
      add(*shot);
  }
  // The tries race: each gets kRaceIterations steps, and the closest of them (the first
  // within the tolerance ends the search) is fitted again from its start with all of
  // kOneSegmentIterations, so that its fit is the one it had fitted to the end (going on
  // from the race's end starts the damping afresh: another fit). Fitted to the end, most
  // tries of a spiral whose centre bends tighter than the tolerance (a loose one) wound
  // off to a neighbouring turn, 3 to 7 tolerances off, each at its full count of steps:
  // 80 of a fit's 93 ms.
  ChainFitOptions race = co;
  race.max_iterations = kRaceIterations;
  std::optional<ChainFitResult> closest;
  const LaSegment* winner = nullptr;
  for (const LaSegment& guess : tries) {
    ChainFitResult r = fitChain({guess}, p, feet, race);
    if (r.report.status == SolveStatus::kBadInput || (closest && !(r.max_distance < closest->max_distance))) continue;
    closest = std::move(r);
    winner = &guess;
    if (closest->max_distance <= so.tolerance) break;
  }
  if (closest && closest->report.status == SolveStatus::kIterationLimit) {
    ChainFitResult full = fitChain({*winner}, p, feet, co);
    if (full.report.status != SolveStatus::kBadInput) closest = std::move(full);
  }
  return closest;
}

// Where the splits of one segment turning more than a full turn (a spiral) at the
// selection's margin leave it outside the tolerance, they come up to this many
// tolerances from a segment's end (SelectionOptions::split_margin): a spiral's one
// segment misses at its centre, a few percent of its length from its end. (A stroke of
// less, cut so, came out with fewer segments than the extrema it was drawn with.)
constexpr double kSplitMarginTolerances = 4.0;

}  // namespace

std::optional<PartFit> oneSegmentPart(const Part& part, const FitContext& context) {
  // (a side between corners is fitted with the others across them, where one segment
  // pinned at both corners may stray; a part beside one corner is pinned there)
  if (part.closed || (part.starts_at_corner && part.ends_at_corner)) return std::nullopt;
  const SelectionOptions so = stage7Selection(context, part);
  // (the selection's merges make a segment turning up to max_turning: only a part turning
  // further needs this; beside a corner, one turning a whole turn or more, kCornerPartTurning)
  const double least_turning = part.starts_at_corner || part.ends_at_corner ? kCornerPartTurning : so.max_turning;
  const std::optional<ChainFitResult> one = oneSegment(part, so, context.noise.sigma, least_turning);
  if (!one) return std::nullopt;
  return partFitOf(*one, "one LA segment");
}

std::optional<PartFit> splitOneSegment(const PartFit& one, const Part& part, const FitContext& context) {
  if (one.segments.size() != 1 || one.feet.size() != part.points.size()) return std::nullopt;
  SelectionOptions so = stage7Selection(context, part);
  SelectionResult selected = selectChain(one.segments, part.points, one.feet, so);
  if (selected.fit.report.status == SolveStatus::kBadInput || selected.fit.segments.empty()) return std::nullopt;
  if (selected.fit.max_distance > so.tolerance && std::abs(one.segments.front().turning()) > 2.0 * std::numbers::pi) {
    // (a spiral of more than a turn: again with splits nearer the ends, kept if closer)
    so.split_margin = kSplitMarginTolerances * context.tolerance;
    SelectionResult nearer = selectChain(one.segments, part.points, one.feet, so);
    if (nearer.fit.report.status != SolveStatus::kBadInput && nearer.fit.max_distance < selected.fit.max_distance)
      selected = std::move(nearer);
  }
  return partFitOf(selected.fit, "one LA segment, split");
}

}  // namespace la
