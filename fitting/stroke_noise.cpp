#include "fitting/stroke_noise.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/root_finding.h"

namespace la {
namespace {

// Points on a grid (pixels) are off the true stroke by up to sqrt(2)/2 of a step; no
// curve can be closer to all of them than about this, so the tolerance is not set below
// this many steps. (At 0.75 the fair curve had a twentieth of a step to spare over the
// true one: a 74-point Omniglot stroke followed its stairs with 26 segments and 11
// extrema, at one step 12 and 5, its largest deviation 0.68 -> 0.78 of a step; over the
// shared data's Omniglot strokes, variants included, 2,573 -> 2,270 segments and 1,170 ->
// 1,060 extrema, their time p99 39 -> 25 ms; 5 MMG and 4 small $1 strokes changed too,
// with no more extrema.)
constexpr double kQuantizationFloor = 1.0;
// A pointer that moves at most this many grid steps per sample stays on a pixel row or
// column for several samples (stairs), so its noise repeats over neighbouring samples;
// see noiseOf.
constexpr double kStairSteps = 2.0;

// Fourth differences whose first quartile is at least this fraction of their third are
// not noise (a half-normal's ratio is 0.28; in the shared pen and mouse strokes, 0.25 in
// the median, 0.38 at the 90th percentile) if their signs alternate too (below): a
// zigzag drawn at the sampling scale.
constexpr double kConcentratedQuartiles = 0.6;
// ... and whose signs change between this share of neighbours (noise: 80%).
constexpr double kZigzagSignChanges = 0.95;

// Where leaving out the differences across corners lowers the noise estimate more than
// this many times, the corners set it (noiseOf).
constexpr double kCornersSetTheNoise = 2.0;

// Noise that neighbouring samples share (a tablet driver's smoothing) is read from the
// differences of every second and every third sample (sharedNoiseAbove) where that
// reading is more than this many times the neighbours' one...
constexpr double kSharedNoise = 2.0;
// ... and the third sample's differences are within this many times the second's: the
// curve's own bending, which grows as lag^4 in them, would make them 5 times larger.
constexpr double kBendingShare = 2.0;

// The noise floor of the tolerance is this many standard deviations of the points'
// estimated noise, at least: a point's distance from the curve (its noise across it)
// exceeds 4 sigma with probability 6e-5, so some point of 160 with 1%. A stroke of more
// points gets the sigmas at which some point of all of them does with that chance
// (floorSigmas): 4.4 for 1,000 points, 4.6 for 2,000; else the true curve itself would
// often miss the tolerance on them.
constexpr double kNoiseSigmas = 4.0;
constexpr double kAnyPointBeyondFloor = 0.01;

// The smallest k (as a double) at which the largest of n standard normal deviations
// exceeds k with at most probability kAnyPointBeyondFloor: n erfc(k / sqrt 2) <= that,
// erfc falling; at least kNoiseSigmas. (The root to the last bit, so the floor is the
// same whatever the root finder's last step.)
double floorSigmas(std::size_t n) {
  const double per_point = kAnyPointBeyondFloor / static_cast<double>(std::max<std::size_t>(n, 1));
  auto keeps = [&](double k) { return std::erfc(k / std::numbers::sqrt2) <= per_point; };
  if (keeps(kNoiseSigmas)) return kNoiseSigmas;
  auto beyond = [&](double k) {  // (its derivative: -sqrt(2 / pi) exp(-k^2 / 2))
    return std::pair{std::erfc(k / std::numbers::sqrt2) - per_point,
                     -std::sqrt(2.0 / std::numbers::pi) * std::exp(-0.5 * k * k)};
  };
  double k = solveMonotone(beyond, kNoiseSigmas, 40.0, kNoiseSigmas, false).x;
  while (!keeps(k)) k = std::nextafter(k, INFINITY);
  while (keeps(std::nextafter(k, 0.0))) k = std::nextafter(k, 0.0);
  return k;
}

// The smallest tolerance the points allow: their noise level and, for points on an
// integer grid (pixels), the quantization. The noise is estimated robustly from the
// fourth differences p[i-2] - 4p[i-1] + 6p[i] - 4p[i+1] + p[i+2] across the stroke
// (along the normal of the chord p[i-2]p[i+2], so uneven spacing along the stroke does
// not count): they cancel any cubic, i.e. the curve's own bending, and for independent
// noise sigma have standard deviation sigma sqrt(70); the median ignores corners. With
// `lag`, the differences of every lag-th point: noise that repeats over up to `lag`
// neighbouring samples cancels partly in the differences of neighbours, not in these.
// Differences whose five points span one of `corners` (strictly inside) are left out.
double noiseSigma(const std::vector<Vec2>& p, const std::vector<std::size_t>& corners, std::size_t lag = 1) {
  if (p.size() < 4 * lag + 3) return 0.0;
  std::vector<bool> across_corner(p.size(), false);  // (by the difference's middle point)
  for (std::size_t c : corners)
    for (std::size_t i = c >= 2 * lag ? c - 2 * lag + 1 : 0; i < std::min(p.size(), c + 2 * lag); ++i) across_corner[i] = true;
  std::vector<double> signed_d;
  for (std::size_t i = 2 * lag; i + 2 * lag < p.size(); ++i) {
    if (across_corner[i]) continue;
    const Vec2 chord = p[i + 2 * lag] - p[i - 2 * lag];
    const double len = chord.norm();
    if (!(len > 0.0)) continue;
    const Vec2 normal(-chord.y() / len, chord.x() / len);
    signed_d.push_back(normal.dot(p[i - 2 * lag] - 4.0 * p[i - lag] + 6.0 * p[i] - 4.0 * p[i + lag] + p[i + 2 * lag]));
  }
  if (signed_d.empty()) return 0.0;
  std::vector<double> d;
  for (double v : signed_d) d.push_back(std::abs(v));
  // (the three order statistics alone, each selection within the part the last one left:
  // the same values as a sort, which was 1.5% of the 1,000-point stroke's fit)
  const std::size_t i25 = d.size() / 4, i50 = d.size() / 2, i75 = 3 * d.size() / 4;
  const auto at = [&](std::size_t k) { return d.begin() + static_cast<std::ptrdiff_t>(k); };
  std::nth_element(d.begin(), at(i50), d.end());
  if (i25 < i50) std::nth_element(d.begin(), at(i25), at(i50));
  if (i75 > i50) std::nth_element(at(i50 + 1), at(i75), d.end());
  const double q25 = d[i25], q50 = d[i50], q75 = d[i75];
  const double by_median = q50 / 0.6745;  // median of |N(0,s)| = 0.6745 s
  // Noise spreads |d| as a half-normal (quartiles 0.32 s and 1.15 s), with signs that
  // change between neighbours 80% of the time (their correlation is -56/70). Differences
  // all about one size whose sign changes at nearly every sample are a zigzag drawn at
  // the sampling scale (every sample a vertex), not noise: the noise is then the spread
  // about that size (the interquartile range of a normal is 1.349 s). A smooth curve's
  // differences may be all one size too, but keep their sign.
  std::size_t changes = 0;
  for (std::size_t i = 1; i < signed_d.size(); ++i) changes += (signed_d[i] > 0.0) != (signed_d[i - 1] > 0.0);
  const bool zigzag = q25 >= kConcentratedQuartiles * q75 &&
                      static_cast<double>(changes) >= kZigzagSignChanges * static_cast<double>(signed_d.size() - 1);
  return (zigzag ? (q75 - q25) / 1.349 : by_median) / std::sqrt(70.0);
}

constexpr double kGridRounding = 1e-3;  // in steps (the files print 6 decimals)
constexpr double kMostGridCells = 1e6;  // across the points' range, along one axis
constexpr int kMostStepParts = 8;       // the grid's step: the smallest change over at most this

// Whether `value` lies a whole number of steps from `origin`, to the files' rounding.
bool onGridLine(double value, double origin, double step) {
  const double k = (value - origin) / step;
  return std::abs(k - std::round(k)) <= kGridRounding;
}

// The grid the points lie on along one coordinate: every value an integer number of
// steps from the smallest (pixels, possibly shifted and scaled, as Omniglot's canvas
// units are); the step 0 if they do not. The step is the smallest change between
// consecutive points, or a whole fraction of it (up to kMostStepParts): a pointer's
// samples several pixels apart (a mouse's events at speed) may have no two neighbours
// one pixel apart, and their grid went unseen (steps of 2-5 pixels read as a grid of 2:
// no grid, a noise of 0 where most fourth differences are, and a tolerance under the
// pixels' rounding, which the fit then followed).
std::pair<double, double> gridAxis(const std::vector<Vec2>& p, int axis) {
  double step = INFINITY, lo = p.front()[axis], hi = lo;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double d = std::abs(p[i][axis] - p[i - 1][axis]);
    if (d > 0.0) step = std::min(step, d);
    lo = std::min(lo, p[i][axis]), hi = std::max(hi, p[i][axis]);
  }
  if (!std::isfinite(step)) return {lo, 0.0};
  // (at most kMostGridCells: a change of a few ulps between two points is rounding, not a
  // pixel; on a grid that fine every double lies, and a resampled stroke passed for a
  // pixel one)
  for (int parts = 1; parts <= kMostStepParts && (hi - lo) / (step / parts) <= kMostGridCells; ++parts) {
    // (the printed step's rounding spread over the range)
    const double h = (hi - lo) / std::round((hi - lo) / (step / parts));
    if (std::all_of(p.begin(), p.end(), [&](const Vec2& q) { return onGridLine(q[axis], lo, h); })) return {lo, h};
  }
  return {lo, 0.0};
}

// The noise that neighbouring samples share, from the fourth differences of every second
// and every third sample (noiseSigma at lags 2 and 3). Each reads noise^2 + (L^4 b)^2, b
// the curve's bending: the two solved for the noise (the bending's share taken out, 256
// of it at lag 2 where 6,561 at lag 3). A [1 2 1]/4 filter over white noise leaves a
// sixth of the points' noise in the differences of neighbours, 85% in these. 0 where it
// is not above `least` (every third's differences then not taken), where the bending
// fills them (kBendingShare), or where the points are too few.
double sharedNoiseAbove(double least, const std::vector<Vec2>& p, const std::vector<std::size_t>& corners) {
  constexpr double kBending = 256.0 / (6561.0 - 256.0);
  const double s2 = noiseSigma(p, corners, 2);
  if (!(std::sqrt(1.0 + kBending) * s2 > least)) return 0.0;
  const double s3 = noiseSigma(p, corners, 3);
  if (!(s3 > 0.0) || s3 > kBendingShare * s2) return 0.0;
  const double v = (1.0 + kBending) * s2 * s2 - kBending * s3 * s3;
  return v > least * least ? std::sqrt(v) : 0.0;
}

}  // namespace

