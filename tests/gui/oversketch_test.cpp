// The oversketch splice (app/gui/oversketch.h) without a window: which old samples are
// kept, in which order the new ones go in, and the cases of one join, two joins, a closed
// stroke and none. The strokes are in world units with a reach of 8 (pixels at zoom 1).

#include "app/gui/oversketch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace la::gui {
namespace {

constexpr double kReach = 8.0;

Stroke strokeOf(const std::vector<Vec2>& pts) {
  Stroke s;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    StrokeSample q;
    q.p = pts[i];
    q.t = 10.0 * static_cast<double>(i);
    s.samples.push_back(q);
  }
  return s;
}

// A gentle wave from x = 0 to 400, a sample every 4 units.
std::vector<Vec2> wavePoints(double x0 = 0, double x1 = 400, double dy = 0) {
  std::vector<Vec2> pts;
  for (double x = x0; x <= x1 + 1e-9; x += 4.0) pts.emplace_back(x, 60.0 * std::sin(x / 90.0) + dy);
  return pts;
}

DocumentStroke documentStroke(const std::vector<Vec2>& pts) {
  Document d;
  d.addStroke(strokeOf(pts));
  return d.strokes().front();
}

bool same(const StrokeSample& a, const StrokeSample& b) { return a.p == b.p; }

// `spliced` is old[0, before) + fresh (reversed or not) + old[after, n).
void expectSplice(const Oversketch& o, const std::vector<StrokeSample>& old, const std::vector<StrokeSample>& fresh,
                  bool reversed_fresh) {
  const auto& r = o.raw.samples;
  ASSERT_EQ(r.size(), o.kept_before + fresh.size() + (old.size() - o.kept_after));
  for (std::size_t i = 0; i < o.kept_before; ++i) EXPECT_TRUE(same(r[i], old[i])) << "kept before, sample " << i;
  for (std::size_t i = 0; i < fresh.size(); ++i)
    EXPECT_TRUE(same(r[o.kept_before + i], fresh[reversed_fresh ? fresh.size() - 1 - i : i])) << "new sample " << i;
  for (std::size_t i = o.kept_after; i < old.size(); ++i)
    EXPECT_TRUE(same(r[o.kept_before + fresh.size() + i - o.kept_after], old[i])) << "kept after, sample " << i;
  for (std::size_t i = 1; i < r.size(); ++i) EXPECT_GE(r[i].t, r[i - 1].t) << "time stamps keep increasing";
}

TEST(Oversketch, BothEndsNearTheMiddleReplaceIt) {
  const DocumentStroke old = documentStroke(wavePoints());
  // from x = 120 to 280, 3 units beside the old stroke at its ends, 25 above it between
  std::vector<Vec2> pts;
  for (double x = 120; x <= 280; x += 4.0)
    pts.emplace_back(x, 60.0 * std::sin(x / 90.0) + 3.0 - 25.0 * std::sin(std::numbers::pi * (x - 120) / 160.0));
  const Stroke fresh = strokeOf(pts);
  const std::optional<Oversketch> o = oversketch(old, fresh, kReach);
  ASSERT_TRUE(o);
  ASSERT_TRUE(o->start && o->end);
  EXPECT_NEAR(o->start->s, 120.0 * 1.1, 0.15 * 120.0) << "the join's arc length (the wave is ~10% longer than its x run)";
  EXPECT_FALSE(o->reversed);
  EXPECT_FALSE(o->closes);
  expectSplice(*o, old.raw.samples, fresh.samples, false);
  // old samples within two reaches of a join went, the others stayed
  EXPECT_LT(old.raw.samples[o->kept_before - 1].p.x(), 120.0 - 2 * kReach * 0.7);
  EXPECT_GT(old.raw.samples[o->kept_before].p.x(), 120.0 - 2 * kReach - 4.0);
  EXPECT_GT(old.raw.samples[o->kept_after].p.x(), 280.0 + 2 * kReach * 0.7);
}

