#include "core/bspline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace la {

CubicBSpline::CubicBSpline(std::vector<double> knots, std::vector<Vec2> control)
    : knots_(std::move(knots)), control_(std::move(control)) {
  if (control_.size() < 4 || knots_.size() != control_.size() + 4)
    throw std::invalid_argument("cubic B-spline needs >= 4 control points and control + 4 knots (got " +
                                std::to_string(control_.size()) + " and " + std::to_string(knots_.size()) + ")");
  for (std::size_t i = 1; i < knots_.size(); ++i)
    if (!(knots_[i] >= knots_[i - 1])) throw std::invalid_argument("B-spline knots must be non-decreasing");
  if (!(tMax() > tMin())) throw std::invalid_argument("B-spline has an empty parameter range");
}

CubicBSpline CubicBSpline::clamped(const std::vector<double>& breaks, std::vector<Vec2> control) {
  std::vector<double> knots{breaks.front(), breaks.front(), breaks.front()};
  knots.insert(knots.end(), breaks.begin(), breaks.end());
  knots.insert(knots.end(), {breaks.back(), breaks.back(), breaks.back()});
  return CubicBSpline(std::move(knots), std::move(control));
}

CubicBSpline CubicBSpline::periodic(const std::vector<double>& breaks, const std::vector<Vec2>& control) {
  const int n = static_cast<int>(control.size());
  if (n < 3 || static_cast<int>(breaks.size()) != n + 1)
    throw std::invalid_argument("periodic cubic B-spline needs >= 3 control points and control + 1 breaks");
  const double period = breaks.back() - breaks.front();
  // Extended knots u_{-3} .. u_{n+3}: breaks shifted by one period on either side.
  std::vector<double> knots;
  for (int k = -3; k <= n + 3; ++k) {
    const int j = ((k % n) + n) % n;
    const double shift = std::floor(static_cast<double>(k) / n) * period;
    knots.push_back(breaks[j] + shift);
  }
  std::vector<Vec2> ext(control);
  for (int k = 0; k < 3; ++k) ext.push_back(control[k]);
  // n + 3 control points need n + 7 knots: the list above has n + 7 entries.
  CubicBSpline s(std::move(knots), std::move(ext));
  s.periodic_count_ = n;
  return s;
}

std::vector<double> CubicBSpline::breaks() const {
  std::vector<double> out;
  for (std::size_t i = kDegree; i + kDegree < knots_.size(); ++i)
    if (out.empty() || knots_[i] > out.back()) out.push_back(knots_[i]);
  return out;
}

double CubicBSpline::wrap(double t) const {
  if (isPeriodic()) {
    const double period = tMax() - tMin();
    t = tMin() + std::fmod(t - tMin(), period);
    if (t < tMin()) t += period;
    if (t >= tMax()) t = tMin();
    return t;
  }
  return std::clamp(t, tMin(), tMax());
}

int CubicBSpline::span(double t) const {
  t = wrap(t);
  const int last = static_cast<int>(control_.size()) - 1;  // highest valid span index
  if (t >= knots_[last + 1]) return last;
  // first knot > t, minus one; restricted to [kDegree, last]
  const auto it = std::upper_bound(knots_.begin() + kDegree, knots_.begin() + last + 1, t);
  return static_cast<int>(it - knots_.begin()) - 1;
}

void CubicBSpline::basis(int i, double t, double ders[4][4], int order) const {
  // The NURBS Book A2.3 for p = 3, all derivatives up to 3.
  constexpr int p = kDegree;
  double ndu[p + 1][p + 1], left[p + 1], right[p + 1];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots_[i + 1 - j];
    right[j] = knots_[i + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[j][r] == 0.0 ? 0.0 : ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  if (order <= 0) return;
  double a[2][p + 1] = {};
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= order; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = ndu[pk + 1][rk] == 0.0 ? 0.0 : a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = ndu[pk + 1][rk + j] == 0.0 ? 0.0 : (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = ndu[pk + 1][r] == 0.0 ? 0.0 : -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= order; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= factor;
    factor *= (p - k);
  }
}

std::array<Vec2, 4> CubicBSpline::derivatives(double t, int order) const {
  t = wrap(t);
  const int i = span(t);
  double ders[4][4];
  basis(i, t, ders, order);
  std::array<Vec2, 4> out;
  out.fill(Vec2::Zero());
  for (int d = 0; d <= order; ++d) {
    out[d] = Vec2::Zero();
    for (int j = 0; j <= kDegree; ++j) out[d] += ders[d][j] * control_[i - kDegree + j];
  }
  return out;
}

Vec2 CubicBSpline::evaluate(double t, int derivative) const { return derivatives(t, derivative)[derivative]; }

double CubicBSpline::curvature(double t) const {
  const auto d = derivatives(t, 2);
  const double speed = d[1].norm();
  return cross(d[1], d[2]) / (speed * speed * speed);
}

void CubicBSpline::curvatureAndSlope(double t, double& kappa, double& dkappa_ds) const {
  // kappa = (C1 x C2) / |C1|^3 and dkappa/dt = ((C1 x C3) |C1|^2 - 3 (C1 x C2)(C1 . C2)) / |C1|^5,
  // Ck the k-th derivative in t; dkappa/ds = dkappa/dt / |C1|.
  const auto d = derivatives(t, 3);
  const double sp2 = d[1].squaredNorm(), sp = std::sqrt(sp2), cr = cross(d[1], d[2]);
  kappa = cr / (sp2 * sp);
  dkappa_ds = (cross(d[1], d[3]) * sp2 - 3.0 * cr * d[1].dot(d[2])) / (sp2 * sp2 * sp) / sp;
}

std::array<Vec2, 4> CubicBSpline::spanPolynomial(int i) const {
  const double t0 = knots_[i];
  double ders[4][4];
  basis(i, t0, ders);
  std::array<Vec2, 4> c;
  const double fact[4] = {1.0, 1.0, 2.0, 6.0};
  for (int d = 0; d < 4; ++d) {
    c[d] = Vec2::Zero();
    for (int j = 0; j <= kDegree; ++j) c[d] += ders[d][j] * control_[i - kDegree + j];
    c[d] /= fact[d];
  }
  return c;
}

}  // namespace la