// The points' noise: sigma per coordinate (the estimate above, plus the quantization of
// a grid of step h: uniform on a step, variance h^2/12 per coordinate) and the floor of
// the tolerance it implies. On a grid walked a pixel or two per sample (a mouse), the
// pointer's tremor and rounding repeat over neighbouring samples (stairs): the noise is
// taken at lag 2 as well, the larger estimate kept. Larger lags, and sparser samples,
// would span the curve's own bends (its share grows as lag^4): at lag 3 small glyphs'
// tolerances rose up to 4x, and lag 2 on strokes sampled every 3-8 pixels 1.6-3x; so
// lags 2 and 3 serve only where together they read the bending apart from the noise
// (sharedNoiseAbove).
Noise noiseOf(const std::vector<Vec2>& p, const std::vector<std::size_t>& corners) {
  const std::optional<PixelGrid> grid = pixelGridOf(p);
  const bool on_grid = grid.has_value();
  const double h = on_grid ? grid->step.maxCoeff() : 0.0;
  const bool stairs = on_grid && medianStep(p) <= kStairSteps * h;
  auto sigmaOf = [&](const std::vector<std::size_t>& left_out) {
    return stairs ? std::max(noiseSigma(p, left_out), noiseSigma(p, left_out, 2)) : noiseSigma(p, left_out);
  };
  // (a stroke's few corners move the median little, and their neighbourhoods may hold
  // more than noise: only where leaving them out changes the estimate several times
  // over are they what set it)
  double sigma = sigmaOf({});
  if (!corners.empty())
    if (const double without = sigmaOf(corners); kCornersSetTheNoise * without < sigma) sigma = without;
  // Noise the samples share hides from the neighbours' differences: a stroke smoothed by
  // its device read as nearly noise-free, and its fit followed the wobble the filter left
  // (data_benchmark --handed-over=smoothed: 5 extrema at the median where the drawn
  // strokes have 2, time p99 0.5 s). Not on stairs: their estimate holds every second
  // sample's reading already (on the shared data, with and without this, the same curves).
  if (!stairs)
    if (const double shared = sharedNoiseAbove(kSharedNoise * sigma, p, corners); shared > 0.0) sigma = shared;
  Noise n;
  n.sigma = on_grid ? std::sqrt(sigma * sigma + h * h / 12.0) : sigma;
  n.floor = std::max(floorSigmas(p.size()) * sigma, on_grid ? kQuantizationFloor * h : 0.0);
  n.on_grid = on_grid;
  return n;
}

