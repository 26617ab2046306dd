// Tests of core/curve_json.h: every kind of segment survives JSON bit for bit,
// documents with error entries round-trip, the independent checker
// (shared/tools/lacheck.py) reads our output and agrees that a G2 chain is G2, and
// every malformed input is rejected with a message that says where.

#include "core/curve_json.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/atomic_file.h"

namespace la {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string bitsOf(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g (0x%016llx)", x,
                static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(x)));
  return text;
}

// Bitwise equality (so -0.0 != 0.0), printing both values on failure.
::testing::AssertionResult sameBits(const char* field, double expected, double actual) {
  if (std::bit_cast<std::uint64_t>(expected) == std::bit_cast<std::uint64_t>(actual))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << field << ": wrote " << bitsOf(expected) << ", read " << bitsOf(actual);
}

void expectSameSegment(const LaSegment& expected, const LaSegment& actual,
                       const std::string& label) {
  SCOPED_TRACE(label);
  EXPECT_TRUE(sameBits("alpha", expected.alpha(), actual.alpha()));
  EXPECT_TRUE(sameBits("length", expected.length(), actual.length()));
  EXPECT_TRUE(sameBits("start.x", expected.start().x(), actual.start().x()));
  EXPECT_TRUE(sameBits("start.y", expected.start().y(), actual.start().y()));
  EXPECT_TRUE(sameBits("theta0", expected.theta0(), actual.theta0()));
  EXPECT_TRUE(sameBits("kappa_start", expected.kappaStart(), actual.kappaStart()));
  EXPECT_TRUE(sameBits("kappa_end", expected.kappaEnd(), actual.kappaEnd()));
}

void expectSameCurve(const Curve& expected, const Curve& actual, const std::string& label) {
  SCOPED_TRACE(label);
  EXPECT_EQ(expected.closed, actual.closed);
  ASSERT_EQ(expected.pieces.size(), actual.pieces.size());
  for (std::size_t i = 0; i < expected.pieces.size(); ++i) {
    EXPECT_EQ(expected.pieces[i].corner, actual.pieces[i].corner) << "piece " << i;
    expectSameSegment(expected.pieces[i].segment, actual.pieces[i].segment,
                      "piece " + std::to_string(i));
  }
}

struct NamedSegment {
  std::string label;
  LaSegment segment;
  bool corner = false;
};

// One segment of every kind the format must carry, with awkward numbers (thirds,
// tiny and huge magnitudes, negative zero) so that rounding would show.
std::vector<NamedSegment> everyKindOfSegment() {
  const Vec2 start(0.1, -1.0 / 3.0);
  return {
      {"alpha negative", LaSegment(-1.3, 2.0 / 3.0, start, 0.7, 0.7, 2.9)},
      {"alpha 0 (log rho linear)", LaSegment(0.0, 1.25, Vec2(1e-300, 1e300), -2.1, 1.0, 0.25)},
      {"alpha 1", LaSegment(1.0, 0.1, start, std::numbers::pi, 0.5, 1.5)},
      {"alpha 2 (clothoid), right turn", LaSegment(2.0, 3.0, start, -0.0, -0.3, -1.7)},
      {"alpha 3.7", LaSegment(3.7, 1e-3, Vec2(-0.0, 5e-324), 1e-17, 123.456, 7.0 / 9.0)},
      {"alpha inf: circle", LaSegment::arc(std::numbers::e, start, 0.5, 1.0 / 3.0)},
      {"alpha -inf: circle", LaSegment(-kInf, 0.5, start, 0.5, -2.0 / 7.0, -2.0 / 7.0)},
      {"alpha inf: line", LaSegment::arc(4.0, start, -1.0, 0.0)},
      {"inflection start", LaSegment(-0.5, 1.7, start, 0.3, 0.0, 1.1)},
      {"inflection end, right turn", LaSegment(-2.0, 0.9, start, 0.3, -2.0, -0.0)},
      {"corner", LaSegment(1.5, 0.75, start, 2.0, 0.2, 0.4), true},
  };
}

TEST(SegmentJson, EveryKindRoundTripsBitExactly) {
  for (const NamedSegment& item : everyKindOfSegment()) {
    const std::string text = segmentToJson(item.segment, item.corner).dump();
    const json read = json::parse(text);
    expectSameSegment(item.segment, segmentFromJson(read, "test"), item.label + ": " + text);
    EXPECT_EQ(read.value("corner", false), item.corner) << item.label;
    EXPECT_EQ(read.contains("corner"), item.corner) << "\"corner\" written only when set";
  }
}