TEST(Oversketch, ANewStrokeRunningBackwardsIsReversed) {
  const DocumentStroke old = documentStroke(wavePoints());
  std::vector<Vec2> pts;
  for (double x = 280; x >= 120; x -= 4.0) pts.emplace_back(x, 60.0 * std::sin(x / 90.0) - 2.0 + 20.0 * std::sin((x - 120) / 51.0));
  const Stroke fresh = strokeOf(pts);
  const std::optional<Oversketch> o = oversketch(old, fresh, kReach);
  ASSERT_TRUE(o && o->start && o->end);
  EXPECT_TRUE(o->reversed);
  expectSplice(*o, old.raw.samples, fresh.samples, true);
}

TEST(Oversketch, AStrokeFromTheEndExtendsIt) {
  const DocumentStroke old = documentStroke(wavePoints());
  const Vec2 end = old.raw.samples.back().p;
  std::vector<Vec2> pts;
  for (double x = 2; x <= 150; x += 4.0) pts.emplace_back(end.x() + x, end.y() - 0.004 * x * x);
  const Stroke fresh = strokeOf(pts);
  const std::optional<Oversketch> o = oversketch(old, fresh, kReach);
  ASSERT_TRUE(o && o->start);
  EXPECT_FALSE(o->end);
  EXPECT_FALSE(o->reversed);
  EXPECT_EQ(o->kept_after, old.raw.samples.size()) << "nothing after the new samples";
  expectSplice(*o, old.raw.samples, fresh.samples, false);
  EXPECT_GT(o->kept_before, old.raw.samples.size() - 8) << "only the blend near the end went";
}

TEST(Oversketch, OneJoinInTheInteriorReplacesToTheNearerEnd) {
  const DocumentStroke old = documentStroke(wavePoints());
  // starts on the old stroke at x = 100 (nearer its start) and runs off up-left: the old
  // stroke's head is replaced, the new samples reversed so the result runs as the old did
  std::vector<Vec2> pts;
  const double y = 60.0 * std::sin(100.0 / 90.0);
  for (double t = 0; t <= 120; t += 4.0) pts.emplace_back(100.0 - t, y - 0.8 * t);
  const Stroke fresh = strokeOf(pts);
  const std::optional<Oversketch> o = oversketch(old, fresh, kReach);
  ASSERT_TRUE(o && o->start);
  EXPECT_FALSE(o->end);
  EXPECT_TRUE(o->reversed);
  EXPECT_EQ(o->kept_before, 0u) << "the head went";
  expectSplice(*o, old.raw.samples, fresh.samples, true);
  EXPECT_GT(old.raw.samples[o->kept_after].p.x(), 100.0 + kReach);

  // the same from its end point (drawn towards the stroke): the head goes, not reversed
  std::vector<Vec2> back(pts.rbegin(), pts.rend());
  const std::optional<Oversketch> o2 = oversketch(old, strokeOf(back), kReach);
  ASSERT_TRUE(o2 && o2->end && !o2->start);
  EXPECT_FALSE(o2->reversed);
  expectSplice(*o2, old.raw.samples, strokeOf(back).samples, false);
}

TEST(Oversketch, JoiningBothEndsClosesTheStroke) {
  std::vector<Vec2> arc;  // three quarters of a circle
  for (int i = 0; i <= 90; ++i) {
    const double a = 1.5 * std::numbers::pi * i / 90.0;
    arc.emplace_back(100.0 * std::cos(a), 100.0 * std::sin(a));
  }
  const DocumentStroke old = documentStroke(arc);
  std::vector<Vec2> rest;  // the missing quarter, from the old end back to its start
  for (int i = 1; i < 30; ++i) {
    const double a = 1.5 * std::numbers::pi + 0.5 * std::numbers::pi * i / 30.0;
    rest.emplace_back(102.0 * std::cos(a), 102.0 * std::sin(a));
  }
  const std::optional<Oversketch> o = oversketch(old, strokeOf(rest), kReach);
  ASSERT_TRUE(o && o->start && o->end);
  EXPECT_TRUE(o->closes);
  EXPECT_FALSE(o->reversed);
  expectSplice(*o, old.raw.samples, strokeOf(rest).samples, false);
}

