// End-to-end tests of the lafit command-line tool (app/lafit): the real binary, built by
// CMake and passed in as LAFIT_PATH, is run through the shell in a fresh temporary
// folder per test, and its exit status, stdout, stderr and output files are checked
// against what the lafit issue asks and what `lafit fit --help` / `lafit batch --help`
// and app/lafit/commands.h promise:
//  - `lafit fit` on real strokes of the shared data ($1 gestures, a DejaVu glyph, an
//    airfoil, a KanjiVG SVG) and on strokes written here (CSV, stroke JSON): exit 0,
//    the JSON in the shared curve format (DESIGN.md section 5), the SVG, CSV and DXF,
//    and the printed quality table agreeing with the JSON;
//  - the JSON checked independently by ../shared/tools/lacheck.py, which rebuilds the
//    curves from their intrinsic segments: G1 and G2 gaps below the thresholds
//    (1e-9 rad, 1e-9 relative; DESIGN.md section 6) and the deviation within the
//    tolerance lafit reports;
//  - the SVG's cubic Bezier paths, on every shared airfoil and glyph, within the
//    tolerance the file states of the JSON's LA curves (both ways), that tolerance a
//    tenth of the fit's or less;
//  - --tolerance, --max-extrema, --g2 newton|bisection|off, --paper-only, --closed;
//  - a file of several strokes with a dot among them: one curve per stroke, in order,
//    an error entry for the dot;
//  - bad input (missing file, unparsable line, NaN, fewer than 2 distinct points): exit
//    1 and a message on stderr naming the file (and the line where there is one); points
//    all on one line, two distinct points among them, are one line;
//  - atomic writes: a failing run (unreadable input, or no stroke that can be fitted)
//    leaves existing output files byte for byte as they were, and no temporary file is
//    left behind, not even when the final rename fails;
//  - usage errors (exit 2) and --help naming every option;
//  - `lafit batch`: good files written, a bad one reported and skipped, exit 1.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/lafit/fit_options.h"
#include "app/lafit/outputs.h"
#include "core/curve_json.h"
#include "tests/shared_data_sets.h"
#include "tests/svg_bezier_paths.h"
#include "tests/test_support.h"

namespace la {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kLafit = LAFIT_PATH;
const fs::path kData = LAFAIR_SHARED_DATA_DIR;
const fs::path kLacheck = kData.parent_path() / "tools" / "lacheck.py";
const fs::path kPython = "/usr/bin/python3";  // lacheck.py's own #! line

// From the issue (the same thresholds as fit_data_test.cpp).
constexpr double kG1Threshold = 1e-9;  // radians
constexpr double kG2Threshold = 1e-9;  // relative curvature gap, DESIGN.md section 6 (issue 16: 1e-9)
// lacheck.py integrates positions numerically (2000 Gauss-Legendre panels per segment)
// and measures distances to the polyline of those positions: its figures carry that
// error, far below these allowances but not zero.
constexpr double kLacheckPositionGap = 1e-6;     // relative to the curve's diagonal
constexpr double kLacheckDeviationSlack = 1e-3;  // relative to lafit's tolerance

// Exit codes of app/lafit/commands.h.
constexpr int kExitInputError = 1;
constexpr int kExitUsage = 2;

// ------------------------------------------------------------------ running programs

struct Outcome {
  int status = -1;  // exit status; -1 if the program did not exit normally
  std::string out, err;
};

std::ostream& operator<<(std::ostream& os, const Outcome& outcome) {
  return os << "exit status " << outcome.status << "\n--- stdout:\n"
            << outcome.out << "--- stderr:\n"
            << outcome.err << "---";
}

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Every file and folder under `dir`, as paths relative to it.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    names.insert(fs::relative(entry.path(), dir).string());
  return names;
}

/// The curves of a lafit JSON document: {"curves": [...]} for several strokes, the
/// curve object itself for one.
json curvesOf(const json& document) {
  if (document.contains("curves")) return document.at("curves");
  return json::array({document});
}

/// Points of a stroke, written as CSV lines.
std::string csvOf(const std::vector<std::array<double, 2>>& points) {
  std::ostringstream out;
  out.precision(17);
  for (const auto& p : points) out << p[0] << "," << p[1] << "\n";
  return out.str();
}

/// A smooth open stroke with varying curvature and no inflection: an arc of the
/// ellipse x = a cos t, y = b sin t from t0 to t1, n points, shifted by (dx, dy).
std::vector<std::array<double, 2>> ellipseArc(double a, double b, double t0, double t1, int n, double dx = 0.0,
                                              double dy = 0.0) {
  std::vector<std::array<double, 2>> points;
  for (int i = 0; i < n; ++i) {
    const double t = t0 + (t1 - t0) * i / (n - 1);
    points.push_back({dx + a * std::cos(t), dy + b * std::sin(t)});
  }
  return points;
}