TEST(SegmentJson, InfiniteAlphaIsAStringAndOtherFieldsAreNumbers) {
  const json circle = segmentToJson(LaSegment::arc(1.0, Vec2(2.0, 3.0), 0.5, 0.25));
  EXPECT_EQ(circle["alpha"], "inf");
  const json negative = segmentToJson(LaSegment(-kInf, 1.0, Vec2(0.0, 0.0), 0.0, 1.0, 1.0));
  EXPECT_EQ(negative["alpha"], "-inf");
  const json finite = segmentToJson(LaSegment(2.0, 1.0, Vec2(2.0, 3.0), 0.5, 1.0, 2.0));
  EXPECT_TRUE(finite["alpha"].is_number());
  EXPECT_EQ(finite["start"], json::array({2.0, 3.0}));
  for (const char* key : {"length", "theta0", "kappa_start", "kappa_end"})
    EXPECT_TRUE(finite[key].is_number()) << key;
  EXPECT_EQ(finite.size(), 6u) << finite.dump();
}

TEST(SegmentJson, IntegersAreAcceptedAsNumbers) {
  const json j = json::parse(
      R"({"alpha": 2, "length": 3, "start": [0, -1], "theta0": 0, "kappa_start": 1, "kappa_end": 2})");
  const LaSegment segment = segmentFromJson(j, "s");
  EXPECT_EQ(segment.alpha(), 2.0);
  EXPECT_EQ(segment.length(), 3.0);
  EXPECT_EQ(segment.start().y(), -1.0);
  EXPECT_EQ(segment.kappaEnd(), 2.0);
}

// nlohmann::json's own writer and reader must round-trip every finite double: this
// is what the bit-exact guarantee of the format rests on.
TEST(SegmentJson, EveryFiniteDoubleRoundTripsThroughText) {
  std::vector<double> values = {0.0, -0.0, 0.1, 1.0 / 3.0, std::numbers::pi,
                                std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::min(),
                                std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::lowest(),
                                std::numeric_limits<double>::epsilon(),
                                std::nextafter(1.0, 2.0), 9007199254740993.0, 1e23, 5e-324};
  std::mt19937_64 random_bits(20240611);  // fixed seed: the same 100000 patterns each run
  while (values.size() < 100000) {
    const double x = std::bit_cast<double>(random_bits());
    if (std::isfinite(x)) values.push_back(x);
  }
  std::uniform_real_distribution<double> unit(-10.0, 10.0);  // typical magnitudes too
  for (int i = 0; i < 20000; ++i) values.push_back(unit(random_bits));

  int failures = 0;
  for (const double x : values) {
    const std::string text = json(x).dump();
    const double back = json::parse(text).get<double>();
    if (std::bit_cast<std::uint64_t>(back) != std::bit_cast<std::uint64_t>(x) && failures++ < 5)
      ADD_FAILURE() << "wrote " << bitsOf(x) << " as " << text << ", read " << bitsOf(back);
  }
  EXPECT_EQ(failures, 0) << "of " << values.size() << " values";
}

// A G2 chain: A with kappa 1 -> 2 over length 0.5, B from A's end with A's end
// tangent and kappa 2 -> 0.5.
Curve g2Chain() {
  const LaSegment a(2.0, 0.5, Vec2(0.3, -0.2), 0.4, 1.0, 2.0);
  const LaSegment b(0.5, 0.8, a.end(), a.theta(a.length()), 2.0, 0.5);
  return {{{a, false}, {b, false}}, false};
}

// The same chain broken at the joint: B turned by 0.1 rad and starting at kappa 2.5.
Curve brokenChain() {
  const LaSegment a(2.0, 0.5, Vec2(0.3, -0.2), 0.4, 1.0, 2.0);
  const LaSegment b(0.5, 0.8, a.end(), a.theta(a.length()) + 0.1, 2.5, 0.5);
  return {{{a, false}, {b, false}}, false};
}

// A closed curve with a corner: three arcs meeting at corners.
Curve closedWithCorners() {
  Curve curve;
  curve.closed = true;
  Vec2 start(1.0, 0.0);
  double theta = std::numbers::pi / 2.0;
  for (int i = 0; i < 3; ++i) {
    const LaSegment arc = LaSegment::arc(1.5, start, theta, 0.4);
    curve.pieces.push_back({arc, true});
    start = arc.end();
    theta = arc.theta(arc.length()) + 2.0 * std::numbers::pi / 3.0;
  }
  return curve;
}