// A closed stroke: a circle of radius 100 drawn counter-clockwise, fitted closed.
class ClosedOversketch : public ::testing::Test {
 protected:
  void SetUp() override {
    std::vector<Vec2> pts;
    for (int i = 0; i < 157; ++i) {
      const double a = 2 * std::numbers::pi * i / 157.0;
      pts.emplace_back(100.0 * std::cos(a), 100.0 * std::sin(a));
    }
    old = documentStroke(pts);
    ASSERT_TRUE(old.fit && old.fit->curve.closed) << "the circle is fitted closed";
  }
  // A bump outward between angles a0 and a1 (radians), drawn from a0 to a1.
  static Stroke bump(double a0, double a1) {
    std::vector<Vec2> pts;
    for (int i = 0; i <= 40; ++i) {
      const double a = a0 + (a1 - a0) * i / 40.0, r = 101.0 + 20.0 * std::sin(std::numbers::pi * i / 40.0);
      pts.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    return strokeOf(pts);
  }
  DocumentStroke old;
};

TEST_F(ClosedOversketch, TheShorterArcIsReplacedKeepingTheLoopsDirection) {
  for (const bool backwards : {false, true}) {
    SCOPED_TRACE(backwards ? "drawn clockwise" : "drawn counter-clockwise");
    const Stroke fresh = backwards ? bump(1.2, 0.4) : bump(0.4, 1.2);
    const std::optional<Oversketch> o = oversketch(old, fresh, kReach);
    ASSERT_TRUE(o && o->start && o->end);
    EXPECT_EQ(o->reversed, backwards);
    // the result: the new samples (counter-clockwise), then the kept arc from ~1.2 + blend
    // round to ~0.4 - blend, every old sample on the replaced arc gone
    const auto& r = o->raw.samples;
    ASSERT_GT(r.size(), fresh.samples.size());
    EXPECT_TRUE(same(r.front(), backwards ? fresh.samples.back() : fresh.samples.front()));
    const std::size_t kept = r.size() - fresh.samples.size();
    EXPECT_GT(kept, 157u * 3 / 4) << "the longer arc stays";
    for (std::size_t i = fresh.samples.size(); i < r.size(); ++i) {
      double a = std::atan2(r[i].p.y(), r[i].p.x());
      if (a < 0) a += 2 * std::numbers::pi;
      EXPECT_FALSE(a > 0.4 && a < 1.2) << "an old sample on the replaced arc, at angle " << a;
      if (i + 1 < r.size()) {
        double b = std::atan2(r[i + 1].p.y(), r[i + 1].p.x());
        if (b < 0) b += 2 * std::numbers::pi;
        EXPECT_TRUE(b > a || a - b > std::numbers::pi) << "the kept arc runs counter-clockwise";
      }
    }
  }
}

TEST_F(ClosedOversketch, OneJoinDoesNotOversketchALoop) {
  std::vector<Vec2> pts;
  for (int i = 0; i < 30; ++i) pts.emplace_back(102.0 + 4.0 * i, 3.0 * i);
  EXPECT_FALSE(oversketch(old, strokeOf(pts), kReach));
}

TEST(Oversketch, AStrokeAwayFromEveryStrokeIsNew) {
  Document d;
  d.addStroke(strokeOf(wavePoints()));
  d.addStroke(strokeOf(wavePoints(0, 400, 300)));
  EXPECT_FALSE(findOversketch(d, strokeOf(wavePoints(0, 400, 150)), kReach));
  // one starting on the second stroke's middle finds that one
  std::vector<Vec2> pts;
  for (double t = 0; t <= 80; t += 4) pts.emplace_back(200.0 + t, 60.0 * std::sin(200.0 / 90.0) + 300.0 + 2.0 + t);
  const auto target = findOversketch(d, strokeOf(pts), kReach);
  ASSERT_TRUE(target);
  EXPECT_EQ(target->stroke, 1u);
}

}  // namespace
}  // namespace la::gui
