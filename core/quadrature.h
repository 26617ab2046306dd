#pragma once
// Gauss-Legendre quadrature: fixed rules and an adaptive integrator.
//
// Every curve in the project is an integral of its unit tangent, so this is the
// numerical heart of evaluation. The fixed rules are computed once, to full double
// precision, by Newton's method on the Legendre polynomial P_N (Golub-Welsch would do
// as well; Newton is shorter and exact enough for N <= 64). The adaptive integrator
// compares one rule on an interval with the same rule on its two halves and splits
// where they disagree, so singular-but-integrable ends (an inflection end of an LA
// segment, rho -> 0 or infinity) get their own small panels.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <type_traits>
#include <vector>

namespace la {

/// N-point Gauss-Legendre rule on [0, 1] (nodes ascending, weights summing to 1).
template <int N>
struct GaussLegendreRule {
  std::array<double, N> node{};
  std::array<double, N> weight{};
};

namespace detail {
template <int N>
GaussLegendreRule<N> computeGaussLegendre() {
  GaussLegendreRule<N> rule;
  for (int i = 0; i < (N + 1) / 2; ++i) {
    // Chebyshev-like first guess of the i-th root of P_N on [-1, 1], then Newton.
    double x = std::cos(std::numbers::pi * (i + 0.75) / (N + 0.5));
    double dp = 0.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;  // P_0, P_1; recurrence up to P_N
      for (int k = 2; k <= N; ++k) {
        const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pk;
      }
      dp = N * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    // Map [-1, 1] -> [0, 1]; roots come out descending from +1.
    rule.node[N - 1 - i] = 0.5 * (1.0 + x);
    rule.node[i] = 0.5 * (1.0 - x);
    rule.weight[N - 1 - i] = rule.weight[i] = 0.5 * w;
  }
  return rule;
}
}  // namespace detail

template <int N>
const GaussLegendreRule<N>& gaussLegendre() {
  static const GaussLegendreRule<N> rule = detail::computeGaussLegendre<N>();
  return rule;
}

/// Applies the N-point rule to f on [a, b]. V needs +, and * by double.
template <int N, class F>
auto integrateFixed(F&& f, double a, double b) {
  using V = std::decay_t<std::invoke_result_t<F&, double>>;
  const auto& rule = gaussLegendre<N>();
  const double h = b - a;
  V sum = V(f(a + h * rule.node[0]) * rule.weight[0]);
  for (int k = 1; k < N; ++k) sum += V(f(a + h * rule.node[k]) * rule.weight[k]);
  return V(sum * h);
}

template <class V>
struct QuadratureResult {
  V value{};
  double error_estimate = 0.0;  // sum of |coarse - fine| over accepted panels, same units as value
  int panels = 0;
  bool converged = false;       // false if a panel hit the depth limit
};

/// Norm used for error control: abs for scalars, max-abs for fixed-size vectors.
template <class V>
double quadratureNorm(const V& v) {
  if constexpr (requires { v.cwiseAbs().maxCoeff(); }) {
    return v.cwiseAbs().maxCoeff();
  } else {
    using std::abs;
    return abs(v);
  }
}

namespace detail {
// A panel of the adaptive integrator: the 10-point rule on it (`whole`) and on its two
// halves, and their disagreement, the panel's error estimate.
template <class V>
struct AdaptivePanel {
  double lo, hi;
  V whole, left, right;
  double err;
  int depth;
  double mid() const { return 0.5 * (lo + hi); }
  V fine() const { return V(left + right); }
};

template <class V, class F>
AdaptivePanel<V> adaptivePanel(F& f, double lo, double hi, const V& whole, int depth) {
  const double mid = 0.5 * (lo + hi);
  AdaptivePanel<V> p{lo, hi, whole, integrateFixed<10>(f, lo, mid), integrateFixed<10>(f, mid, hi), 0.0, depth};
  p.err = quadratureNorm(V(p.fine() - whole));
  return p;
}

// The global rule (QUADPACK's strategy): the panel with the largest error is halved until
// the errors sum to abs_tol. Panels at max_depth stay as they are.
template <class F, class V>
QuadratureResult<V> integrateGlobal(F& f, double a, double b, const V& first, double abs_tol, int max_depth,
                                    int max_panels) {
  auto smaller = [](const AdaptivePanel<V>& x, const AdaptivePanel<V>& y) { return x.err < y.err; };
  std::vector<AdaptivePanel<V>> open, done;  // `open`: a max-heap on err
  open.push_back(adaptivePanel(f, a, b, first, 0));
  double total = open.front().err;
  while (total > abs_tol && !open.empty() && static_cast<int>(open.size() + done.size()) < max_panels) {
    std::pop_heap(open.begin(), open.end(), smaller);
    const AdaptivePanel<V> p = open.back();
    open.pop_back();
    if (p.depth >= max_depth) {
      done.push_back(p);
      continue;
    }
    for (auto half : {adaptivePanel(f, p.lo, p.mid(), p.left, p.depth + 1), adaptivePanel(f, p.mid(), p.hi, p.right, p.depth + 1)}) {
      total += half.err;
      open.push_back(half);
      std::push_heap(open.begin(), open.end(), smaller);
    }
    total -= p.err;
  }
  QuadratureResult<V> result;
  result.value = V(first * 0.0);
  for (const auto* panels : {&open, &done})
    for (const AdaptivePanel<V>& p : *panels) {
      result.value += p.fine();
      result.error_estimate += p.err;
      ++result.panels;
    }
  result.converged = result.error_estimate <= abs_tol;
  return result;
}
}  // namespace detail

/// Adaptive Gauss-Legendre on [a, b] to an absolute tolerance: each panel is accepted
/// when the 10-point rule on it and on its two halves agree within tol * panel/(b-a).
/// The result is the finer estimate. max_depth bounds the bisection (2^-60 of the
/// interval is below double resolution anyway) and max_panels the total work, for a
/// tolerance below the rounding noise; hitting either clears `converged`.
///
/// That local rule asks every panel for the same relative accuracy. Near a point where
/// the integrand is nearly singular it cannot get it: the rounding of the nodes' arguments,
/// times a huge derivative, is noise above the panel's share (a cusp of an LA segment,
/// curvature 3e17 times its start's, bisected 60 levels deep all along its last 1e-7 of
/// length, 20,000 panels for each of its positions). So where the local rule needs more
/// than kLocalPanels panels (the shared data's curves need at most 32), the integral is
/// done again by the global rule (detail::integrateGlobal), whose noise is its own
/// panels' error: a few tens of panels there.
template <class F>
auto integrateAdaptive(F&& f, double a, double b, double abs_tol, int max_depth = 60, int max_panels = 20000) {
  constexpr int kLocalPanels = 128;
  using V = decltype(integrateFixed<10>(f, a, b));
  QuadratureResult<V> result;
  const V first = integrateFixed<10>(f, a, b);
  result.value = V(first * 0.0);
  result.converged = true;
  if (!(b > a)) return result;
  const double total = b - a;
  struct Pending {  // (a panel not yet split: its rule on the whole is known)
    double lo, hi;
    V whole;
    int depth;
  };
  std::vector<Pending> stack;
  stack.push_back({a, b, first, 0});
  while (!stack.empty()) {
    const Pending q = stack.back();
    stack.pop_back();
    const detail::AdaptivePanel<V> p = detail::adaptivePanel(f, q.lo, q.hi, q.whole, q.depth);
    const double allowed = abs_tol * (p.hi - p.lo) / total;
    const int panels = result.panels + static_cast<int>(stack.size());
    if (p.err > allowed && panels >= kLocalPanels && kLocalPanels < max_panels)
      return detail::integrateGlobal(f, a, b, first, abs_tol, max_depth, max_panels);
    if (p.err <= allowed || p.depth >= max_depth || panels >= max_panels) {
      if (p.err > allowed) result.converged = false;
      result.value += p.fine();
      result.error_estimate += p.err;
      ++result.panels;
    } else {
      stack.push_back({p.mid(), p.hi, p.right, p.depth + 1});
      stack.push_back({p.lo, p.mid(), p.left, p.depth + 1});
    }
  }
  return result;
}

}  // namespace la