bool PixelGrid::holds(const Vec2& q) const {
  return onGridLine(q.x(), origin.x(), step.x()) && onGridLine(q.y(), origin.y(), step.y());
}

std::optional<PixelGrid> pixelGridOf(const std::vector<Vec2>& p) {
  if (p.empty()) return std::nullopt;
  const auto [x0, hx] = gridAxis(p, 0);
  const auto [y0, hy] = gridAxis(p, 1);
  if (!(hx > 0.0 && hy > 0.0)) return std::nullopt;
  return PixelGrid{Vec2(x0, y0), Vec2(hx, hy)};
}

std::vector<Vec2> withoutStairs(const std::vector<Vec2>& p, bool closed) {
  const auto m = static_cast<long>(p.size());
  if (m < 5) return p;
  auto at = [&](long k) { return p[static_cast<std::size_t>(closed ? (k % m + m) % m : std::clamp(k, 0L, m - 1))]; };
  std::vector<Vec2> out = p;
  for (long i = closed ? 0 : 1; i < (closed ? m : m - 1); ++i)
    out[static_cast<std::size_t>(i)] = (at(i - 2) + 4.0 * at(i - 1) + 6.0 * at(i) + 4.0 * at(i + 1) + at(i + 2)) / 16.0;
  return out;
}

}  // namespace la
