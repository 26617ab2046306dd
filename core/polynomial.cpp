#include "core/polynomial.h"

#include <algorithm>
#include <cmath>

namespace la {

double evaluate(const Polynomial& p, double x) {
  double v = 0.0;
  for (auto it = p.rbegin(); it != p.rend(); ++it) v = v * x + *it;
  return v;
}

Polynomial derivative(const Polynomial& p) {
  Polynomial d;
  for (std::size_t k = 1; k < p.size(); ++k) d.push_back(k * p[k]);
  return d;
}

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  if (a.empty() || b.empty()) return {};
  Polynomial c(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

Polynomial operator+(const Polynomial& a, const Polynomial& b) {
  Polynomial c(std::max(a.size(), b.size()), 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) c[i] += a[i];
  for (std::size_t i = 0; i < b.size(); ++i) c[i] += b[i];
  return c;
}

Polynomial operator*(double s, const Polynomial& a) {
  Polynomial c(a);
  for (double& v : c) v *= s;
  return c;
}

namespace {

Polynomial trimmed(Polynomial p) {
  double scale = 0.0;
  for (double v : p) scale = std::max(scale, std::abs(v));
  while (!p.empty() && std::abs(p.back()) <= 1e-14 * scale) p.pop_back();
  return p;
}

// Root of p in [a, b] where p(a), p(b) have opposite signs: bisection with Newton steps.
double bracketedRoot(const Polynomial& p, const Polynomial& dp, double a, double b) {
  double fa = evaluate(p, a);
  double x = 0.5 * (a + b);
  for (int iter = 0; iter < 200 && b - a > 1e-15 * (1.0 + std::abs(x)); ++iter) {
    const double fx = evaluate(p, x);
    if (fx == 0.0) return x;
    if ((fx < 0.0) == (fa < 0.0)) {
      a = x;
      fa = fx;
    } else {
      b = x;
    }
    const double newton = x - fx / evaluate(dp, x);
    x = (newton > a && newton < b) ? newton : 0.5 * (a + b);
  }
  return x;
}

}  // namespace

std::vector<double> realRoots(const Polynomial& input, double lo, double hi) {
  const Polynomial p = trimmed(input);
  std::vector<double> roots;
  if (p.size() < 2 || !(hi > lo)) return roots;
  const Polynomial dp = derivative(p);
  // Between consecutive critical points p is monotone: at most one root each.
  std::vector<double> cuts{lo};
  for (double c : realRoots(dp, lo, hi))
    if (c > cuts.back()) cuts.push_back(c);
  cuts.push_back(hi);
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    const double fa = evaluate(p, a), fb = evaluate(p, b);
    if (fa == 0.0) {
      if (roots.empty() || a > roots.back()) roots.push_back(a);
    } else if ((fa < 0.0) != (fb < 0.0) && fb != 0.0) {
      roots.push_back(bracketedRoot(p, dp, a, b));
    }
  }
  // [lo, hi): drop a root at hi
  while (!roots.empty() && roots.back() >= hi) roots.pop_back();
  return roots;
}

}  // namespace la
