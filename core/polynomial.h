#pragma once
// Small dense polynomials in one variable (coefficients lowest degree first) and their
// real roots in an interval, for the per-span root finding of the segmentation.

#include <vector>

namespace la {

using Polynomial = std::vector<double>;  // p[k] is the coefficient of x^k

double evaluate(const Polynomial& p, double x);
Polynomial derivative(const Polynomial& p);
Polynomial operator*(const Polynomial& a, const Polynomial& b);
Polynomial operator+(const Polynomial& a, const Polynomial& b);
Polynomial operator*(double s, const Polynomial& a);

/// Real roots in [lo, hi), ascending. Roots of odd multiplicity are found exactly (to
/// machine precision) by bisection refined with Newton between the critical points of
/// p (found recursively from p'), so no sign change is missed; even-multiplicity
/// roots (touching zero) are not returned. Leading coefficients below
/// 1e-14 * max|coefficient| are dropped first.
std::vector<double> realRoots(const Polynomial& p, double lo, double hi);

}  // namespace la
