#include "core/lcg.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace la {
namespace {

// Rounding level of LCG coordinates, in units of eps * (1 + |x| + |y|). Each x =
// -log|kappa| carries an absolute rounding error of about eps * (1 + |x|) (eps from
// kappa itself, eps * |x| from the log), each y = log|kappa| - log|kappa'| about
// eps * (2 + |x| + |x + y|); a few dozen such units cannot be told from exact.
// Used twice: all x within this level of each other make a vertical LCG (a circle:
// the fitted slope would be noise), and residuals within it make R^2 = 1.
constexpr double kRoundoffUlps = 64.0;

// The LCG point of one sample, or false when it has none (see lcg.h).
bool lcgPoint(double kappa, double dkappa, LcgPoint& out) {
  if (!std::isfinite(kappa) || !std::isfinite(dkappa) || kappa == 0.0 || dkappa == 0.0)
    return false;
  const double log_kappa = std::log(std::abs(kappa));
  out.log_rho = -log_kappa;
  out.log_rho_ds_drho = log_kappa - std::log(std::abs(dkappa));
  // Finite inputs give finite logs (subnormals included); kept as a guard.
  return std::isfinite(out.log_rho) && std::isfinite(out.log_rho_ds_drho);
}

}  // namespace

std::vector<LcgPoint> lcgFromDerivative(std::span<const double> kappa,
                                        std::span<const double> dkappa) {
  if (kappa.size() != dkappa.size())
    throw std::invalid_argument("lcgFromDerivative: kappa has " + std::to_string(kappa.size()) +
                                " samples, dkappa " + std::to_string(dkappa.size()));
  std::vector<LcgPoint> points;
  points.reserve(kappa.size());
  LcgPoint p{};
  for (std::size_t i = 0; i < kappa.size(); ++i)
    if (lcgPoint(kappa[i], dkappa[i], p)) points.push_back(p);
  return points;
}

std::vector<LcgPoint> lcgFromSamples(std::span<const double> s, std::span<const double> kappa) {
  if (s.size() != kappa.size())
    throw std::invalid_argument("lcgFromSamples: s has " + std::to_string(s.size()) +
                                " samples, kappa " + std::to_string(kappa.size()));
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s[i]))
      throw std::invalid_argument("lcgFromSamples: s[" + std::to_string(i) + "] is not finite");
    if (i > 0 && !(s[i] > s[i - 1]))
      throw std::invalid_argument("lcgFromSamples: s is not strictly increasing at index " +
                                  std::to_string(i));
  }
  const std::size_t n = s.size();
  if (n < 3) return {};

  // Three-point Lagrange derivatives on a non-uniform grid. With the stencil
  // s_a < s_b < s_c, h0 = s_b - s_a, h1 = s_c - s_b, h = h0 + h1 (order 2):
  //   at s_a: -(2h0+h1)/(h0 h) f_a + h/(h0 h1) f_b - h0/(h1 h) f_c
  //   at s_b: -h1/(h0 h) f_a + (h1-h0)/(h0 h1) f_b + h0/(h1 h) f_c
  //   at s_c:  h1/(h0 h) f_a - h/(h0 h1) f_b + (2h1+h0)/(h1 h) f_c
  // The weights sum to 0, so each is evaluated on differences from the point itself:
  // a constant kappa (a circle) then gives exactly 0, and close values subtract exactly.
  std::vector<double> dkappa(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t b = std::clamp<std::size_t>(i, 1, n - 2);  // stencil centre
    const double fa = kappa[b - 1], fb = kappa[b], fc = kappa[b + 1];
    const double h0 = s[b] - s[b - 1], h1 = s[b + 1] - s[b], h = h0 + h1;
    if (i < b) {
      dkappa[i] = h / (h0 * h1) * (fb - fa) - h0 / (h1 * h) * (fc - fa);
    } else if (i > b) {
      dkappa[i] = h1 / (h0 * h) * (fa - fc) - h / (h0 * h1) * (fb - fc);
    } else {
      dkappa[i] = -h1 / (h0 * h) * (fa - fb) + h0 / (h1 * h) * (fc - fb);
    }
  }
  return lcgFromDerivative(kappa, dkappa);
}