std::vector<CurveOrError> sampleDocument() {
  Curve mixed;
  for (const NamedSegment& item : everyKindOfSegment())
    mixed.pieces.push_back({item.segment, item.corner});
  return {{g2Chain(), ""},
          {std::nullopt, "stroke has 2 points; a curve needs at least 3"},
          {closedWithCorners(), ""},
          {mixed, ""}};
}

void expectSameDocument(const std::vector<CurveOrError>& expected,
                        const std::vector<CurveOrError>& actual) {
  ASSERT_EQ(expected.size(), actual.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(expected[i].curve.has_value(), actual[i].curve.has_value()) << "entry " << i;
    if (expected[i].curve)
      expectSameCurve(*expected[i].curve, *actual[i].curve, "entry " + std::to_string(i));
    else
      EXPECT_EQ(expected[i].error, actual[i].error) << "entry " << i;
  }
}

// A fresh directory per test, removed afterwards.
class CurveFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() /
            ("curve_json_test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override {
    std::error_code ignored;  // best effort: a leftover directory in /tmp is harmless
    fs::remove_all(m_dir, ignored);
  }
  fs::path m_dir;
};

TEST(CurvesDocument, WithErrorEntryRoundTrips) {
  const std::vector<CurveOrError> document = sampleDocument();
  const std::string text = curvesDocumentToString(document);
  const std::vector<CurveOrError> read = parseCurvesDocument(text, "memory");
  expectSameDocument(document, read);
  EXPECT_EQ(curvesDocumentToString(read), text) << "writing what was read changes nothing";
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(text.substr(0, 16), "{\n  \"curves\": [\n") << "indent 2";
  EXPECT_EQ(json::parse(text)["curves"][1], json({{"error", document[1].error}}));
}

TEST_F(CurveFileTest, WriteAndReadFile) {
  const fs::path path = m_dir / "curves.json";
  writeCurvesFile(path, sampleDocument());
  expectSameDocument(sampleDocument(), readCurvesFile(path));
}

TEST_F(CurveFileTest, ReadingAMissingFileSaysCannotOpen) {
  const fs::path path = m_dir / "missing.json";
  try {
    readCurvesFile(path);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("cannot open " + path.string() + ": ", 0), 0u)
        << e.what();
  }
}

TEST(CurvesDocument, SingleCurveFormsAndExtraKeysAreIgnored) {
  json single = curveToJson(closedWithCorners());
  single["metrics"] = {{"max_dev", 0.001}, {"extrema", 2}};
  single["samples"] = json::array({json::array({0.0, 1.0}), json::array({1.0, 2.0})});
  single["stages"] = {{"segmentation", {{"count", 3}}}};
  single["segments"][1]["note"] = "extra key on a segment";
  single["segments"][1]["kappa_samples"] = json::array({1, 2, 3});

  const auto read = parseCurvesDocument(single.dump(), "single");
  ASSERT_EQ(read.size(), 1u);
  ASSERT_TRUE(read[0].curve.has_value());
  expectSameCurve(closedWithCorners(), *read[0].curve, "{\"segments\": ...}");

  const json wrapped = {{"curve", single}, {"input", "stroke.csv"}};
  const auto read_wrapped = parseCurvesDocument(wrapped.dump(), "wrapped");
  ASSERT_EQ(read_wrapped.size(), 1u);
  ASSERT_TRUE(read_wrapped[0].curve.has_value());
  expectSameCurve(closedWithCorners(), *read_wrapped[0].curve, "{\"curve\": ...}");

  const auto open = parseCurvesDocument(R"({"segments": [{"alpha": "inf", "length": 1,
      "start": [0, 0], "theta0": 0, "kappa_start": 0, "kappa_end": 0}]})", "open");
  ASSERT_TRUE(open.at(0).curve.has_value());
  EXPECT_FALSE(open[0].curve->closed) << "\"closed\" defaults to false";
  EXPECT_FALSE(open[0].curve->pieces.at(0).corner);
}

// --- The independent checker ------------------------------------------------------

const std::string kPython = "/usr/bin/python3";
const std::string kChecker = LAFAIR_SOURCE_DIR "/../shared/tools/lacheck.py";

std::string shellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// Why lacheck.py cannot run here, or "" when it can.
std::string checkerUnavailable() {
  if (::access(kPython.c_str(), X_OK) != 0) return kPython + " not found";
  if (std::system((kPython + " -c 'import numpy' >/dev/null 2>&1").c_str()) != 0)
    return "numpy cannot be imported by " + kPython;
  if (!fs::exists(kChecker)) return kChecker + " not found";
  return "";
}

