#pragma once
// The data sets of the shared data (../shared/data, see its SOURCES.md) as the tests
// and benchmarks that fit them all group them: which files, and the options their
// strokes are fitted with. Used by tests/fit_data_test.cpp and
// tests/benchmarks/data_benchmark.cpp.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "fitting/pipeline.h"

namespace la::test {

struct DataSet {
  const char* name;
  const char* folder;     // relative to the data folder, searched recursively
  const char* extension;  // lower case, with the dot
  // Glyph contours are fitted with CleanupOptions::assume_closed, the option stroke.h
  // documents for font outlines: their CSVs do not sample a contour's closing straight
  // edge (the implicit line back to the start), so some contours end 25-90% of their
  // diagonal from their start (DejaVuSans_a #0, _e #1, _g #1) and no gap test can
  // tell them from an open stroke. Everything else: default options.
  bool assume_closed = false;
};

inline constexpr DataSet kDataSets[] = {
    {"dollar1", "strokes/dollar1_unistroke_s01_pilot", ".csv"},
    {"mmg", "strokes/mmg_s10_stylus_medium", ".csv"},
    {"omniglot", "strokes/omniglot_small1_sample", ".csv"},
    {"airfoils", "curves/airfoils", ".dat"},
    {"kanjivg_csv", "curves/kanjivg", ".csv"},
    {"kanjivg_svg", "curves/kanjivg", ".svg"},
    {"glyphs", "curves/glyphs_dejavusans", ".csv", true},
};

/// `options` with what the set's strokes need on top.
inline FitOptions fitOptionsFor(const DataSet& set, FitOptions options = {}) {
  options.cleanup.assume_closed = set.assume_closed;
  return options;
}

/// The files under `folder` (recursively) whose extension is `extension` in any case,
/// sorted; none if the folder does not exist.
inline std::vector<std::filesystem::path> filesOf(const std::filesystem::path& folder, const std::string& extension) {
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
  };
  std::vector<std::filesystem::path> out;
  if (!std::filesystem::is_directory(folder)) return out;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder))
    if (entry.is_regular_file() && lower(entry.path().extension().string()) == extension) out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// Variant k of a stroke (data_benchmark --variants): scaled by 1 + k/10, moved by
/// k (12.345, -6.789), turned by k quarter turns. The fit is invariant under all three.
inline Stroke variantOf(const Stroke& stroke, int k) {
  Stroke out = stroke;
  for (StrokeSample& s : out.samples) {
    s.p = (1.0 + 0.1 * k) * s.p + k * Vec2(12.345, -6.789);
    for (int q = 0; q < k % 4; ++q) s.p = Vec2(-s.p.y(), s.p.x());
  }
  return out;
}

/// The stroke's points, without their times.
inline std::vector<Vec2> pointsOf(const Stroke& stroke) {
  std::vector<Vec2> points;
  for (const StrokeSample& s : stroke.samples) points.push_back(s.p);
  return points;
}

/// The sample at fraction f of the step from a to b (its time too; NaN stays NaN).
inline StrokeSample between(const StrokeSample& a, const StrokeSample& b, double f) {
  StrokeSample s = a;
  s.p = (1.0 - f) * a.p + f * b.p;
  s.t = (1.0 - f) * a.t + f * b.t;
  return s;
}

/// The stroke with each step between two samples cut into `parts(its length)` equal
/// parts, the samples kept, as a resampler does.
template <typename Parts>
Stroke withStepsCut(const Stroke& stroke, Parts parts) {
  const std::vector<StrokeSample>& in = stroke.samples;
  Stroke out = stroke;
  if (in.empty()) return out;
  out.samples.clear();
  for (std::size_t i = 0; i + 1 < in.size(); ++i) {
    out.samples.push_back(in[i]);
    const int n = parts((in[i + 1].p - in[i].p).norm());
    for (int j = 1; j < n; ++j) out.samples.push_back(between(in[i], in[i + 1], static_cast<double>(j) / n));
  }
  out.samples.push_back(in.back());
  return out;
}

/// The stroke subdivided k-fold: k - 1 points evenly on each step between two samples.
inline Stroke subdivided(const Stroke& stroke, int k) {
  return withStepsCut(stroke, [k](double) { return k; });
}

/// The stroke with each step between two samples filled with points `step` apart or
/// less, evenly, as an importer flattening a polyline does; the samples stay.
inline Stroke filledSteps(const Stroke& stroke, double step) {
  return withStepsCut(stroke, [step](double length) { return std::max(1, static_cast<int>(std::ceil(length / step))); });
}

/// The stroke resampled by arc length: points `step` apart along its polyline from its
/// first sample, and its last (their times interpolated); the samples between are gone.
inline Stroke resampledEvenly(const Stroke& stroke, double step) {
  const std::vector<StrokeSample>& in = stroke.samples;
  Stroke out = stroke;
  if (in.size() < 2) return out;
  out.samples = {in.front()};
  double to_next = step;  // (along the polyline, from the start of the current step)
  for (std::size_t i = 0; i + 1 < in.size(); ++i) {
    const double length = (in[i + 1].p - in[i].p).norm();
    for (; to_next < length; to_next += step) out.samples.push_back(between(in[i], in[i + 1], to_next / length));
    to_next -= length;
  }
  out.samples.push_back(in.back());
  return out;
}