LcgFit fitLcg(std::span<const LcgPoint> points) {
  LcgFit fit;
  fit.report.status = SolveStatus::kBadInput;

  std::vector<LcgPoint> used;
  used.reserve(points.size());
  for (const LcgPoint& p : points)
    if (std::isfinite(p.log_rho) && std::isfinite(p.log_rho_ds_drho)) used.push_back(p);
  fit.points_used = static_cast<int>(used.size());
  if (used.size() < 3) {
    fit.report.message = "LCG fit needs at least 3 finite points, got " +
                         std::to_string(used.size()) + " of " + std::to_string(points.size()) +
                         " (a circle or line has dkappa/ds = 0 everywhere and no LCG points)";
    return fit;
  }

  // Pass 1: means.
  const double n = static_cast<double>(used.size());
  double x_mean = 0.0, y_mean = 0.0, x_min = used[0].log_rho, x_max = used[0].log_rho;
  double y_abs_max = 0.0;
  for (const LcgPoint& p : used) {
    x_mean += p.log_rho;
    y_mean += p.log_rho_ds_drho;
    x_min = std::min(x_min, p.log_rho);
    x_max = std::max(x_max, p.log_rho);
    y_abs_max = std::max(y_abs_max, std::abs(p.log_rho_ds_drho));
  }
  x_mean /= n;
  y_mean /= n;

  const double eps = std::numeric_limits<double>::epsilon();
  const double x_abs_max = std::max(std::abs(x_min), std::abs(x_max));
  if (x_max - x_min <= kRoundoffUlps * eps * (1.0 + x_abs_max)) {
    fit.report.message = "LCG is vertical (all log rho equal, x = " + std::to_string(x_mean) +
                         "): the curve is a circle, alpha = +-inf, slope undefined";
    return fit;
  }

  // Pass 2: centred sums (no cancellation against the means).
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const LcgPoint& p : used) {
    const double dx = p.log_rho - x_mean, dy = p.log_rho_ds_drho - y_mean;
    sxx += dx * dx;
    sxy += dx * dy;
    syy += dy * dy;
  }
  const double alpha = sxy / sxx;

  // Pass 3: residuals summed directly, so R^2 close to 1 keeps its digits.
  double ss_res = 0.0;
  for (const LcgPoint& p : used) {
    const double r = (p.log_rho_ds_drho - y_mean) - alpha * (p.log_rho - x_mean);
    ss_res += r * r;
  }

  fit.alpha = alpha;
  fit.intercept = y_mean - alpha * x_mean;
  // Residuals at rounding level: the points are on the line as far as can be told, and
  // R^2 = 1 (this covers SS_tot = 0, all y equal). Without this an exact horizontal
  // LCG (alpha = 0) would give R^2 = rounding / rounding, anything in [0, 1].
  const double rounding = kRoundoffUlps * eps * (1.0 + x_abs_max + y_abs_max);
  fit.r2 = ss_res <= n * rounding * rounding ? 1.0 : 1.0 - ss_res / syy;
  fit.report.status = SolveStatus::kConverged;
  fit.report.iterations = 0;  // direct solve
  fit.report.residual = std::sqrt(ss_res / n);
  fit.report.message = "LCG line fitted to " + std::to_string(used.size()) + " points";
  return fit;
}

std::vector<LcgPoint> lcgOfSegment(const LaSegment& segment, int samples) {
  std::vector<double> kappa, dkappa;
  const CurveSamples smp = segment.sample(samples);
  for (std::size_t i = 0; i < smp.size(); ++i) {
    kappa.push_back(smp.kappa[i]);
    dkappa.push_back(segment.dkappa(smp.s[i]));
  }
  return lcgFromDerivative(kappa, dkappa);
}

}  // namespace la