TEST_F(CurveFileTest, IndependentCheckerReadsOutputAndFindsG2Chain) {
  const std::string why = checkerUnavailable();
  ASSERT_TRUE(why.empty()) << why << " (scripts/setup.sh installs python3-numpy; ../shared holds the checker)";

  const std::vector<CurveOrError> document = {{g2Chain(), ""},
                                              {std::nullopt, "too few points"},
                                              {brokenChain(), ""},
                                              {closedWithCorners(), ""}};
  const fs::path curves = m_dir / "curves.json", out = m_dir / "out.json",
                 err = m_dir / "err.txt";
  writeCurvesFile(curves, document);
  const std::string command = kPython + " " + shellQuoted(kChecker) + " " +
                              shellQuoted(curves.string()) + " --json > " +
                              shellQuoted(out.string()) + " 2> " + shellQuoted(err.string());
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << command << "\nstatus " << status << "\n" << readFile(err);

  const json results = json::parse(readFile(out));
  ASSERT_TRUE(results.is_array() && results.size() == document.size()) << results.dump();

  // The G2 chain: gaps at the level of rounding. Thresholds: the checker's rebuild
  // (2000 panels of 8-point Gauss-Legendre) and ours (1e-10 relative) are both far
  // more accurate than 1e-9; theta and kappa come from closed forms on both sides.
  constexpr double kGapTolerance = 1e-9;
  const json& chain = results[0];
  EXPECT_EQ(chain["segments"], 2);
  EXPECT_EQ(chain["corners"], 0);
  EXPECT_LT(chain["pos_gap"].get<double>(), kGapTolerance) << chain.dump();
  EXPECT_LT(chain["g1_gap"].get<double>(), kGapTolerance) << chain.dump();
  EXPECT_LT(chain["g2_gap"].get<double>(), kGapTolerance) << chain.dump();

  EXPECT_EQ(results[1]["error"], "too few points") << results[1].dump();

  // The broken chain shows that the check can fail: 0.1 rad and (2.5 - 2) / 2.5.
  const json& broken = results[2];
  EXPECT_NEAR(broken["g1_gap"].get<double>(), 0.1, 1e-9) << broken.dump();
  EXPECT_NEAR(broken["g2_gap"].get<double>(), 0.2, 1e-9) << broken.dump();

  // Corners are counted and their joints skipped.
  EXPECT_EQ(results[3]["corners"], 3) << results[3].dump();
  EXPECT_EQ(results[3]["g1_gap"].get<double>(), 0.0) << results[3].dump();
}

// --- Malformed input --------------------------------------------------------------

// The message of the CurveFormatError that parsing `text` throws; fails if none.
std::string formatErrorOf(const std::string& text) {
  try {
    parseCurvesDocument(text, "bad.json");
  } catch (const CurveFormatError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected CurveFormatError, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected CurveFormatError for:\n" << text;
  return "";
}

constexpr const char* kGoodSegment =
    R"({"alpha": 2, "length": 1, "start": [0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": 2})";

// {"curves": [{"segments": [good, <second>]}]}: the problem is always in segments[1].
std::string documentWithSecondSegment(const std::string& second) {
  return std::string(R"({"curves": [{"segments": [)") + kGoodSegment + ", " + second + "]}]}";
}

struct MalformedCase {
  std::string label;
  std::string text;
  std::vector<std::string> message_contains;
};

