#include "core/bernstein.h"

#include <algorithm>
#include <cmath>

namespace la {
namespace {

// Control values below this times max|c_i| count as zero: subdivision rounds each
// value by ~n machine epsilons of the function's scale (n <= ~40 here).
constexpr double kZeroRelative = 1e-13;
// Below this width an interval with several sign changes in its control values is
// decided by the signs at its ends (one root or a cluster, as far as doubles can tell).
constexpr double kMinWidth = 1e-14;

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

int signOf(double v, double zero) { return v > zero ? 1 : (v < -zero ? -1 : 0); }

struct Signs {
  int changes = 0;
  int first = 0;  // sign of the first control value that is not zero (0 if all are)
  int last = 0;
};

Signs signsOf(const BernsteinCoefficients& c, double zero) {
  Signs s;
  for (double v : c) {
    const int g = signOf(v, zero);
    if (g == 0) continue;
    if (s.first == 0) s.first = g;
    if (s.last != 0 && g != s.last) ++s.changes;
    s.last = g;
  }
  return s;
}

// de Casteljau split at the middle.
void split(const BernsteinCoefficients& c, BernsteinCoefficients& left, BernsteinCoefficients& right) {
  BernsteinCoefficients w = c;
  const std::size_t n = c.size();
  left.resize(n);
  right.resize(n);
  for (std::size_t r = 0; r < n; ++r) {
    left[r] = w[0];
    right[n - 1 - r] = w[n - 1 - r];
    for (std::size_t i = 0; i + 1 < n - r; ++i) w[i] = 0.5 * (w[i] + w[i + 1]);
  }
}

void isolate(const BernsteinCoefficients& original, const BernsteinCoefficients& c, double a, double b, double zero,
             std::vector<double>& out) {
  const Signs sg = signsOf(c, zero);
  if (sg.changes == 0) return;
  if (sg.changes == 1) {  // exactly one simple root in (a, b): bisection on f
    double lo = a, hi = b;
    while (true) {
      const double m = 0.5 * (lo + hi);
      if (!(m > lo && m < hi)) break;
      const int g = signOf(evaluateBernstein(original, m), 0.0);
      if (g == 0) {
        lo = hi = m;
        break;
      }
      (g == sg.first ? lo : hi) = m;
    }
    out.push_back(0.5 * (lo + hi));
    return;
  }
  if (b - a < kMinWidth) {
    if (sg.first != sg.last) out.push_back(0.5 * (a + b));
    return;
  }
  BernsteinCoefficients left, right;
  split(c, left, right);
  const double m = 0.5 * (a + b);
  isolate(original, left, a, m, zero, out);
  // A root exactly at the split point is a zero end of both halves, seen by neither.
  if (signOf(right.front(), zero) == 0) {
    const int before = signsOf(left, zero).last, after = signsOf(right, zero).first;
    if (before != 0 && after != 0 && before != after) out.push_back(m);
  }
  isolate(original, right, m, b, zero, out);
}

}  // namespace

double evaluateBernstein(const BernsteinCoefficients& c, double t) {
  if (c.empty()) return 0.0;
  double small[32];
  std::vector<double> big;
  double* w = small;
  if (c.size() > 32) {
    big.assign(c.begin(), c.end());
    w = big.data();
  } else {
    std::copy(c.begin(), c.end(), small);
  }
  const double u = 1.0 - t;
  for (std::size_t r = c.size() - 1; r > 0; --r)
    for (std::size_t i = 0; i < r; ++i) w[i] = u * w[i] + t * w[i + 1];
  return w[0];
}

BernsteinCoefficients bernsteinDerivative(const BernsteinCoefficients& c) {
  const int n = static_cast<int>(c.size()) - 1;
  if (n < 1) return {0.0};
  BernsteinCoefficients d(n);
  for (int i = 0; i < n; ++i) d[i] = n * (c[i + 1] - c[i]);
  return d;
}

BernsteinCoefficients bernsteinIntegral(const BernsteinCoefficients& c) {
  const std::size_t n1 = c.size();  // n + 1
  BernsteinCoefficients F(n1 + 1, 0.0);
  double sum = 0.0;
  for (std::size_t j = 1; j <= n1; ++j) {
    sum += c[j - 1];
    F[j] = sum / static_cast<double>(n1);
  }
  return F;
}

BernsteinCoefficients bernsteinProduct(const BernsteinCoefficients& f, const BernsteinCoefficients& g) {
  const int n = static_cast<int>(f.size()) - 1, m = static_cast<int>(g.size()) - 1;
  BernsteinCoefficients p(n + m + 1, 0.0);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) p[i + j] += binomial(n, i) * binomial(m, j) * f[i] * g[j];
  for (int k = 0; k <= n + m; ++k) p[k] /= binomial(n + m, k);
  return p;
}

std::vector<double> bernsteinSignChanges(const BernsteinCoefficients& c) {
  std::vector<double> roots;
  double scale = 0.0;
  for (double v : c) scale = std::max(scale, std::abs(v));
  if (!(scale > 0.0) || !std::isfinite(scale)) return roots;
  isolate(c, c, 0.0, 1.0, kZeroRelative * scale, roots);
  return roots;
}

}  // namespace la
