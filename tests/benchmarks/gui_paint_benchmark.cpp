// How long one repaint of the canvas takes (issue 17, part 7: a repaint within a frame,
// 16 ms): the canvas rendered into a QImage, offscreen, with the default layers (raw
// points, curves, combs, marks). Two sketches: 50 faired strokes, and one stroke of
// 200,000 points. "zoomed" repaints after a zoom step, so caches keyed on the view are
// measured too. Reported per repaint (Google Benchmark's time column, in ms).
//
//   QT_QPA_PLATFORM=offscreen build/tests/benchmarks/gui_paint_benchmark

#include <benchmark/benchmark.h>

#include <QApplication>
#include <QImage>
#include <QPainter>
#include <QWheelEvent>
#include <cmath>
#include <numbers>
#include <memory>
#include <random>

#include "app/gui/canvas.h"
#include "app/gui/document.h"

namespace la::gui {
namespace {

constexpr int kWidth = 1100, kHeight = 760;

// A wavy pen stroke of n samples with a little noise (seeded: the same every run), with
// a pen pressure rising and falling along it where `pressure`.
Stroke waveStroke(int n, double x0, double y0, double length, double amplitude, unsigned seed, bool pressure = false) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.3);
  Stroke s;
  for (int i = 0; i < n; ++i) {
    const double x = x0 + length * i / (n - 1);
    StrokeSample q;
    q.p = Vec2(x + noise(rng), y0 + amplitude * std::sin((x - x0) / (length / 4.0)) + noise(rng));
    q.t = 8.0 * i;
    if (pressure) q.pressure = 0.2 + 0.7 * std::sin(std::numbers::pi * i / (n - 1));
    s.samples.push_back(q);
  }
  return s;
}

struct Sketch {
  Document document;
  std::unique_ptr<Canvas> canvas;
  QImage image{kWidth, kHeight, QImage::Format_ARGB32_Premultiplied};
  explicit Sketch(const std::vector<Stroke>& strokes) {
    for (const Stroke& s : strokes) document.addStroke(s);
    canvas = std::make_unique<Canvas>();
    canvas->resize(kWidth, kHeight);
    canvas->setDocument(&document);
    canvas->fitView();
    paint();  // (the first repaint after a change is not what is measured)
  }
  void paint() {
    QPainter p(&image);
    canvas->render(&p);
  }
};

Sketch& fiftyStrokes() {
  static Sketch sketch([] {
    std::vector<Stroke> strokes;
    for (int k = 0; k < 50; ++k)
      strokes.push_back(waveStroke(150, 20.0 + 40.0 * (k % 5), 30.0 + 15.0 * k, 700.0, 25.0 + k % 7, 17u + k));
    return strokes;
  }());
  return sketch;
}

// The same strokes drawn with pressure: their raw samples are pressure ink (Layers::pressure_ink).
Sketch& fiftyPenStrokes() {
  static Sketch sketch([] {
    std::vector<Stroke> strokes;
    for (int k = 0; k < 50; ++k)
      strokes.push_back(waveStroke(150, 20.0 + 40.0 * (k % 5), 30.0 + 15.0 * k, 700.0, 25.0 + k % 7, 17u + k, true));
    return strokes;
  }());
  return sketch;
}

Sketch& hugeStroke() {
  static Sketch sketch({waveStroke(200000, 0.0, 300.0, 1000.0, 150.0, 7u)});
  return sketch;
}

void repaint(benchmark::State& state, Sketch& sketch, bool zoomed) {
  for (auto _ : state) {
    if (zoomed) {  // alternate in and out about the middle: the view changes every repaint
      QWheelEvent wheel(QPointF(kWidth / 2.0, kHeight / 2.0), QPointF(), QPoint(), QPoint(0, state.iterations() % 2 ? 120 : -120),
                        Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
      QApplication::sendEvent(sketch.canvas.get(), &wheel);
    }
    sketch.paint();
  }
}

// The floor: the empty canvas (its background filled, the hint drawn).
void BM_RepaintEmpty(benchmark::State& state) {
  static Sketch empty({});
  repaint(state, empty, false);
}
// Layers one at a time over the 50 strokes (0 points, 1 curves, 2 combs, 3 marks).
void BM_Repaint50FairedStrokesOneLayer(benchmark::State& state) {
  Sketch& sketch = fiftyStrokes();
  const Layers saved = sketch.canvas->layers();
  Layers& l = sketch.canvas->layers();
  l.raw_points = state.range(0) == 0, l.curve = state.range(0) == 1, l.comb = state.range(0) == 2, l.markers = state.range(0) == 3;
  sketch.paint();
  repaint(state, sketch, false);
  sketch.canvas->layers() = saved;
}
BENCHMARK(BM_RepaintEmpty)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Repaint50FairedStrokesOneLayer)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_Repaint50FairedStrokes(benchmark::State& state) { repaint(state, fiftyStrokes(), false); }
void BM_Repaint50FairedStrokesZoomed(benchmark::State& state) { repaint(state, fiftyStrokes(), true); }
void BM_Repaint50FairedPenStrokesInk(benchmark::State& state) { repaint(state, fiftyPenStrokes(), false); }
void BM_Repaint200kPointStroke(benchmark::State& state) { repaint(state, hugeStroke(), false); }
void BM_Repaint200kPointStrokeZoomed(benchmark::State& state) { repaint(state, hugeStroke(), true); }

// The pen-up fit the UI thread makes of a drawn stroke of N samples (the provisional fit:
// stages 1-6), to choose where a stroke is fitted off the UI thread instead.
void BM_PenUpProvisionalFit(benchmark::State& state) {
  const Stroke s = waveStroke(static_cast<int>(state.range(0)), 0.0, 300.0, 800.0, 120.0, 3u);
  for (auto _ : state) {
    Document d;
    d.insertStroke(0, s, /*provisional=*/true);
    benchmark::DoNotOptimize(d.strokes().front().fit);
  }
}
BENCHMARK(BM_PenUpProvisionalFit)->Arg(500)->Arg(2000)->Arg(8000)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_Repaint50FairedStrokes)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Repaint50FairedStrokesZoomed)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Repaint50FairedPenStrokesInk)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Repaint200kPointStroke)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Repaint200kPointStrokeZoomed)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace la::gui

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