TEST(CurvesDocument, MalformedInputNamesTheLocation) {
  const std::string segment_location = "bad.json: curves[0].segments[1]: ";
  const std::vector<MalformedCase> cases = {
      {"missing key",
       documentWithSecondSegment(
           R"({"alpha": 2, "length": 1, "start": [0, 0], "kappa_start": 1, "kappa_end": 2})"),
       {segment_location, "missing key \"theta0\""}},
      {"string where a number is expected",
       documentWithSecondSegment(
           R"({"alpha": 2, "length": "1.5", "start": [0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": 2})"),
       {segment_location, "\"length\" must be a number", "string"}},
      {"negative length",
       documentWithSecondSegment(
           R"({"alpha": 2, "length": -1, "start": [0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": 2})"),
       {segment_location, "length"}},
      {"opposite-sign curvatures",
       documentWithSecondSegment(
           R"({"alpha": 2, "length": 1, "start": [0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": -2})"),
       {segment_location, "opposite sign", "kappa_start"}},
      {"alpha as an unknown string",
       documentWithSecondSegment(
           R"({"alpha": "Infinity", "length": 1, "start": [0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": 1})"),
       {segment_location, "\"alpha\"", "Infinity"}},
      {"start with three coordinates",
       documentWithSecondSegment(
           R"({"alpha": 2, "length": 1, "start": [0, 0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": 2})"),
       {segment_location, "\"start\""}},
      {"zero end with alpha >= 0",
       documentWithSecondSegment(
           R"({"alpha": 2, "length": 1, "start": [0, 0], "theta0": 0, "kappa_start": 0, "kappa_end": 2})"),
       {segment_location, "alpha < 0"}},
      {"corner not a boolean",
       documentWithSecondSegment(
           R"({"alpha": 2, "length": 1, "start": [0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": 2, "corner": 1})"),
       {segment_location, "\"corner\""}},
      {"segment not an object", documentWithSecondSegment("[1, 2]"),
       {segment_location, "expected a segment object", "array"}},
      {"empty segments", R"({"curves": [{"segments": []}]})",
       {"bad.json: curves[0]: ", "empty"}},
      {"closed not a boolean", std::string(R"({"curves": [{"closed": "no", "segments": [)") +
                                   kGoodSegment + "]}]}",
       {"bad.json: curves[0]: ", "\"closed\""}},
      {"error entry not a string", R"({"curves": [{"error": 3}]})",
       {"bad.json: curves[0]: ", "\"error\" must be a string"}},
      {"curves not an array", R"({"curves": {"segments": []}})",
       {"bad.json: ", "\"curves\" must be an array"}},
      {"top level an array", "[1, 2]", {"bad.json: ", "array"}},
      {"neither curves nor segments", R"({"strokes": []})", {"bad.json: ", "\"curves\""}},
      {"single curve missing key",
       R"({"segments": [{"alpha": 2, "start": [0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": 2}]})",
       {"bad.json: segments[0]: missing key \"length\""}},
      {"number out of range",
       documentWithSecondSegment(
           R"({"alpha": 2, "length": 1e400, "start": [0, 0], "theta0": 0, "kappa_start": 1, "kappa_end": 2})"),
       {"bad.json: ", "1e400"}},
      {"truncated JSON on line 3", "{\n  \"curves\": [\n    {\"segments\": [{\"alpha\": 1,",
       // line 3 has 30 characters; the end of the input is just after them
       {"bad.json: line 3, column 31: ", "unexpected end of input"}},
      {"syntax error in the middle of line 2", "{\"curves\": [\n  {\"segments\": tru}\n]}",
       {"bad.json: line 2, column 19: ", "invalid literal"}},
  };
  for (const MalformedCase& item : cases) {
    const std::string message = formatErrorOf(item.text);
    for (const std::string& part : item.message_contains)
      EXPECT_NE(message.find(part), std::string::npos)
          << item.label << ": message \"" << message << "\" should contain \"" << part << "\"";
  }
}

TEST(SegmentJson, ErrorMessageStartsWithTheGivenLocation) {
  const json missing = json::parse(R"({"alpha": 2, "length": 1, "start": [0, 0], "theta0": 0})");
  try {
    segmentFromJson(missing, "curves[2].segments[5]");
    FAIL() << "expected CurveFormatError";
  } catch (const CurveFormatError& e) {
    EXPECT_EQ(std::string(e.what()), "curves[2].segments[5]: missing key \"kappa_start\"");
  }
}

}  // namespace
}  // namespace la

namespace la {
namespace {

// The format is versioned: a document names "lafair-curves/1"; one without the key (an
// older file, another tool's) reads as version 1; a later version, or another format,
// is refused with the versions named.
TEST(CurvesDocument, NamesItsFormatAndReadsDocumentsWithout) {
  const std::vector<CurveOrError> document = sampleDocument();
  json written = json::parse(curvesDocumentToString(document));
  EXPECT_EQ(written.at("format"), "lafair-curves/1");
  json unversioned = written;
  unversioned.erase("format");
  expectSameDocument(document, parseCurvesDocument(unversioned.dump(), "old.json"));

  auto errorOf = [](const json& doc) {
    try {
      parseCurvesDocument(doc.dump(), "v.json");
    } catch (const CurveFormatError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  json later = written;
  later["format"] = "lafair-curves/2";
  const std::string newer = errorOf(later);
  EXPECT_NE(newer.find("v.json"), std::string::npos) << newer;
  EXPECT_NE(newer.find("lafair-curves/2"), std::string::npos) << newer;
  EXPECT_NE(newer.find("lafair-curves/1"), std::string::npos) << newer;
  json other = written;
  other["format"] = "lafair-sketch";
  EXPECT_NE(errorOf(other).find("lafair-sketch"), std::string::npos);
  json number = written;
  number["format"] = 1;
  EXPECT_NE(errorOf(number).find("\"format\" must be a string"), std::string::npos);
}

}  // namespace
}  // namespace la
