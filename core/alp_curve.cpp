#include "core/alp_curve.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <numbers>
#include <string>

#include "core/quadrature.h"

namespace la {
namespace {

// Initial panels of the tables have at most this much turning (bounded by the convex
// hull property, L max|kappa_i| per unit tau): 20-point Gauss-Legendre integrates
// cos theta over 1 rad to ~1e-40, so most panels are accepted at once.
constexpr double kInitialPanelTurning = 1.0;
// Bounds on the tables: 2^-40 of the length, at most this many initial panels (a
// curve turning 4000 rad is not a design curve; the refinement still applies), and
// at most kMaxPanels in all (beyond, panels are accepted as they are).
constexpr int kMaxDepth = 40;
constexpr int kMaxInitialPanels = 4096;
constexpr std::size_t kMaxPanels = 16384;
// The turning table's tolerance per unit tau, relative to max |kappa_i|: 20-point
// sums round to a few 1e-16 of that, so this leaves a margin of ~100.
constexpr double kTurningTolerance = 1e-14;

using Rule = GaussLegendreRule<20>;

// Splits [a, b] until the 20-point rule on a panel and on its halves agree within
// tol_density * width; appends accepted panels' right ends to `breaks` and their
// integrals to `values`.
template <class F, class V>
void refinePanels(const F& f, double a, double b, const V& whole, double tol_density, int depth,
                  std::vector<double>& breaks, std::vector<V>& values) {
  const double m = 0.5 * (a + b);
  const V left = integrateFixed<20>(f, a, m), right = integrateFixed<20>(f, m, b);
  const V fine = left + right;
  if (quadratureNorm(V(fine - whole)) <= tol_density * (b - a) || depth >= kMaxDepth || breaks.size() >= kMaxPanels) {
    breaks.push_back(b);
    values.push_back(fine);
    return;
  }
  refinePanels(f, a, m, left, tol_density, depth + 1, breaks, values);
  refinePanels(f, m, b, right, tol_density, depth + 1, breaks, values);
}

// Rational turning: on each panel the curvature K_R is interpolated at kChebPoints
// Chebyshev-Lobatto points and its Chebyshev series integrated term by term, so theta
// costs one Clenshaw sum. A panel is split until the last two coefficients are below
// the tolerance (K_R is analytic on [0, 1]: its poles are off the real interval, so
// the coefficients fall geometrically and the tail bounds the error).
constexpr int kChebPoints = 24;

// Coefficients of the integral over [a, x(t)] of f on [a, b] in t in [-1, 1] (degree
// kChebPoints), times the half width; `tail` gets the size of f's last two coefficients.
template <class F>
std::vector<double> chebyshevIntegral(const F& f, double a, double b, double& tail) {
  constexpr int N = kChebPoints;
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double values[N];
  for (int j = 0; j < N; ++j) values[j] = f(mid + half * std::cos(std::numbers::pi * j / (N - 1)));
  double c[N + 2] = {};
  for (int k = 0; k < N; ++k) {
    double sum = 0.0;
    for (int j = 0; j < N; ++j) {
      const double w = (j == 0 || j == N - 1) ? 0.5 : 1.0;
      sum += w * values[j] * std::cos(std::numbers::pi * j * k / (N - 1));
    }
    c[k] = sum * 2.0 / (N - 1) * ((k == 0 || k == N - 1) ? 0.5 : 1.0);
  }
  tail = std::max(std::abs(c[N - 1]), std::abs(c[N - 2]));
  std::vector<double> C(N + 1, 0.0);
  C[1] = c[0] - 0.5 * c[2];
  for (int k = 2; k <= N; ++k) C[k] = (c[k - 1] - c[k + 1]) / (2.0 * k);
  double at_minus_one = 0.0;
  for (int k = 1; k <= N; ++k) at_minus_one += (k % 2 ? -1.0 : 1.0) * C[k];
  C[0] = -at_minus_one;
  for (double& v : C) v *= half;
  return C;
}

double clenshaw(const double* C, int n, double x) {
  double b1 = 0.0, b2 = 0.0;
  for (int k = n; k >= 1; --k) {
    const double b0 = C[k] + 2.0 * x * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return C[0] + x * b1 - b2;
}

template <class F>
void refineChebyshev(const F& f, double a, double b, double tol, int depth, std::vector<double>& breaks,
                     std::vector<double>& coefficients) {
  double tail = 0.0;
  std::vector<double> C = chebyshevIntegral(f, a, b, tail);
  if (tail <= tol || depth >= kMaxDepth || breaks.size() >= kMaxPanels) {
    breaks.push_back(b);
    coefficients.insert(coefficients.end(), C.begin(), C.end());
    return;
  }
  const double m = 0.5 * (a + b);
  refineChebyshev(f, a, m, tol, depth + 1, breaks, coefficients);
  refineChebyshev(f, m, b, tol, depth + 1, breaks, coefficients);
}

std::size_t panelIndex(const std::vector<double>& breaks, double tau) {
  // breaks = {0, ..., 1}: the panel [breaks[k], breaks[k+1]) holding tau
  auto it = std::upper_bound(breaks.begin(), breaks.end(), tau);
  std::size_t k = static_cast<std::size_t>(it - breaks.begin());
  k = k == 0 ? 0 : k - 1;
  return std::min(k, breaks.size() - 2);
}

bool finite(double v) { return std::isfinite(v); }

}  // namespace

AlpCurve::AlpCurve(std::vector<double> control_kappa, std::vector<double> weights, double length, Vec2 start,
                   double theta0)
    : control_kappa_(std::move(control_kappa)),
      weights_(std::move(weights)),
      length_(length),
      start_(start),
      theta0_(theta0) {
  if (control_kappa_.empty()) throw std::invalid_argument("AlpCurve: no control curvatures");
  if (!weights_.empty() && weights_.size() != control_kappa_.size())
    throw std::invalid_argument("AlpCurve: " + std::to_string(weights_.size()) + " weights for " +
                                std::to_string(control_kappa_.size()) + " control curvatures");
  if (!(length_ > 0.0) || !finite(length_)) throw std::invalid_argument("AlpCurve: length must be positive and finite");
  if (!allFinite(start_) || !finite(theta0_)) throw std::invalid_argument("AlpCurve: start or theta0 not finite");
  double max_control = 0.0;
  for (double k : control_kappa_) {
    if (!finite(k)) throw std::invalid_argument("AlpCurve: control curvature not finite");
    max_control = std::max(max_control, std::abs(k));
  }
  for (double w : weights_)
    if (!(w > 0.0) || !finite(w)) throw std::invalid_argument("AlpCurve: weights must be positive and finite");

  numerator_ = control_kappa_;
  if (isRational())
    for (std::size_t i = 0; i < weights_.size(); ++i) numerator_[i] *= weights_[i];
  d_numerator_ = bernsteinDerivative(numerator_);
  if (isRational()) d_weights_ = bernsteinDerivative(weights_);

  const double bound = length_ * max_control;  // >= the turning per unit tau anywhere
  const int initial = ceilWithin(bound / kInitialPanelTurning, 1, kMaxInitialPanels);

  if (isRational()) {
    // Turning table: Chebyshev panels of the integral of K_R (theta to ~1e-14 of
    // L max|kappa_i|).
    const auto f = [this](double tau) { return curvatureAt(tau); };
    const double tol = kTurningTolerance * std::max(max_control, 1e-300);
    theta_breaks_ = {0.0};
    for (int i = 0; i < initial; ++i)
      refineChebyshev(f, double(i) / initial, double(i + 1) / initial, tol, 0, theta_breaks_, theta_series_);
    theta_breaks_.back() = 1.0;
    unit_turning_ = {0.0};
    for (std::size_t k = 0; k + 1 < theta_breaks_.size(); ++k)
      unit_turning_.push_back(unit_turning_.back() + clenshaw(&theta_series_[k * (kChebPoints + 1)], kChebPoints, 1.0));
  } else {
    turning_poly_ = bernsteinIntegral(control_kappa_);
  }

  // Position table: integral of L (cos theta, sin theta) d tau per panel.
  const auto g = [this](double tau) { return Vec2(length_ * unitVector(theta0_ + length_ * unitTurningAt(tau))); };
  breaks_ = {0.0};
  std::vector<Vec2> pieces;
  for (int i = 0; i < initial; ++i) {
    const double a = double(i) / initial, b = double(i + 1) / initial;
    refinePanels(g, a, b, Vec2(integrateFixed<20>(g, a, b)), kTableRelativeTolerance * length_, 0, breaks_, pieces);
  }
  breaks_.back() = 1.0;
  table_ = {start_};
  for (const Vec2& d : pieces) table_.push_back(table_.back() + d);
  end_ = table_.back();
  turning_ = length_ * unitTurningAt(1.0);

  // Total turning and max |kappa| from the sign changes of kappa and of its derivative.
  std::vector<double> cuts{0.0};
  for (double t : bernsteinSignChanges(numerator_)) cuts.push_back(t);
  cuts.push_back(1.0);
  total_turning_ = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    total_turning_ += std::abs(unitTurningAt(cuts[i + 1]) - unitTurningAt(cuts[i])) * length_;
  max_abs_kappa_ = std::max(std::abs(curvatureAt(0.0)), std::abs(curvatureAt(1.0)));
  for (double t : bernsteinSignChanges(curvatureDerivativeNumerator()))
    max_abs_kappa_ = std::max(max_abs_kappa_, std::abs(curvatureAt(t)));
}

BernsteinCoefficients AlpCurve::curvatureDerivativeNumerator() const {
  if (!isRational()) return d_numerator_;
  // N' D - N D', both products of degree 2n - 1
  BernsteinCoefficients a = bernsteinProduct(d_numerator_, weights_);
  const BernsteinCoefficients b = bernsteinProduct(numerator_, d_weights_);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] -= b[i];
  return a;
}

double AlpCurve::curvatureAt(double tau) const {
  if (!isRational()) return evaluateBernstein(numerator_, tau);
  return evaluateBernstein(numerator_, tau) / evaluateBernstein(weights_, tau);
}

double AlpCurve::curvatureDerivativeAt(double tau) const {
  if (!isRational()) return evaluateBernstein(d_numerator_, tau);
  const double n = evaluateBernstein(numerator_, tau), d = evaluateBernstein(weights_, tau);
  const double dn = evaluateBernstein(d_numerator_, tau), dd = evaluateBernstein(d_weights_, tau);
  return (dn * d - n * dd) / (d * d);
}

double AlpCurve::unitTurningAt(double tau) const {
  tau = std::clamp(tau, 0.0, 1.0);
  if (!isRational()) return evaluateBernstein(turning_poly_, tau);
  const std::size_t k = panelIndex(theta_breaks_, tau);
  const double a = theta_breaks_[k], b = theta_breaks_[k + 1];
  if (tau == a) return unit_turning_[k];
  const double x = std::clamp((2.0 * tau - a - b) / (b - a), -1.0, 1.0);
  return unit_turning_[k] + clenshaw(&theta_series_[k * (kChebPoints + 1)], kChebPoints, x);
}

double AlpCurve::kappa(double s) const { return curvatureAt(std::clamp(s / length_, 0.0, 1.0)); }

double AlpCurve::dkappa(double s) const { return curvatureDerivativeAt(std::clamp(s / length_, 0.0, 1.0)) / length_; }

double AlpCurve::theta(double s) const { return theta0_ + length_ * unitTurningAt(s / length_); }

Vec2 AlpCurve::position(double s, double relative_tolerance) const {
  const double tau = std::clamp(s / length_, 0.0, 1.0);
  if (tau == 0.0) return start_;
  if (tau == 1.0) return end_;
  const std::size_t k = panelIndex(breaks_, tau);
  if (tau == breaks_[k]) return table_[k];
  const auto g = [this](double t) { return Vec2(length_ * unitVector(theta0_ + length_ * unitTurningAt(t))); };
  return table_[k] + integrateAdaptive(g, breaks_[k], tau, relative_tolerance * length_).value;
}

void AlpCurve::sample(int n, CurveSamples& out, double s_offset, double relative_tolerance) const {
  if (n < 2) throw std::invalid_argument("AlpCurve::sample: need at least 2 samples");
  const auto g = [this](double t) { return Vec2(length_ * unitVector(theta0_ + length_ * unitTurningAt(t))); };
  // Each step integrates from the previous sample, or from the table's break when a
  // break lies between them, so errors add up over one panel at most. A step is the
  // 8-point rule when the 4-point rule agrees with it within the step's tolerance
  // (the 8-point error is then far below it: the rules' errors go as h^8 and h^16),
  // else adaptive quadrature.
  const double step_tol = relative_tolerance * length_ / (n - 1);
  const auto integrate = [&](double t0, double t1) {
    const Vec2 fine = integrateFixed<8>(g, t0, t1);
    if ((fine - Vec2(integrateFixed<4>(g, t0, t1))).norm() <= step_tol) return fine;
    return Vec2(integrateAdaptive(g, t0, t1, step_tol).value);
  };
  Vec2 p = start_;
  double tau_prev = 0.0;
  std::size_t panel_prev = 0;
  for (int i = 0; i < n; ++i) {
    const double tau = (i == n - 1) ? 1.0 : double(i) / (n - 1);
    if (i == n - 1) {
      p = end_;
    } else if (i > 0) {
      const std::size_t k = panelIndex(breaks_, tau);
      if (k == panel_prev)
        p += integrate(tau_prev, tau);
      else
        p = table_[k] + integrate(breaks_[k], tau);
      panel_prev = k;
    }
    tau_prev = tau;
    const double th = theta0_ + length_ * unitTurningAt(tau);
    out.s.push_back(s_offset + tau * length_);
    out.point.push_back(p);
    out.tangent.push_back(unitVector(th));
    out.theta.push_back(th);
    out.kappa.push_back(curvatureAt(tau));
  }
}

CurveSamples AlpCurve::sample(int n) const {
  CurveSamples out;
  out.reserve(static_cast<std::size_t>(std::max(n, 0)));
  sample(n, out);
  return out;
}

}  // namespace la
