#pragma once
// Explicit Bezier functions f(t) = sum_i c_i B_i^n(t) on t in [0, 1] (Bernstein
// polynomials B_i^n(t) = C(n, i) (1-t)^(n-i) t^i), the numerics behind the ALP curves
// of seeds 000 and 004: evaluation by de Casteljau, derivative, integral, product,
// and the points where f changes sign.
//
// Sign changes are found by subdivision (the variation-diminishing property: f has
// at most as many roots in (a, b) as its control values on [a, b] have sign changes,
// and the same parity), which is what seed 000 section 3.4 does with Bezier clipping:
// an interval whose control values keep one sign has no sign change of f, one with
// exactly one sign change has exactly one simple root, found by bisection.

#include <vector>

namespace la {

using BernsteinCoefficients = std::vector<double>;  // c_0..c_n, degree n = size - 1

/// f(t) by de Casteljau (stable for t in [0, 1]).
double evaluateBernstein(const BernsteinCoefficients& c, double t);

/// df/dt: degree n - 1 with coefficients n (c_{i+1} - c_i); the zero function of
/// degree 0 for a constant.
BernsteinCoefficients bernsteinDerivative(const BernsteinCoefficients& c);

/// F(t) = integral_0^t f: degree n + 1 with coefficients C_j = (1/(n+1)) sum_{i<j} c_i.
BernsteinCoefficients bernsteinIntegral(const BernsteinCoefficients& c);

/// f * g in the Bernstein basis of degree n + m:
/// (fg)_k = sum_{i+j=k} C(n,i) C(m,j) / C(n+m,k) f_i g_j.
BernsteinCoefficients bernsteinProduct(const BernsteinCoefficients& f, const BernsteinCoefficients& g);

/// The t in (0, 1) where f changes sign (roots of odd multiplicity), ascending, to
/// about 1e-15 in t. Touching zeros (even multiplicity) and zeros at t = 0 or 1 are
/// not sign changes. Control values below 1e-13 * max|c_i| count as zero (the
/// rounding of subdivision, ~n * machine epsilon, relative to the function's scale),
/// so a function that is zero up to rounding has no sign changes.
std::vector<double> bernsteinSignChanges(const BernsteinCoefficients& c);

}  // namespace la
