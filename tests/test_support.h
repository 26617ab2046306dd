#pragma once
// Helpers shared by the tests of the segment constructions and of the chain fit.

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/la_segment.h"

namespace la::test {

struct Triangle {
  Vec2 q0, q1, q2;
};

/// The control triangle of a segment: its end points and the intersection of its end
/// tangents (computed here by a 2x2 solve, independently of the constructions).
inline Triangle triangleOf(const LaSegment& seg) {
  const Vec2 p0 = seg.start(), p2 = seg.end(1e-15);
  const Vec2 t0 = seg.tangent(0.0), t1 = seg.tangent(seg.length());
  Eigen::Matrix2d m;  // p0 + a t0 = p2 - b t1
  m << t0.x(), t1.x(), t0.y(), t1.y();
  const Eigen::Vector2d ab = m.colPivHouseholderQr().solve(p2 - p0);
  return {p0, p0 + ab.x() * t0, p2};
}

inline double relDiff(double a, double b) {
  return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300});
}

// --- G2 chains of LA segments built with known parameters, sampled, measured.

/// One segment of a chain: its law, length and end curvature (its start follows the
/// previous segment's end). An infinite alpha is a straight line (its neighbours meet
/// it at zero curvature).
struct Spec {
  double alpha, length, kappa_end;
};

/// Appends an open G2 chain from its start pose and curvature and per-segment specs.
inline void appendChain(std::vector<LaSegment>& chain, Vec2 start, double theta, double kappa,
                        const std::vector<Spec>& specs) {
  for (const Spec& s : specs) {
    if (std::isinf(s.alpha)) chain.push_back(LaSegment::arc(s.length, start, theta, 0.0));
    else chain.emplace_back(s.alpha, s.length, start, theta, kappa, s.kappa_end);
    start = chain.back().end();
    theta = chain.back().theta(s.length);
    kappa = s.kappa_end;
  }
}

inline std::vector<LaSegment> buildChain(Vec2 start, double theta, double kappa, const std::vector<Spec>& specs) {
  std::vector<LaSegment> chain;
  appendChain(chain, start, theta, kappa, specs);
  return chain;
}

/// `per_segment` points on each segment, uniform in arc length, with gaussian noise
/// sigma (seeded), in order along the chain (a closed chain's start only once); point
/// per_segment * j is joint j.
inline std::vector<Vec2> sampleChain(const std::vector<LaSegment>& chain, int per_segment, double sigma, unsigned seed,
                                     bool closed = false) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const int last = closed && i + 1 == chain.size() ? per_segment - 1 : per_segment;
    for (int k = i == 0 ? 0 : 1; k <= last; ++k)
      points.push_back(chain[i].position(chain[i].length() * k / per_segment) + Vec2(noise(rng), noise(rng)));
  }
  return points;
}

/// Distance from each point to the chain, independent of the chain fit: on each segment
/// the nearest vertex of a dense polyline (LaSegment::sample), then Newton on the
/// closest-point condition with LaSegment's own position, tangent and curvature (adaptive
/// quadrature); the nearest of the segments' answers. (Every segment is refined: a point
/// just past a joint has its nearest vertex at the joint, where the segment that ends
/// there can only clamp.)
inline std::vector<double> distances(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points) {
  std::vector<CurveSamples> samples;
  for (const LaSegment& seg : chain) samples.push_back(seg.sample(2000));
  std::vector<double> out;
  for (const Vec2& p : points) {
    double best = INFINITY;
    for (std::size_t i = 0; i < chain.size(); ++i) {
      const CurveSamples& smp = samples[i];
      std::size_t nearest = 0;
      for (std::size_t k = 1; k < smp.size(); ++k)
        if ((smp.point[k] - p).squaredNorm() < (smp.point[nearest] - p).squaredNorm()) nearest = k;
      const LaSegment& seg = chain[i];
      double s = smp.s[nearest];
      for (int it = 0; it < 8; ++it) {
        const Vec2 d = p - seg.position(s), t = seg.tangent(s), n(-t.y(), t.x());
        s = std::clamp(s + t.dot(d) / (1.0 - seg.kappa(s) * n.dot(d)), 0.0, seg.length());
      }
      best = std::min({best, (p - seg.position(s)).norm(), (p - smp.point[nearest]).norm()});
    }
    out.push_back(best);
  }
  return out;
}

inline double maxDistance(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points) {
  const std::vector<double> d = distances(chain, points);
  return *std::max_element(d.begin(), d.end());
}

}  // namespace la::test