/// A fresh folder per test (kept when the test fails, so its files can be looked at),
/// and lafit run inside it.
class LafitCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_root =
        fs::temp_directory_path() / ("lafit_cli_test-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
    fs::remove_all(m_root);
    m_work = m_root / "work";
    fs::create_directories(m_work);
  }

  void TearDown() override {
    if (HasFailure()) {
      std::printf("files of this test kept in %s\n", m_work.c_str());
      return;
    }
    std::error_code ignored;
    fs::remove_all(m_root, ignored);
  }

  /// Runs argv[0] with the other arguments in the work folder; stdout and stderr are
  /// captured apart (stderr through a file outside the work folder, so listings of the
  /// work folder show only what the program wrote).
  Outcome run(const std::vector<std::string>& argv) const {
    const fs::path err_file = m_root / "stderr.txt";
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on " " + s.
    std::string command = "cd " + shellQuote(m_work.string()) + " &&";
    for (const std::string& a : argv) {
      command += ' ';
      command += shellQuote(a);
    }
    command += " 2>";
    command += shellQuote(err_file.string());
    command += " </dev/null";
    Outcome result;
    std::FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) {
      ADD_FAILURE() << "popen failed: " << command;
      return result;
    }
    std::array<char, 4096> buffer;
    std::size_t got = 0;
    while ((got = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.out.append(buffer.data(), got);
    const int status = ::pclose(pipe);
    result.status = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.err = slurp(err_file);
    fs::remove(err_file);
    return result;
  }

  Outcome lafit(std::vector<std::string> args) const {
    args.insert(args.begin(), kLafit.string());
    return run(args);
  }

  fs::path at(const std::string& name) const { return m_work / name; }

  void write(const std::string& name, const std::string& text) const {
    fs::create_directories(at(name).parent_path());
    std::ofstream(at(name), std::ios::binary) << text;
  }

  std::string read(const std::string& name) const { return slurp(at(name)); }

  json readJson(const std::string& name) const {
    const std::string text = read(name);
    json document = json::parse(text, nullptr, /*allow_exceptions=*/false);
    EXPECT_FALSE(document.is_discarded()) << name << " is not JSON:\n" << text.substr(0, 400);
    return document;
  }

  /// Copies a file of the shared data into the work folder under `name`.
  void copyData(const std::string& relative, const std::string& name) const {
    const fs::path source = kData / relative;
    ASSERT_TRUE(fs::exists(source)) << "shared data file missing: " << source;
    fs::create_directories(at(name).parent_path());
    fs::copy_file(source, at(name), fs::copy_options::overwrite_existing);
    fs::permissions(at(name), fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::add);
  }

  /// Runs lafit with `args` and expects exit `status` and every fragment in its stderr.
  void expectRefused(const std::vector<std::string>& args, int status, const std::vector<std::string>& fragments) const {
    const Outcome r = lafit(args);
    EXPECT_EQ(r.status, status) << r;
    for (const std::string& fragment : fragments) EXPECT_TRUE(contains(r.err, fragment)) << r;
  }

  /// Fits `file` with -o curve.json (`text` written to it first unless empty) and
  /// expects the input-error status and every fragment in the message.
  void expectInputError(const std::string& file, const std::string& text, const std::vector<std::string>& fragments) const {
    if (!text.empty()) write(file, text);
    expectRefused({"fit", file, "-o", "curve.json"}, kExitInputError, fragments);
  }

  fs::path m_root, m_work;
};

// The shared-data stroke most tests fit: a $1 left curly brace drawn slowly, two
// repetitions (two strokes, 68 and 76 points) with inflections, corners and curvature
// extrema; the clean-up keeps every point (no hook, no closing overlap), so lacheck.py
// measures the deviation of the same points lafit fitted.
constexpr const char* kBrace = "strokes/dollar1_unistroke_s01_pilot/csv/slow/left_curly_brace.csv";

/// Checks every curve of a document has segments in the shared format (DESIGN.md
/// section 5) and G1/G2 gaps in its quality below the thresholds. (Whether max_dev
/// meets the tolerance is the pipeline's business: fit_data_test.cpp, where it does not
/// yet on every shared stroke, e.g. the KanjiVG SVG of 04e59. Here it is checked only
/// for the brace, by the --tolerance test and independently by lacheck.py.)
void expectFittedCurves(const json& curves, std::size_t count) {
  ASSERT_TRUE(curves.is_array());
  ASSERT_EQ(curves.size(), count);
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const json& curve = curves[i];
    SCOPED_TRACE("curve " + std::to_string(i));
    ASSERT_FALSE(curve.contains("error")) << curve.at("error");
    ASSERT_TRUE(curve.contains("segments"));
    ASSERT_FALSE(curve.at("segments").empty());
    for (const char* key : {"alpha", "length", "start", "theta0", "kappa_start", "kappa_end"})
      EXPECT_TRUE(curve.at("segments")[0].contains(key)) << key;
    EXPECT_TRUE(curve.at("closed").is_boolean());
    const json& quality = curve.at("quality");
    EXPECT_LT(quality.at("g1_gap").get<double>(), kG1Threshold);
    EXPECT_LT(quality.at("g2_gap").get<double>(), kG2Threshold);
  }
}

// ------------------------------------------------------------------ fit: outputs

TEST_F(LafitCli, FitWritesJsonSvgCsvDxfAndPrintsTheQualityTable) {
  copyData(kBrace, "brace.csv");
  const Outcome r = lafit({"fit", "brace.csv", "--tolerance", "0.005", "--g2", "newton", "-o", "curve.json", "--svg",
                           "curve.svg", "--csv", "curve.csv", "--dxf", "curve.dxf"});
  ASSERT_EQ(r.status, 0) << r;

  const json curves = curvesOf(readJson("curve.json"));
  expectFittedCurves(curves, 2);
  for (const char* file : {"curve.json", "curve.svg", "curve.csv", "curve.dxf"})
    EXPECT_TRUE(contains(r.err, std::string("wrote ") + file)) << r;

  // The table: a header naming the figures, then one row per stroke whose segment count
  // and max_dev (printed with 4 significant digits) are the JSON's; indented lines
  // under a row are its warnings.
  std::istringstream table(r.out);
  std::string line;
  ASSERT_TRUE(std::getline(table, line)) << r;
  for (const char* column : {"stroke", "segs", "closed", "max_dev", "rms_dev", "g1_gap", "g2_gap", "extrema"})
    EXPECT_TRUE(contains(line, column)) << "header: " << line;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    do {
      ASSERT_TRUE(std::getline(table, line)) << r;
    } while (line.starts_with(" "));
    std::istringstream row(line);
    std::size_t stroke = 0;
    int segments = 0;
    std::string closed;
    double max_dev = 0.0;
    ASSERT_TRUE(row >> stroke >> segments >> closed >> max_dev) << "row: " << line;
    EXPECT_EQ(stroke, i + 1);
    EXPECT_EQ(segments, static_cast<int>(curves[i].at("segments").size()));
    const double json_dev = curves[i].at("quality").at("max_dev").get<double>();
    EXPECT_NEAR(max_dev, json_dev, 1e-3 * json_dev) << "row: " << line;
  }

  // SVG: a document with the curves as path data of cubic Beziers.
  const std::string svg = read("curve.svg");
  EXPECT_TRUE(contains(svg, "<svg")) << svg.substr(0, 300);
  EXPECT_TRUE(contains(svg, "<path d=\"M")) << svg.substr(0, 300);
  EXPECT_TRUE(contains(svg, " C")) << svg.substr(0, 300);

  // DXF: one SPLINE entity per curve, and a complete file.
  const std::string dxf = read("curve.dxf");
  std::istringstream dxf_lines(dxf);
  int splines = 0;
  while (std::getline(dxf_lines, line)) splines += line == "SPLINE";
  EXPECT_EQ(splines, static_cast<int>(curves.size()));
  EXPECT_TRUE(contains(dxf, "EOF"));

  // CSV: header x,y,s,theta,kappa, then one block of rows per curve (a blank line
  // between); each row five finite numbers, s increasing, and the first row of each
  // block at the start of the curve's first segment.
  std::istringstream csv(read("curve.csv"));
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line, "x,y,s,theta,kappa");
  std::vector<std::vector<std::array<double, 5>>> blocks(1);
  while (std::getline(csv, line)) {
    if (line.empty()) {
      blocks.emplace_back();
      continue;
    }
    std::array<double, 5> v{};
    char comma = 0;
    std::istringstream row(line);
    row >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3] >> comma >> v[4];
    ASSERT_TRUE(row && row.peek() == std::char_traits<char>::eof()) << "CSV row: " << line;
    for (double x : v) ASSERT_TRUE(std::isfinite(x)) << "CSV row: " << line;
    blocks.back().push_back(v);
  }
  if (blocks.back().empty()) blocks.pop_back();
  ASSERT_EQ(blocks.size(), curves.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    ASSERT_GE(blocks[i].size(), 2u);
    for (std::size_t k = 1; k < blocks[i].size(); ++k) EXPECT_GE(blocks[i][k][2], blocks[i][k - 1][2]) << "row " << k;
    const json& start = curves[i].at("segments")[0].at("start");
    const double diagonal = curves[i].at("quality").at("diagonal").get<double>();
    EXPECT_NEAR(blocks[i][0][0], start[0].get<double>(), 1e-6 * diagonal);
    EXPECT_NEAR(blocks[i][0][1], start[1].get<double>(), 1e-6 * diagonal);
  }
}

