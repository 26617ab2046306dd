#pragma once
// Strokes a resampler subdivided: between every two samples it put k - 1 points evenly on
// their chord (an importer's or a device's upsampling), so every point but the samples
// is the midpoint of its neighbours; or it filled every step at a fixed spacing (an
// importer flattening a polyline), or resampled the stroke by arc length. Such points
// say nothing the samples do not: fitted, they hid the samples' noise (every fourth
// difference spans a midpoint: the shared strokes subdivided 2-fold read their noise at
// about half, the fit followed the samples' wobble, 6 curvature extrema at the median
// where the strokes have 2, 16 of 207 curves off the tolerance, up to 1.7 s; filled a
// 300th of the diagonal apart, 3,743 extrema where they have 633, up to 15 s),
// shortened the clean-up's steps (a pen-down hook of two samples went unseen), and
// pulled the curve onto the chords. The clean-up
// (fitting/stroke.h) leaves them out, as it does duplicates: the stroke is fitted as
// drawn, and the curve is measured against every point.

#include <vector>

#include "core/geometry.h"

namespace la {

/// Which of `points` are the samples, where a resampler subdivided them 2- or 3-fold (a
/// 4-fold subdivision is a 2-fold one twice): the first and last point and every k-th
/// between, the one class of the points by index (mod k) that is not all at midpoints of
/// their neighbours. Empty where the points are not so (the drawn strokes: at most 75% of
/// one class of two are midpoints, a pointer walking a pixel per sample; an evenly
/// sampled straight or gently curved outline: every class).
std::vector<bool> subdivisionSamples(const std::vector<Vec2>& points);

/// Which of `points` are the samples, where a resampler filled the straight steps between
/// them with points at even spacing, as many per step as its length asks (an importer
/// flattening a polyline at a fixed step): the points that are not at the midpoint of
/// their neighbours. Resampled by arc length, without the samples, the points beside
/// each sample stand in for it. Empty where fewer than half the points are the
/// resampler's: drawn strokes; an evenly sampled gently curved outline, whose points are
/// each nearly a midpoint but whose runs of them bend away from their chords; a pixel
/// stroke as drawn, whose samples along a row or column are midpoints on its own grid
/// (filled at a fraction of a pixel, its fills are found: they are off that grid).
std::vector<bool> filledStepSamples(const std::vector<Vec2>& points);

/// The samples among `points` where a resampler put points between them: a subdivision
/// where every point it leaves out is at a midpoint (the classes by index are exact),
/// else filled steps, else a subdivision whose classes a few points shifted (a drawn
/// duplicate gone with its midpoint). Empty where neither.
std::vector<bool> resamplerSamples(const std::vector<Vec2>& points);

}  // namespace la
