// A consumer of the installed lafair package: fits a noisy wave with la::fitStroke and
// checks what a user of the library relies on: the curve is within the fit's tolerance
// of every point and G2 at its joints. The joints are measured here from the segments'
// own functions (core's LaSegment: end point, theta(s), kappa(s)), not taken from the
// fit's figures, which read the segments' stored end values. Returns non-zero
// otherwise, printing each figure and its threshold.
//
// The stroke: one period of y = 30 sin(x / 20), x in [0, 40 pi], 200 points evenly in x
// time-stamped as a 125 Hz pen would, with Gaussian noise of sigma 0.2 on both
// coordinates (std::mt19937, seed 1), fitted with an absolute tolerance of 1.0 (five
// sigma). Its curvature, -1.5 sin(x / 20) / (20 (1 + 2.25 cos^2(x / 20))^1.5), changes
// sign once and has two extrema, so the curve needs joints, and its fit must show the
// one inflection.

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <exception>
#include <numbers>
#include <random>

#include "core/la_segment.h"
#include "fitting/pipeline.h"

namespace {

constexpr double kAmplitude = 30.0;
constexpr double kWavelengthOver2Pi = 20.0;
constexpr int kPoints = 200;
constexpr double kNoiseSigma = 0.2;  // same units as the coordinates
constexpr double kTolerance = 1.0;
// The project's own thresholds for G2 joints (tests/pipeline_test.cpp, DESIGN.md section 6).
constexpr double kG0Threshold = 1e-9;  // of the bounding-box diagonal
constexpr double kG1Threshold = 1e-9;  // radians
constexpr double kG2Threshold = 1e-6;  // relative curvature jump

la::Stroke noisyWave() {
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, kNoiseSigma);
  la::Stroke stroke;
  for (int i = 0; i < kPoints; ++i) {
    const double x = 2.0 * std::numbers::pi * kWavelengthOver2Pi * i / (kPoints - 1);
    la::StrokeSample sample;
    sample.p = la::Vec2(x + noise(rng), kAmplitude * std::sin(x / kWavelengthOver2Pi) + noise(rng));
    sample.t = 8.0 * i;  // ms
    stroke.samples.push_back(sample);
  }
  return stroke;
}

struct JointGaps {
  double g0 = 0.0;  // distance, relative to the diagonal
  double g1 = 0.0;  // tangent angle, radians
  double g2 = 0.0;  // curvature, relative to the larger one (or to 1 / diagonal)
};

JointGaps measureJoints(const la::Curve& curve, double diagonal) {
  JointGaps gaps;
  for (std::size_t j = 1; j < curve.pieces.size(); ++j) {
    const la::LaSegment& a = curve.pieces[j - 1].segment;
    const la::LaSegment& b = curve.pieces[j].segment;
    gaps.g0 = std::max(gaps.g0, (a.end() - b.start()).norm() / diagonal);
    gaps.g1 = std::max(gaps.g1, std::abs(la::wrapAngle(b.theta(0.0) - a.theta(a.length()))));
    const double ka = a.kappa(a.length()), kb = b.kappa(0.0);
    gaps.g2 = std::max(gaps.g2, std::abs(ka - kb) / std::max({std::abs(ka), std::abs(kb), 1.0 / diagonal}));
  }
  return gaps;
}

bool check(bool ok, const char* what, double value, const char* relation, double threshold) {
  std::printf("%-4s %-36s %.3g %s %.3g\n", ok ? "ok" : "FAIL", what, value, relation, threshold);
  return ok;
}

}  // namespace

int main() {
  try {
    la::FitOptions options;
    options.tolerance = kTolerance;
    const la::FitResult r = la::fitStroke(noisyWave(), options);
    if (r.curve.pieces.empty() || r.curve.closed) {
      std::printf("FAIL expected an open curve, got %zu segments%s\n", r.curve.pieces.size(), r.curve.closed ? ", closed" : "");
      return 1;
    }
    for (const std::string& w : r.warnings) std::printf("warning: %s\n", w.c_str());

    const la::QualityFigures& q = r.quality;
    std::printf("%d segments, %d inflections, %d extrema; G2 solve: %s\n", q.segments, q.inflections, q.extrema,
                r.g2.message.c_str());
    bool ok = check(q.segments >= 2, "segments (the curve has joints)", q.segments, ">=", 2);
    ok &= check(q.max_dev <= r.tolerance, "max distance of a point to the curve", q.max_dev, "<=", r.tolerance);
    ok &= check(q.corners == 0, "corners", q.corners, "==", 0);
    const JointGaps gaps = measureJoints(r.curve, q.diagonal);
    ok &= check(gaps.g0 < kG0Threshold, "position gap at joints (of diagonal)", gaps.g0, "<", kG0Threshold);
    ok &= check(gaps.g1 < kG1Threshold, "tangent gap at joints (rad)", gaps.g1, "<", kG1Threshold);
    ok &= check(gaps.g2 < kG2Threshold, "curvature gap at joints (relative)", gaps.g2, "<", kG2Threshold);
    ok &= check(q.inflections == 1, "inflections", q.inflections, "==", 1);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("FAIL fitStroke threw: %s\n", e.what());
    return 1;
  }
}