TEST_F(LafitCli, IndependentCheckerFindsTheFitG2AndAsCloseAsLafitSays) {
  ASSERT_TRUE(fs::exists(kPython) && fs::exists(kLacheck)) << "no " << kPython << " or " << kLacheck << " (scripts/setup.sh installs python3-numpy)";
  ASSERT_EQ(run({kPython.string(), "-c", "import numpy"}).status, 0) << "python3 has no numpy";
  copyData(kBrace, "brace.csv");
  const Outcome r = lafit({"fit", "brace.csv", "--stages", "-o", "curve.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json curves = curvesOf(readJson("curve.json"));
  expectFittedCurves(curves, 2);
  // lafit's max_dev is over the points its clean-up kept, lacheck's over the file's
  // (less 5% at each end of an open stroke): the comparison holds only if the clean-up
  // dropped none (no hook trimmed, no closing overlap cut).
  const std::vector<std::size_t> raw_counts = {68, 76};
  for (std::size_t i = 0; i < curves.size(); ++i)
    ASSERT_EQ(curves[i].at("stages").at("cleaned").at("points").size(), raw_counts[i])
        << "curve " << i << ": the clean-up dropped points; choose another stroke";

  const Outcome check = run({kPython.string(), kLacheck.string(), "curve.json", "brace.csv", "--json"});
  ASSERT_EQ(check.status, 0) << check;
  const json results = json::parse(check.out, nullptr, false);
  ASSERT_TRUE(results.is_array() && results.size() == curves.size()) << check;
  for (std::size_t i = 0; i < results.size(); ++i) {
    SCOPED_TRACE("curve " + std::to_string(i) + ": " + results[i].dump());
    const json& c = results[i];
    ASSERT_FALSE(c.contains("error"));
    EXPECT_LT(c.at("g1_gap").get<double>(), kG1Threshold);
    EXPECT_LT(c.at("g2_gap").get<double>(), kG2Threshold);
    EXPECT_LT(c.at("pos_gap").get<double>(), kLacheckPositionGap);
    // lacheck's deviation is relative to the rebuilt curve's diagonal and measured on
    // the interior points (it trims 5% at each end of an open stroke): at most lafit's
    // own figure, which is at most the tolerance or comes with a warning saying so.
    const double deviation = c.at("max_dev").get<double>() * c.at("diag").get<double>();
    const json& quality = curves[i].at("quality");
    const double max_dev = quality.at("max_dev").get<double>(), tolerance = quality.at("tolerance").get<double>();
    EXPECT_LE(deviation, max_dev * (1 + kLacheckDeviationSlack));
    if (max_dev > tolerance) {
      EXPECT_TRUE(curves[i].at("warnings").dump().find("misses the tolerance") != std::string::npos);
    }
    EXPECT_EQ(c.at("segments").get<std::size_t>(), curves[i].at("segments").size());
  }
}

// A closed stroke drawn past its start: the clean-up cuts the overlap. --stages lists
// what it kept (each kept point's raw sample in "source", the count cut), so lacheck
// can measure lafit's max_dev on the same points: within the tolerance, G2, closed.
TEST_F(LafitCli, StagesNameThePointsKeptSoTheCheckerMeasuresTheSame) {
  ASSERT_TRUE(fs::exists(kPython) && fs::exists(kLacheck)) << "no " << kPython << " or " << kLacheck << " (scripts/setup.sh installs python3-numpy)";
  ASSERT_EQ(run({kPython.string(), "-c", "import numpy"}).status, 0) << "python3 has no numpy";
  copyData("strokes/dollar1_unistroke_s01_pilot/csv/slow/circle.csv", "circle.csv");
  const Outcome r = lafit({"fit", "circle.csv", "--stages", "-o", "curve.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json curves = curvesOf(readJson("curve.json"));
  ASSERT_FALSE(curves.empty());
  std::size_t cut = 0;
  std::string csv;  // the kept points of every stroke, a blank line between strokes
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const json& cleaned = curves[i].at("stages").at("cleaned");
    const json& raw = curves[i].at("stages").at("raw");
    EXPECT_TRUE(curves[i].at("closed").get<bool>()) << "curve " << i;
    cut += cleaned.at("removed_overlap").get<std::size_t>();
    const json& kept = cleaned.at("points");
    const json& source = cleaned.at("source");
    ASSERT_EQ(source.size(), kept.size());
    if (i > 0) csv += "\n";
    for (std::size_t k = 0; k < kept.size(); ++k) {
      EXPECT_EQ(kept[k], raw[source[k].get<std::size_t>()]) << "curve " << i << ", kept point " << k;
      csv += std::to_string(kept[k][0].get<double>()) + "," + std::to_string(kept[k][1].get<double>()) + "\n";
    }
  }
  ASSERT_GT(cut, 0u) << "the circles should be drawn past their start";
  write("kept.csv", csv);
  const Outcome check = run({kPython.string(), kLacheck.string(), "curve.json", "kept.csv", "--json"});
  ASSERT_EQ(check.status, 0) << check;
  const json results = json::parse(check.out, nullptr, false);
  ASSERT_TRUE(results.is_array() && results.size() == curves.size()) << check;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const json& c = results[i];
    EXPECT_LT(c.at("g1_gap").get<double>(), kG1Threshold) << c;
    EXPECT_LT(c.at("g2_gap").get<double>(), kG2Threshold) << c;
    const double tolerance = curves[i].at("quality").at("tolerance").get<double>();
    EXPECT_LE(c.at("max_dev").get<double>() * c.at("diag").get<double>(), tolerance * (1 + kLacheckDeviationSlack)) << c;
  }
}

TEST_F(LafitCli, FitAppliesToleranceAndMaxExtrema) {
  copyData(kBrace, "brace.csv");
  // A coarse tolerance is the bound on the deviation, as a fraction of the diagonal
  // (0.02 lies above the noise floor of these 1-pixel points, so lafit keeps it as given;
  // the default 0.005 it raises: information in the figures, a star in the table, and
  // no warning).
  Outcome r = lafit({"fit", "brace.csv", "--tolerance", "0.02", "-o", "coarse.json"});
  ASSERT_EQ(r.status, 0) << r;
  for (const json& curve : curvesOf(readJson("coarse.json"))) {
    const json& q = curve.at("quality");
    EXPECT_NEAR(q.at("tolerance").get<double>(), 0.02 * q.at("diagonal").get<double>(),
                1e-12 * q.at("diagonal").get<double>());
    EXPECT_EQ(q.at("tolerance_requested").get<double>(), q.at("tolerance").get<double>());
    EXPECT_LE(q.at("max_dev").get<double>(), q.at("tolerance").get<double>() * (1 + 1e-9));
  }
  const Outcome fine = lafit({"fit", "brace.csv", "-o", "fine.json"});
  ASSERT_EQ(fine.status, 0) << fine;
  EXPECT_FALSE(contains(fine.out, "warning")) << fine;
  EXPECT_TRUE(contains(fine.out, "* the tolerance asked for, raised to the noise floor")) << fine;
  for (const json& curve : curvesOf(readJson("fine.json"))) {
    const json& q = curve.at("quality");
    EXPECT_NEAR(q.at("tolerance_requested").get<double>(), 0.005 * q.at("diagonal").get<double>(),
                1e-12 * q.at("diagonal").get<double>());
    EXPECT_GT(q.at("tolerance").get<double>(), q.at("tolerance_requested").get<double>());
  }

  // --max-extrema caps the curvature extrema the segmentation keeps in each smooth part
  // of a stroke (between two corners): the splits of kind "extremum" in --stages, per
  // "part". Without the cap the brace keeps two in one part.
  const auto mostExtremaInAPart = [](const json& curve) {
    std::map<int, int> per_part;
    for (const json& split : curve.at("stages").at("splits"))
      per_part[split.at("part").get<int>()] += split.at("kind") == "extremum";
    int most = 0;
    for (const auto& [part, n] : per_part) most = std::max(most, n);
    return most;
  };
  r = lafit({"fit", "brace.csv", "--stages", "-o", "all.json"});
  ASSERT_EQ(r.status, 0) << r;
  r = lafit({"fit", "brace.csv", "--stages", "--max-extrema", "1", "-o", "capped.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json all = curvesOf(readJson("all.json")), capped = curvesOf(readJson("capped.json"));
  ASSERT_EQ(all.size(), capped.size());
  int uncapped_most = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    uncapped_most = std::max(uncapped_most, mostExtremaInAPart(all[i]));
    EXPECT_LE(mostExtremaInAPart(capped[i]), 1) << "curve " << i;
  }
  EXPECT_GT(uncapped_most, 1) << "the cap has nothing to cut: choose another stroke";
}

// ------------------------------------------------------------------ fit: methods and flags

// The limits' flags: over one, lafit refuses the file with the limit and its flag
// named (exit 1, nothing written); raised, it reads. --jobs does not change the curves.
TEST_F(LafitCli, LimitsAreNamedWithTheirFlagsAndJobsDoNotChangeTheCurves) {
  std::string d = "M 0 0";
  for (int i = 0; i < 200; ++i) d += i % 2 ? " C 0 50 100 -50 0 0" : " C 100 50 0 -50 100 0";
  write("zig.svg", "<svg>\n<path d='" + d + "'/>\n</svg>\n");
  Outcome refused = lafit({"fit", "zig.svg", "-o", "zig.json", "--max-svg-points", "20000"});
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find("zig.svg:2: <path> flattens to more than 20000 points"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--max-svg-points"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(m_work / "zig.json"));
  EXPECT_EQ(lafit({"fit", "zig.svg", "-o", "zig.json", "--max-svg-points", "0"}).status, 2);  // usage

  write("three.csv", csvOf(ellipseArc(40, 20, 0.2, 2.5, 60)) + "\n" + csvOf(ellipseArc(30, 50, -1.0, 1.5, 80, 5, 5)) +
                         "\n" + csvOf(ellipseArc(60, 25, 1.0, 4.0, 70, -3, 2)));
  EXPECT_EQ(lafit({"fit", "three.csv", "--max-points", "70"}).status, 1);
  ASSERT_EQ(lafit({"fit", "three.csv", "-o", "one.json", "--jobs", "1"}).status, 0);
  ASSERT_EQ(lafit({"fit", "three.csv", "-o", "two.json", "--jobs", "3"}).status, 0);
  auto withoutTimings = [&](const std::string& name) {
    json curves = curvesOf(json::parse(slurp(m_work / name)));
    for (json& c : curves) c.erase("timings_ms");
    return curves;
  };
  EXPECT_EQ(withoutTimings("one.json"), withoutTimings("two.json"));
}

TEST_F(LafitCli, FitWithG2BisectionIsG2) {
  copyData(kBrace, "brace.csv");
  const Outcome r = lafit({"fit", "brace.csv", "--g2", "bisection", "-o", "curve.json"});
  ASSERT_EQ(r.status, 0) << r;
  expectFittedCurves(curvesOf(readJson("curve.json")), 2);
}

TEST_F(LafitCli, FitWithG2OffIsStillG1) {
  copyData(kBrace, "brace.csv");
  const Outcome r = lafit({"fit", "brace.csv", "--g2", "off", "-o", "curve.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json curves = curvesOf(readJson("curve.json"));
  ASSERT_EQ(curves.size(), 2u);
  for (const json& curve : curves) {
    ASSERT_FALSE(curve.at("segments").empty());
    EXPECT_LT(curve.at("quality").at("g1_gap").get<double>(), kG1Threshold);
  }
}

TEST_F(LafitCli, FitPaperOnlyStopsAfterJointDeformation) {
  copyData(kBrace, "brace.csv");
  const Outcome r = lafit({"fit", "brace.csv", "--paper-only", "-o", "curve.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json curves = curvesOf(readJson("curve.json"));
  ASSERT_EQ(curves.size(), 2u);
  for (const json& curve : curves) {
    ASSERT_FALSE(curve.at("segments").empty());
    EXPECT_LT(curve.at("quality").at("g2_gap").get<double>(), kG2Threshold);
    // No stage 7: no time spent in it.
    EXPECT_EQ(curve.at("timings_ms").at("polish").get<double>(), 0.0);
  }
}

TEST_F(LafitCli, FitClosedMakesEveryGlyphContourClosed) {
  // DejaVu 'a': its CSV does not sample a contour's closing straight edge, so without
  // --closed one contour ends far from its start and stays open (fit_data_test.cpp).
  copyData("curves/glyphs_dejavusans/DejaVuSans_a.csv", "a.csv");
  Outcome r = lafit({"fit", "a.csv", "-o", "open.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json open = curvesOf(readJson("open.json"));
  ASSERT_GE(open.size(), 2u);
  EXPECT_TRUE(std::any_of(open.begin(), open.end(), [](const json& c) { return !c.at("closed").get<bool>(); }))
      << "every contour closes without --closed: the test shows nothing";

  r = lafit({"fit", "a.csv", "--closed", "-o", "closed.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json closed = curvesOf(readJson("closed.json"));
  expectFittedCurves(closed, open.size());
  for (std::size_t i = 0; i < closed.size(); ++i) EXPECT_TRUE(closed[i].at("closed").get<bool>()) << "contour " << i;
}

// The SVG draws each curve as cubic Beziers within the tolerance the file states, a
// tenth of the fit's or less so the export adds little to the fit's deviation. Checked
// on every shared airfoil and glyph, each path against its curve as the project's reader
// reads it from the JSON, both ways: points of the LA segments near the path, and points
// of the cubics near the LA curve (a cubic could bulge away between the LA samples).
// Both distances are to actual points of the other curve, so their refinement can only
// overstate them.
TEST_F(LafitCli, SvgBeziersStayWithinTheirStatedToleranceOfTheLaCurvesOnSharedProfilesAndGlyphs) {
  std::vector<fs::path> files = test::filesOf(kData / "curves/airfoils", ".dat");
  const std::vector<fs::path> glyphs = test::filesOf(kData / "curves/glyphs_dejavusans", ".csv");
  ASSERT_GE(files.size(), 4u) << "airfoils missing from " << kData;
  ASSERT_GE(glyphs.size(), 9u) << "glyphs missing from " << kData;
  files.insert(files.end(), glyphs.begin(), glyphs.end());

  auto check = [&](const fs::path& file) {  // a lambda, so that an ASSERT ends one file only
    const std::string name = file.stem().string();
    const Outcome r = lafit({"fit", file.string(), "-o", name + ".json", "--svg", name + ".svg"});
    ASSERT_EQ(r.status, 0) << r;
    const std::string svg = read(name + ".svg");
    // Without --y-up nothing is mirrored: the paths are in the JSON's coordinates.
    ASSERT_FALSE(contains(svg, "transform=")) << svg.substr(0, 600);
    const double tolerance = test::statedBezierTolerance(svg);
    ASSERT_GT(tolerance, 0.0) << "no stated tolerance:\n" << svg.substr(0, 600);
    double fit_tolerance = INFINITY;  // the smallest of the document's curves
    for (const json& curve : curvesOf(readJson(name + ".json")))
      if (curve.contains("quality"))
        fit_tolerance = std::min(fit_tolerance, curve.at("quality").at("tolerance").get<double>());
    EXPECT_LE(tolerance, 0.1 * fit_tolerance);

    std::vector<Curve> curves;
    for (const CurveOrError& entry : readCurvesFile(at(name + ".json")))
      if (entry.curve) curves.push_back(*entry.curve);
    const std::vector<std::vector<CubicBezier>> paths = test::curvePathsOf(svg);
    ASSERT_EQ(paths.size(), curves.size()) << "one path per fitted curve, in order";
    double worst = 0.0;  // the largest distance either way, in stated tolerances
    for (std::size_t i = 0; i < curves.size(); ++i) {
      ASSERT_FALSE(paths[i].empty()) << "path " << i << " unreadable";
      std::vector<LaSegment> segments;
      for (const CurvePiece& piece : curves[i].pieces) {
        segments.push_back(piece.segment);
        for (const Vec2& q : piece.segment.sample(200).point)
          worst = std::max(worst, test::distanceToBeziers(paths[i], q) / tolerance);
      }
      std::vector<Vec2> on_path;
      for (const CubicBezier& b : paths[i])
        for (int k = 0; k <= 32; ++k) on_path.push_back(b.point(k / 32.0));
      for (double d : test::distances(segments, on_path)) worst = std::max(worst, d / tolerance);
    }
    EXPECT_LE(worst, 1.0) << "paths and LA curves up to " << worst << " stated tolerances (" << tolerance << ") apart";
  };
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    check(file);
  }
}

// ------------------------------------------------------------------ fit: input formats

// The output names the options the curves were made with (the sketch file's reader and
// writer), the time budget and the cap among them.
TEST_F(LafitCli, FitWritesTheOptionsItUsed) {
  copyData("curves/airfoils/clark-y.dat", "clark-y.dat");
  const Outcome r = lafit({"fit", "clark-y.dat", "-o", "curve.json", "--time-budget", "500", "--max-extrema", "4"});
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_EQ(readJson("curve.json").at("format"), "lafair-curves/1");
  const json options = readJson("curve.json").at("options");
  EXPECT_EQ(options.at("time_budget_ms").get<double>(), 500.0);
  EXPECT_EQ(options.at("max_extrema").get<int>(), 4);
  EXPECT_EQ(options.at("polish").get<bool>(), true);
  EXPECT_EQ(lafit({"fit", "clark-y.dat", "--time-budget", "-3"}).status, kExitUsage);
}

TEST_F(LafitCli, FitReadsAnAirfoilDat) {
  copyData("curves/airfoils/clark-y.dat", "clark-y.dat");
  const Outcome r = lafit({"fit", "clark-y.dat", "-o", "curve.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json document = readJson("curve.json");
  // One profile: the document is the curve itself.
  EXPECT_FALSE(document.contains("curves"));
  expectFittedCurves(curvesOf(document), 1);
  // A closed profile with one corner, its trailing edge (where it starts); its nose round.
  EXPECT_TRUE(document.at("closed").get<bool>());
  int corners = 0;
  for (const json& segment : document.at("segments")) corners += segment.value("corner", false) ? 1 : 0;
  EXPECT_EQ(corners, 1);
  EXPECT_TRUE(document.at("segments").front().value("corner", false));
}

TEST_F(LafitCli, FitReadsAStrokeJsonFile) {
  json strokes = json::array();
  for (const auto& points : {ellipseArc(40, 20, 0.0, 2.0, 30), ellipseArc(30, 15, 3.0, 5.0, 25, 100.0)}) {
    json stroke;
    for (const auto& p : points) stroke["points"].push_back({p[0], p[1]});
    strokes.push_back(stroke);
  }
  write("strokes.json", json{{"strokes", strokes}}.dump());
  const Outcome r = lafit({"fit", "strokes.json", "-o", "curve.json"});
  ASSERT_EQ(r.status, 0) << r;
  expectFittedCurves(curvesOf(readJson("curve.json")), 2);
}

TEST_F(LafitCli, FitReadsAKanjiVgSvg) {
  copyData("curves/kanjivg/0306e.svg", "kanji.svg");
  const Outcome r = lafit({"fit", "kanji.svg", "-o", "curve.json"});
  ASSERT_EQ(r.status, 0) << r;
  const json curves = curvesOf(readJson("curve.json"));
  ASSERT_GE(curves.size(), 1u);
  expectFittedCurves(curves, curves.size());
}

TEST_F(LafitCli, FitOfSeveralStrokesGivesAnErrorEntryForADotAndFitsTheRestInOrder) {
  const auto first = ellipseArc(40, 20, 0.0, 2.0, 30);
  const auto last = ellipseArc(30, 15, 3.0, 5.0, 25, 200.0, 0.0);
  write("strokes.csv", csvOf(first) + "\n50,50\n\n" + csvOf(last));
  const Outcome r = lafit({"fit", "strokes.csv", "-o", "curve.json"});
  // A stroke that could not be fitted makes the exit status 1 (app/lafit/commands.h);
  // the others are still fitted and written.
  EXPECT_EQ(r.status, kExitInputError) << r;
  const json document = readJson("curve.json");
  ASSERT_TRUE(document.contains("curves")) << document.dump().substr(0, 300);
  const json& curves = document.at("curves");
  ASSERT_EQ(curves.size(), 3u);
  ASSERT_TRUE(curves[1].contains("error")) << curves[1].dump();
  const std::string why = curves[1].at("error");
  EXPECT_TRUE(contains(why, "strokes.csv") && contains(why, "stroke 2")) << why;
  EXPECT_TRUE(contains(r.err, why)) << r;
  // In input order: the first curve starts near the first stroke, the last near the last
  // (they are 200 units apart; the clean-up may trim a point or two at the ends).
  for (const auto& [index, stroke] : {std::pair{0, first}, std::pair{2, last}}) {
    ASSERT_TRUE(curves[index].contains("segments")) << curves[index].dump().substr(0, 300);
    const json& start = curves[index].at("segments")[0].at("start");
    EXPECT_LT(std::hypot(start[0].get<double>() - stroke[0][0], start[1].get<double>() - stroke[0][1]), 5.0)
        << "curve " << index;
  }
  EXPECT_TRUE(contains(r.out, "error:")) << r;
}

// ------------------------------------------------------------------ fit: bad input

TEST_F(LafitCli, MissingInputFileIsReportedByName) {
  expectInputError("nowhere.csv", "", {"cannot open nowhere.csv"});
  EXPECT_FALSE(fs::exists(at("curve.json")));
}

TEST_F(LafitCli, UnparsableLineIsReportedWithFileAndLineNumber) {
  expectInputError("bad.csv", "0,0\n1,0.5\n2,1.5\n3,x2\n4,3\n", {"bad.csv:4:", "x2"});
  EXPECT_FALSE(fs::exists(at("curve.json")));
}

TEST_F(LafitCli, NaNIsReportedWithFileAndLineNumber) {
  expectInputError("nan.csv", "0,0\n1,1\nnan,2\n3,1\n4,0\n", {"nan.csv:3:", "NaN"});
}

TEST_F(LafitCli, FewerThanTwoDistinctPointsIsReportedByFile) {
  expectInputError("few.csv", "1,1\n1,1\n1,1\n", {"few.csv", "fewer than 2 distinct"});
}

TEST_F(LafitCli, CollinearPointsAreOneLine) {
  // (two distinct points too: a short dash)
  const std::pair<std::string, double> lines[] = {{"0,0\n1,1\n2,2\n3,3\n4,4\n", 4.0 * std::sqrt(2.0)},
                                                   {"0,0\n0,0\n3,4\n3,4\n", 5.0}};
  for (const auto& [text, length] : lines) {
    write("line.csv", text);
    const Outcome r = lafit({"fit", "line.csv", "-o", "curve.json"});
    ASSERT_EQ(r.status, 0) << r;
    const json segments = readJson("curve.json").at("segments");
    ASSERT_EQ(segments.size(), 1u) << text;
    EXPECT_EQ(segments[0].at("alpha"), "inf");
    EXPECT_DOUBLE_EQ(segments[0].at("length").get<double>(), length);
    EXPECT_DOUBLE_EQ(segments[0].at("kappa_start").get<double>(), 0.0);
  }
}

TEST_F(LafitCli, FitReadsLoneCarriageReturnLineEnds) {
  // Classic Mac OS line ends: the file was one line of 60 numbers, refused.
  std::string text = csvOf(ellipseArc(40, 20, 0.0, 2.0, 30));
  std::replace(text.begin(), text.end(), '\n', '\r');
  write("mac.csv", text);
  const Outcome r = lafit({"fit", "mac.csv", "-o", "curve.json"});
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_TRUE(readJson("curve.json").contains("segments"));
}

TEST_F(LafitCli, DecimalCommasAreReportedWithFileAndLine) {
  // "x;y" with decimal commas read as x, y, t, pressure: exit 0 and a wrong curve.
  std::string text = "0,0;0,0\n";
  for (int i = 1; i < 20; ++i) text += std::to_string(i) + ",5;" + std::to_string(i * i % 7) + ",25\n";
  expectInputError("comma.csv", text, {"comma.csv:1:", "mixed separators"});
  EXPECT_FALSE(fs::exists(at("curve.json")));
}

TEST_F(LafitCli, JsonNumberOutOfRangeIsReportedWithFileAndLine) {
  // nlohmann's out_of_range error: "[json.exception.out_of_range.406] number overflow
  // parsing '1e400'", without the file.
  expectInputError("big.json", "{\"strokes\": [{\"points\": [[0, 0], [1, 2],\n  [1e400, 1], [3, 0]]}]}",
                   {"big.json:2:4:", "out of range", "1e400"});
  EXPECT_FALSE(fs::exists(at("curve.json")));
}

TEST_F(LafitCli, SvgCoordinatesOverflowingAreReportedWithFileAndLine) {
  // Relative steps past the largest double: the points went to infinity and the fit
  // reported "fewer than 3 distinct finite points (1 samples ...)".
  expectInputError("far.svg", "<svg>\n<path d='M1.7e308 0 l 1.7e308 0 l 0 5 l 3 3'/>\n</svg>\n",
                   {"far.svg:2:", "coordinate out of range"});
  EXPECT_FALSE(fs::exists(at("curve.json")));
}

// ------------------------------------------------------------------ fit: atomic writes

TEST_F(LafitCli, UnreadableInputLeavesExistingOutputsUntouched) {
  write("bad.csv", "0,0\n1,0.5\nnot a number\n");
  const std::vector<std::string> outputs = {"out.json", "out.svg", "out.csv", "out.dxf"};
  for (const std::string& name : outputs) write(name, "previous " + name + "\n");
  const std::set<std::string> before = listing(m_work);
  const Outcome r =
      lafit({"fit", "bad.csv", "-o", "out.json", "--svg", "out.svg", "--csv", "out.csv", "--dxf", "out.dxf"});
  EXPECT_EQ(r.status, kExitInputError) << r;
  for (const std::string& name : outputs) EXPECT_EQ(read(name), "previous " + name + "\n") << name;
  EXPECT_EQ(listing(m_work), before);
}

TEST_F(LafitCli, StrokeThatCannotBeFittedLeavesAnExistingOutputUntouched) {
  // The whole file is one unfittable stroke: nothing to write, and a good curve from an
  // earlier run must not be replaced by an error entry.
  write("dot.csv", "1,1\n1,1\n1,1\n");  // one distinct point
  write("out.json", "previous\n");
  const Outcome r = lafit({"fit", "dot.csv", "-o", "out.json", "--svg", "out.svg"});
  EXPECT_EQ(r.status, kExitInputError) << r;
  EXPECT_TRUE(contains(r.err, "no output written")) << r;
  EXPECT_EQ(read("out.json"), "previous\n");
  EXPECT_FALSE(fs::exists(at("out.svg")));
  EXPECT_EQ(listing(m_work), (std::set<std::string>{"dot.csv", "out.json"}));
}

TEST_F(LafitCli, FailedWriteLeavesNoTemporaryFile) {
  // -o names a folder: the temporary file is written beside it, the rename over the
  // folder fails, and the temporary must go.
  copyData(kBrace, "brace.csv");
  fs::create_directory(at("taken"));
  const Outcome r = lafit({"fit", "brace.csv", "-o", "taken"});
  EXPECT_EQ(r.status, kExitInputError) << r;
  EXPECT_TRUE(contains(r.err, "cannot write taken")) << r;
  EXPECT_EQ(listing(m_work), (std::set<std::string>{"brace.csv", "taken"}));
}

TEST_F(LafitCli, SuccessfulRunLeavesOnlyItsOutputs) {
  copyData(kBrace, "brace.csv");
  write("out.json", "previous\n");
  const Outcome r =
      lafit({"fit", "brace.csv", "-o", "out.json", "--svg", "out.svg", "--csv", "out.csv", "--dxf", "out.dxf"});
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_NE(read("out.json"), "previous\n");
  EXPECT_EQ(listing(m_work), (std::set<std::string>{"brace.csv", "out.json", "out.svg", "out.csv", "out.dxf"}));
}

// ------------------------------------------------------------------ usage

TEST_F(LafitCli, UnknownOptionIsAUsageError) {
  copyData(kBrace, "brace.csv");
  expectRefused({"fit", "brace.csv", "--frobnicate"}, kExitUsage, {"unknown option --frobnicate", "lafit fit --help"});
}

TEST_F(LafitCli, BadG2MethodIsAUsageError) {
  copyData(kBrace, "brace.csv");
  expectRefused({"fit", "brace.csv", "--g2", "sideways"}, kExitUsage, {"--g2", "sideways"});
}

TEST_F(LafitCli, ClosedWithNoCloseIsAUsageError) {
  copyData(kBrace, "brace.csv");
  expectRefused({"fit", "brace.csv", "--closed", "--no-close"}, kExitUsage, {"--closed", "--no-close"});
}

// ------------------------------------------------------------------ help

/// Checks a help text names every option: the list and every option the
/// command's parser accepts (so a new option without help fails here).
void expectHelpNames(const std::string& help, std::set<std::string> options) {
  for (const std::string& option : options) EXPECT_TRUE(contains(help, option)) << "not in the help: " << option;
}

TEST_F(LafitCli, FitHelpExplainsEveryOption) {
  const Outcome r = lafit({"fit", "--help"});
  ASSERT_EQ(r.status, 0) << r;
  expectHelpNames(r.out, {"INPUT", "-o", "--svg", "--csv", "--dxf", "--tolerance", "--max-extrema", "--g2", "newton",
                          "bisection", "off", "--closed", "--no-close", "--paper-only", ".csv", ".txt", ".dat",
                          ".json", ".svg", "exit status"});
  for (const auto* set : {&cli::kOutputOptions, &cli::kOutputFlags, &cli::kFitValued, &cli::kFitFlags})
    expectHelpNames(r.out, *set);
}

TEST_F(LafitCli, BatchHelpExplainsEveryOption) {
  const Outcome r = lafit({"batch", "--help"});
  ASSERT_EQ(r.status, 0) << r;
  expectHelpNames(r.out, {"DIR", "-o", "OUTDIR", "--recursive", "--svg", "--jobs", "--tolerance", "--max-extrema",
                          "--g2", "--closed", "--no-close", "--paper-only", "exit status"});
  for (const auto* set : {&cli::kFitValued, &cli::kFitFlags}) expectHelpNames(r.out, *set);
}

TEST_F(LafitCli, TopLevelHelpListsFitAndBatch) {
  const Outcome r = lafit({"--help"});
  ASSERT_EQ(r.status, 0) << r;
  expectHelpNames(r.out, {"fit", "batch", "lafit COMMAND --help"});
}

// ------------------------------------------------------------------ batch

TEST_F(LafitCli, BatchFitsTheGoodFilesAndReportsTheBadOne) {
  copyData("strokes/dollar1_unistroke_s01_pilot/csv/medium/v.csv", "in/v.csv");
  copyData("curves/airfoils/clark-y.dat", "in/clark-y.dat");
  write("in/bad.csv", "0,0\n1,0.5\n2,1.5\n3,x2\n");
  const Outcome r = lafit({"batch", "in", "-o", "out", "--jobs", "2"});
  // `lafit batch --help`: exit status 1 when a file or stroke could not be fitted; the
  // rest are still written.
  EXPECT_EQ(r.status, kExitInputError) << r;
  EXPECT_EQ(listing(at("out")), (std::set<std::string>{"clark-y.json", "v.json"}));
  expectFittedCurves(curvesOf(readJson("out/v.json")), 2);
  expectFittedCurves(curvesOf(readJson("out/clark-y.json")), 1);
  // The summary table: a row per file, the bad one with its message (file and line),
  // and the count.
  bool bad_row = false;
  std::istringstream table(r.out);
  for (std::string line; std::getline(table, line);)
    bad_row |= line.starts_with("bad.csv") && contains(line, "error:") && contains(line, "bad.csv:4:");
  EXPECT_TRUE(bad_row) << r;
  EXPECT_TRUE(contains(r.out, "3 files: 2 fitted, 1 unreadable")) << r;
  EXPECT_TRUE(contains(r.err, "3/3")) << "no progress bar\n" << r;
}

// A file none of whose strokes can be fitted gets no output in a batch, as `lafit fit`
// writes none; the summary counts its strokes.
TEST_F(LafitCli, BatchWritesNothingForAFileWhoseStrokesAllFail) {
  copyData("strokes/dollar1_unistroke_s01_pilot/csv/medium/v.csv", "in/v.csv");
  write("in/dots.csv", "0,0\n0,0\n\n5,5\n5,5\n");  // two strokes of one distinct point each
  const Outcome r = lafit({"batch", "in", "-o", "out"});
  EXPECT_EQ(r.status, kExitInputError) << r;
  EXPECT_EQ(listing(at("out")), (std::set<std::string>{"v.json"}));
  EXPECT_TRUE(contains(r.out, "2 files: 1 fitted, 0 unreadable, 1 without a stroke that fits (not written)")) << r;
  EXPECT_TRUE(contains(r.out, "4 strokes: 2 fitted, 2 could not be fitted")) << r;
  const Outcome single = lafit({"fit", "in/dots.csv", "-o", "dots.json"});
  EXPECT_EQ(single.status, kExitInputError) << single;
  EXPECT_FALSE(fs::exists(at("dots.json")));
}

TEST_F(LafitCli, BatchOfGoodFilesExitsZero) {
  copyData("strokes/dollar1_unistroke_s01_pilot/csv/medium/v.csv", "in/v.csv");
  copyData("curves/airfoils/clark-y.dat", "in/sub/clark-y.dat");
  const Outcome r = lafit({"batch", "in", "-o", "out", "--recursive", "--svg"});
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_EQ(listing(at("out")),
            (std::set<std::string>{"v.json", "v.svg", "sub", "sub/clark-y.json", "sub/clark-y.svg"}));
  EXPECT_TRUE(contains(r.out, "2 files: 2 fitted, 0 unreadable")) << r;
}

// Inputs that differ only in their extension keep it in their outputs' names (one
// output each, none overwriting another); an OUTDIR inside DIR is not read back as
// input, the second run no more than the first; OUTDIR = DIR is a usage error.
TEST_F(LafitCli, BatchKeepsEveryOutputApartAndNeverReadsItsOwn) {
  copyData("strokes/dollar1_unistroke_s01_pilot/csv/medium/v.csv", "in/a.csv");
  copyData("strokes/dollar1_unistroke_s01_pilot/csv/slow/x.csv", "in/a.txt");
  copyData("curves/airfoils/clark-y.dat", "in/sub/b.dat");
  for (int run = 0; run < 2; ++run) {
    const Outcome r = lafit({"batch", "in", "-o", "in/out", "--recursive"});
    EXPECT_EQ(r.status, 0) << "run " << run << "\n" << r;
    EXPECT_TRUE(contains(r.out, "3 files: 3 fitted, 0 unreadable")) << "run " << run << "\n" << r;
  }
  EXPECT_EQ(listing(at("in/out")), (std::set<std::string>{"a.csv.json", "a.txt.json", "sub", "sub/b.json"}));
  expectFittedCurves(curvesOf(readJson("in/out/a.csv.json")), 2);
  expectFittedCurves(curvesOf(readJson("in/out/a.txt.json")), 2);
  const Outcome same = lafit({"batch", "in", "-o", "in"});
  EXPECT_EQ(same.status, kExitUsage) << same;
  EXPECT_TRUE(contains(same.err, "OUTDIR")) << same;
}

}  // namespace
}  // namespace la