/// `p` scaled by `scale` and rounded to its pixel.
inline Vec2 pixelOf(const Vec2& p, double scale) { return Vec2(std::round(scale * p.x()), std::round(scale * p.y())); }

/// `s` appended unless the last sample is on its point already (a pointer reports a
/// pixel once while it stays there).
inline void addUnlessRepeated(Stroke& out, const StrokeSample& s) {
  if (out.samples.empty() || out.samples.back().p != s.p) out.samples.push_back(s);
}

/// The stroke as a slow mouse gives it: scaled to `diagonal` pixels, the pointer's path a
/// Catmull-Rom spline through the samples (or, `along_polyline`, the straight steps between
/// them), and a sample at every pixel it enters (integer coordinates, times interpolated),
/// a pixel or two apart where the samples were many.
inline Stroke walkedByPixels(const Stroke& stroke, double diagonal, bool along_polyline = false) {
  const std::vector<StrokeSample>& in = stroke.samples;
  const double scale = diagonal / boundingBoxDiagonal(pointsOf(stroke));
  Stroke out = stroke;
  if (in.size() < 2 || !std::isfinite(scale)) return out;
  out.samples.clear();
  const std::size_t n = in.size();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Vec2 p0 = in[i > 0 ? i - 1 : 0].p, p1 = in[i].p, p2 = in[i + 1].p, p3 = in[std::min(i + 2, n - 1)].p;
    const int steps = 4 * std::max(1, static_cast<int>(std::ceil(scale * (p2 - p1).norm())));  // (no pixel skipped)
    for (int k = 0; k < steps; ++k) {
      const double t = static_cast<double>(k) / steps;
      StrokeSample s = between(in[i], in[i + 1], t);
      s.p = pixelOf(along_polyline ? Vec2(p1 + (p2 - p1) * t)
                                   : Vec2(0.5 * (2.0 * p1 + (p2 - p0) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t * t +
                                                 (3.0 * p1 - p0 - 3.0 * p2 + p3) * t * t * t)),
                    scale);
      addUnlessRepeated(out, s);
    }
  }
  StrokeSample last = in.back();
  last.p = pixelOf(last.p, scale);
  addUnlessRepeated(out, last);
  return out;
}

/// The stroke's samples as a pointer reports them on a screen where it spans `diagonal`
/// pixels: each scaled and rounded to a pixel, one of a run on the same pixel kept (a
/// mouse's or a tablet's events, several pixels apart where the pen moves fast).
inline Stroke roundedToPixels(const Stroke& stroke, double diagonal) {
  const double scale = diagonal / boundingBoxDiagonal(pointsOf(stroke));
  Stroke out = stroke;
  if (!std::isfinite(scale)) return out;
  out.samples.clear();
  for (StrokeSample s : stroke.samples) {
    s.p = pixelOf(s.p, scale);
    addUnlessRepeated(out, s);
  }
  return out;
}

/// How a device or an importer may have handed the samples over (data_benchmark
/// --handed-over): as drawn; each point averaged with its neighbours by [1 2 1] / 4, the
/// ends kept (a tablet driver's smoothing: the noise then shared by neighbours); or with
/// the midpoint of every step filled in (an importer's resampling); with every step
/// filled at a 300th of the stroke's diagonal (an importer flattening a polyline, about
/// a pixel at a drawing's size), or resampled by arc length at that spacing without the
/// samples. The same strokes: the fit should read the same noise and draw about the same
/// curves. Or walked by a slow mouse at a diagonal of 800 pixels (walkedByPixels): the
/// samples' wiggles, scaled up, are shape at the pixels' scale, so the curves have more
/// segments; the figures to watch are the time and the guarantees. Or rounded to the
/// pixels of a diagonal of 150 (roundedToPixels): the samples as drawn, on a coarse grid.
enum class HandedOver { kAsDrawn, kSmoothed, kMidpoints, kFilled, kResampled, kWalked, kRounded };

inline Stroke handedOver(const Stroke& stroke, HandedOver how) {
  if (how == HandedOver::kMidpoints) return subdivided(stroke, 2);
  if (how == HandedOver::kWalked) return walkedByPixels(stroke, 800.0);
  if (how == HandedOver::kRounded) return roundedToPixels(stroke, 150.0);
  if (how == HandedOver::kFilled || how == HandedOver::kResampled) {
    const double step = boundingBoxDiagonal(pointsOf(stroke)) / 300.0;
    if (!(step > 0.0)) return stroke;
    return how == HandedOver::kFilled ? filledSteps(stroke, step) : resampledEvenly(stroke, step);
  }
  Stroke out = stroke;
  if (how == HandedOver::kSmoothed) {
    const std::vector<StrokeSample>& in = stroke.samples;
    for (std::size_t i = 1; i + 1 < in.size(); ++i) out.samples[i].p = (in[i - 1].p + 2.0 * in[i].p + in[i + 1].p) / 4.0;
  }
  return out;
}

}  // namespace la::test
