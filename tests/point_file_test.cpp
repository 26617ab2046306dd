// Tests of app/io/point_file.h: every format parsed from strings (comments, headers,
// stroke breaks, time and pressure kept, every separator); every malformed input
// rejected with the file name and the right line; the shared real files (DESIGN data:
// $1, MMG and Omniglot strokes, airfoils, KanjiVG, DejaVu glyphs) read with the right
// stroke and point counts; SVG flattening checked against closed forms (circles and
// ellipses from arcs), against the explicit forms of shorthand and relative commands,
// and against independent dense samples of the same Beziers.

#include "app/io/point_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace la {
namespace {

namespace fs = std::filesystem;

const fs::path kData = LAFAIR_SHARED_DATA_DIR;

/// Spacing bound of the SVG flattening (point_file.cpp kMaxSpacingFraction), with 2%
/// slack because the spacing is set from a chord-length estimate of arc length.
constexpr double kSpacingFraction = 0.005 * 1.02;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The message of the PointFileError `parse` throws, or a note that none came.
std::string errorOf(const std::function<void()>& parse) {
  try {
    parse();
  } catch (const PointFileError& e) {
    return e.what();
  }
  return "(no PointFileError thrown)";
}

void expectError(const std::string& text, const std::string& name, std::initializer_list<std::string> parts,
                 const ReadLimits& limits = {}) {
  const std::string message = errorOf([&] { parseStrokes(text, name, limits); });
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "message: " << message << "\nexpected to contain: " << part
                                                     << "\ninput:\n" << text;
}

std::vector<Vec2> pointsOf(const Stroke& stroke) {
  std::vector<Vec2> points;
  for (const StrokeSample& s : stroke.samples) points.push_back(s.p);
  return points;
}

double distanceToSegment(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double u = length2 > 0.0 ? std::clamp((q - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (q - (a + u * ab)).norm();
}

double distanceToPolyline(const Vec2& q, const std::vector<Vec2>& line) {
  if (line.size() == 1) return (q - line[0]).norm();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < line.size(); ++i) best = std::min(best, distanceToSegment(q, line[i], line[i + 1]));
  return best;
}

double distanceToPoints(const Vec2& q, const std::vector<Vec2>& points) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec2& p : points) best = std::min(best, (q - p).norm());
  return best;
}

double diagonalOf(const std::vector<Vec2>& points) {
  Vec2 lo = points.front(), hi = points.front();
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

double largestStep(const std::vector<Vec2>& points) {
  double step = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) step = std::max(step, (points[i] - points[i - 1]).norm());
  return step;
}

std::vector<Stroke> svg(const std::string& body) { return parseStrokes("<svg>" + body + "</svg>", "test.svg"); }

/// Both path data flatten to the same points (to rounding).
void expectSamePath(const std::string& d, const std::string& reference) {
  SCOPED_TRACE("d=\"" + d + "\" vs \"" + reference + "\"");
  const std::vector<Stroke> a = svg("<path d=\"" + d + "\"/>");
  const std::vector<Stroke> b = svg("<path d=\"" + reference + "\"/>");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].samples.size(), b[i].samples.size()) << "stroke " << i;
    for (std::size_t j = 0; j < a[i].samples.size(); ++j)
      EXPECT_LE((a[i].samples[j].p - b[i].samples[j].p).norm(), 1e-12)
          << "stroke " << i << " point " << j << ": " << a[i].samples[j].p.transpose() << " vs "
          << b[i].samples[j].p.transpose();
  }
}

// ------------------------------------------------------------------ CSV / TXT

TEST(PointFileCsv, CommentsHeaderBlankLinesTimeAndPressure) {
  const std::string text =
      "# recorded by hand\n"
      "x,y,t,pressure\n"
      "1,2,3,0.5\n"
      "# a comment inside a stroke does not break it\n"
      "4 5 6 0.25\n"
      "\n"
      "   \n"
      "\n"
      "7;8\n"
      "9\t10\t11\n"
      "\n";
  const std::vector<Stroke> strokes = parseStrokes(text, "pen.csv");
  ASSERT_EQ(strokes.size(), 2u);
  ASSERT_EQ(strokes[0].samples.size(), 2u);
  ASSERT_EQ(strokes[1].samples.size(), 2u);
  EXPECT_EQ(strokes[0].samples[0].p, Vec2(1, 2));
  EXPECT_EQ(strokes[0].samples[0].t, 3.0);
  EXPECT_EQ(strokes[0].samples[0].pressure, 0.5);
  EXPECT_EQ(strokes[0].samples[1].p, Vec2(4, 5));
  EXPECT_EQ(strokes[0].samples[1].t, 6.0);
  EXPECT_EQ(strokes[0].samples[1].pressure, 0.25);
  EXPECT_EQ(strokes[1].samples[0].p, Vec2(7, 8));
  EXPECT_TRUE(std::isnan(strokes[1].samples[0].t));
  EXPECT_TRUE(std::isnan(strokes[1].samples[0].pressure));
  EXPECT_EQ(strokes[1].samples[1].p, Vec2(9, 10));
  EXPECT_EQ(strokes[1].samples[1].t, 11.0);
  EXPECT_TRUE(std::isnan(strokes[1].samples[1].pressure));
}

TEST(PointFileCsv, EverySeparatorAndNumberForm) {
  const std::string text =
      "\xEF\xBB\xBF"  // UTF-8 byte order mark
      "1,2\r\n"
      "  3 , 4  \r\n"
      "5 ;\t6\n"
      "+7.5e1\t\t-8E-1\n"
      ".5 -.25 # trailing comment\n"
      "1e3,2";  // no final newline
  const std::vector<Stroke> strokes = parseStrokes(text, "mixed.txt");
  ASSERT_EQ(strokes.size(), 1u);
  const std::vector<Vec2> expected{{1, 2}, {3, 4}, {5, 6}, {75, -0.8}, {0.5, -0.25}, {1000, 2}};
  ASSERT_EQ(strokes[0].samples.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(strokes[0].samples[i].p, expected[i]) << i;
}

TEST(PointFileCsv, KnownHeaderNamesPickTheColumns) {
  const std::vector<Stroke> strokes = parseStrokes("Y,pressure,X\n2,0.5,1\n4,0.75,3\n", "named.csv");
  ASSERT_EQ(strokes.size(), 1u);
  ASSERT_EQ(strokes[0].samples.size(), 2u);
  EXPECT_EQ(strokes[0].samples[1].p, Vec2(3, 4));
  EXPECT_EQ(strokes[0].samples[1].pressure, 0.75);
  EXPECT_TRUE(std::isnan(strokes[0].samples[1].t));
  // An unknown header is only skipped: columns stay positional.
  const std::vector<Stroke> positional = parseStrokes("a b c\n1 2 3\n", "plain.csv");
  EXPECT_EQ(positional[0].samples[0].p, Vec2(1, 2));
  EXPECT_EQ(positional[0].samples[0].t, 3.0);
}

TEST(PointFileCsv, OmniglotStartAndBreakLines) {
  const std::vector<Stroke> strokes = parseStrokes("START\n1,2,0\n3,4,10\nBREAK\n5,6,20\n6,7,30\nBREAK\n", "o.txt");
  ASSERT_EQ(strokes.size(), 2u);
  EXPECT_EQ(strokes[1].samples[0].p, Vec2(5, 6));
  EXPECT_EQ(strokes[1].samples[0].t, 20.0);
}

TEST(PointFileCsv, ErrorsNameFileAndLine) {
  expectError("x,y\n1,2\n3,abc\n", "a.csv", {"a.csv:3:", "non-numeric", "abc"});
  expectError("1,2\n\n3\n", "b.csv", {"b.csv:3:", "expected 2 to 4 numbers", "found 1"});
  expectError("1 2 3 4 5\n", "c.txt", {"c.txt:1:", "expected 2 to 4 numbers", "found 5"});
  expectError("# c\n1,2\nnan,3\n", "d.csv", {"d.csv:3:", "NaN coordinate"});
  expectError("1,2\n3,-inf\n", "e.csv", {"e.csv:2:", "infinite coordinate"});
  expectError("1,2,nan\n", "e2.csv", {"e2.csv:1:", "time stamp"});
  expectError("1,,2\n", "f.csv", {"f.csv:1:", "empty field"});
  expectError("1,2,\n", "g.csv", {"g.csv:1:", "empty field"});
  expectError("1,2\n3,4\nx,y\n", "h.csv", {"h.csv:3:", "non-numeric"});  // a header only comes first
  expectError("x,y,t\n1,2,3\n1,2,3,4\n", "i.csv", {"i.csv:3:", "header"});
  expectError("t,x,y\n1,2,3\n1,2\n", "j.csv", {"j.csv:3:", "header"});  // no y
  expectError("", "empty.csv", {"empty.csv: no points"});
  expectError("# only a comment\nx,y\n\n", "nothing.csv", {"nothing.csv: no points"});
}

TEST(PointFileCsv, MissingFileSaysCannotOpen) {
  const fs::path missing = fs::temp_directory_path() / "lafair-no-such-dir" / "strokes.csv";
  const std::string message = errorOf([&] { readStrokes(missing); });
  EXPECT_NE(message.find("cannot open " + missing.string() + ": "), std::string::npos) << message;
  EXPECT_NE(message.find("No such file"), std::string::npos) << message;
  const std::string directory = errorOf([&] { readStrokes(fs::temp_directory_path()); });
  EXPECT_NE(directory.find("cannot open"), std::string::npos) << directory;
}

TEST(PointFileCsv, LoneCarriageReturnsEndLines) {
  // Classic Mac OS line ends: read as one line, the points ran together into a row of
  // numbers (two points became one with a time stamp and a pressure).
  const std::vector<Stroke> strokes = parseStrokes("0,0\r1,1\r\r2,0\r3,1\r", "mac.csv");
  ASSERT_EQ(strokes.size(), 2u);
  ASSERT_EQ(strokes[0].samples.size(), 2u);
  EXPECT_EQ(strokes[0].samples[1].p, Vec2(1, 1));
  EXPECT_TRUE(std::isnan(strokes[0].samples[0].t));
  EXPECT_EQ(strokes[1].samples.size(), 2u);
  // Mixed line ends in one file, and line numbers counted across them.
  EXPECT_EQ(parseStrokes("0,0\r\n1,1\r2,0\n3,1\r\n", "mixed.csv")[0].samples.size(), 4u);
  expectError("0,0\r1,1\r\n2,x\n", "bad.csv", {"bad.csv:3:", "non-numeric", "x"});
}

TEST(PointFileCsv, DecimalCommasAreRefusedNotReadAsFourColumns) {
  // "1,5;2,5" is (1.5, 2.5) with decimal commas; read field by field it was x=1, y=5,
  // t=2, pressure=5: a wrong curve without a word.
  expectError("1,5;2,5\n", "semi.csv", {"semi.csv:1:", "mixed separators", "decimal commas"});
  expectError("0.5 1\n1,5 2,5\n", "space.txt", {"space.txt:2:", "mixed separators"});
  expectError("1,5\t2,5\n", "tab.txt", {"tab.txt:1:", "mixed separators"});
  // One kind of separator per line is fine, with blanks around it.
  EXPECT_EQ(parseStrokes("1 , 2 , 3\n4;5; 6\n", "ok.csv")[0].samples[1].t, 6.0);
}

TEST(PointFileCsv, FirstLineMixingNumbersAndTextIsAnErrorNotAHeader) {
  // A damaged first point was skipped as a header, losing it unsaid.
  expectError("13.0x,0.5\n1,2\n3,4\n", "first.csv", {"first.csv:1:", "non-numeric", "13.0x"});
  expectError("\xEF\xBB\xBF\xEF\xBB\xBF" "1,2\n3,4\n", "bom2.csv", {"bom2.csv:1:", "non-numeric"});
  // A header of names still is one.
  EXPECT_EQ(parseStrokes("px,py\n1,2\n", "names.csv")[0].samples.size(), 1u);
}

TEST(PointFileCsv, HugeNumbersWithoutAnExponentAreInfiniteNotZero) {
  // 400 digits overflow a double like 1e400 does; they used to read as 0.
  expectError("1" + std::string(400, '0') + ",2\n3,4\n", "digits.csv", {"digits.csv:1:", "infinite coordinate"});
  expectError("0,0\n3,-" + std::string(400, '9') + ".5\n", "neg.csv", {"neg.csv:2:", "infinite coordinate"});
  // Too small still reads as 0, as strtod gives, however the digits are written.
  const std::vector<Stroke> tiny = parseStrokes("0." + std::string(400, '0') + "1,2\n0.01e-399,3\n", "tiny.csv");
  EXPECT_EQ(tiny[0].samples[0].p, Vec2(0, 2));
  EXPECT_EQ(tiny[0].samples[1].p, Vec2(0, 3));
  EXPECT_EQ(parseStrokes("1e-99999999999999999999,2\n", "e.csv")[0].samples[0].p, Vec2(0, 2));
  expectError("1e99999999999999999999,2\n", "e2.csv", {"e2.csv:1:", "infinite coordinate"});
}

TEST(PointFileCsv, QuotedInputHasNoControlCharacters) {
  // A NUL cut the message short where it stood; an ESC went to the terminal.
  const std::string nul = errorOf([] { parseStrokes(std::string("1,2\n3,4\0x\n", 10), "nul.csv"); });
  EXPECT_NE(nul.find("nul.csv:2: non-numeric field '4?x'"), std::string::npos) << nul;
  const std::string esc = errorOf([] { parseStrokes("1,2\n3,\x1b[31m\n", "esc.csv"); });
  EXPECT_NE(esc.find("esc.csv:2:"), std::string::npos) << esc;
  EXPECT_EQ(esc.find('\x1b'), std::string::npos) << esc;
  // An excerpt is not cut inside a UTF-8 character (24 bytes: the 'é' straddles it).
  const std::string utf8 = errorOf([] { parseStrokes("1,2\n3," + std::string(23, 'a') + "\xC3\xA9z\n", "u.csv"); });
  EXPECT_NE(utf8.find(std::string(23, 'a') + "...'"), std::string::npos) << utf8;
}

// ------------------------------------------------------------------ airfoil .dat

TEST(PointFileDat, SeligNameLineThenOneProfile) {
  const std::vector<Stroke> strokes = parseStrokes("NACA 0012\n1.0 0.00126\n\n0.5  0.05\n0.0 0.0\n0.5 -0.05\n", "foil.dat");
  ASSERT_EQ(strokes.size(), 1u);  // blank lines do not split a profile
  ASSERT_EQ(strokes[0].samples.size(), 4u);
  EXPECT_EQ(strokes[0].samples[3].p, Vec2(0.5, -0.05));
  EXPECT_TRUE(strokes[0].profile);  // (corners only at its trailing edge)
  EXPECT_FALSE(parseStrokes("1 0\n0 0.1\n0 0.2\n", "not_a_profile.csv")[0].profile);
  // Without a name line the numbers are points too.
  EXPECT_EQ(parseStrokes("1 0\n0 0.1\n", "bare.DAT")[0].samples.size(), 2u);
}

TEST(PointFileDat, Errors) {
  expectError("Foil\n1 0\n0.5 0.1 7\n", "x.dat", {"x.dat:3:", "expected 2 numbers"});
  expectError("Foil\n1 0\nzero 0\n", "y.dat", {"y.dat:3:", "non-numeric"});
  expectError("Foil (Lednicer)\n17. 17.\n\n0 0\n", "l.dat", {"l.dat:2:", "Lednicer"});
  expectError("Just a name\n", "n.dat", {"n.dat: no points"});
}

TEST(PointFileDat, LoneCarriageReturnsEndLines) {
  // Read as one line, the whole file was the name line: "no points".
  const std::vector<Stroke> strokes = parseStrokes("NACA 0012\r1 0\r0.5 0.1\r0 0\r0.5 -0.1\r", "mac.dat");
  ASSERT_EQ(strokes.size(), 1u);
  EXPECT_EQ(strokes[0].samples.size(), 4u);
}

// ------------------------------------------------------------------ JSON

TEST(PointFileJson, StrokesWithOptionalTimeAndPressure) {
  const std::string text = R"({"strokes": [
      {"points": [[0, 0], [1, 2.5]], "t": [0, 16], "pressure": [0.5, null]},
      {"points": [[3, 4], [5, 6], [7, 8]], "id": "ignored", "profile": true},
      {"points": []}
    ]})";
  const std::vector<Stroke> strokes = parseStrokes(text, "s.json");
  ASSERT_EQ(strokes.size(), 3u);  // the empty stroke keeps its place
  ASSERT_EQ(strokes[0].samples.size(), 2u);
  EXPECT_EQ(strokes[0].samples[1].p, Vec2(1, 2.5));
  EXPECT_EQ(strokes[0].samples[1].t, 16.0);
  EXPECT_EQ(strokes[0].samples[0].pressure, 0.5);
  EXPECT_TRUE(std::isnan(strokes[0].samples[1].pressure));
  ASSERT_EQ(strokes[1].samples.size(), 3u);
  EXPECT_TRUE(std::isnan(strokes[1].samples[2].t));
  EXPECT_FALSE(strokes[0].profile);
  EXPECT_TRUE(strokes[1].profile);
  EXPECT_TRUE(strokes[2].samples.empty());
}

TEST(PointFileJson, Errors) {
  // Syntax: line 3, column of the stray ']' (1-based).
  const std::string broken = "{\n \"strokes\": [\n  {\"points\": [[1, 2], [3, ]]}\n ]\n}";
  const std::size_t column = std::string("  {\"points\": [[1, 2], [3, ]]}").find(", ]") + 3;
  expectError(broken, "bad.json", {"bad.json:3:" + std::to_string(column) + ":", "JSON"});
  expectError("{\"strokes\": [{\"points\": [[1, 2]]}", "eof.json", {"eof.json:1:"});
  expectError("[]", "arr.json", {"arr.json:", "\"strokes\" array"});
  expectError(R"({"strokes": [{"points": [[1, 2]]}, {"pts": []}]})", "k.json", {"k.json:", "strokes[1].points"});
  expectError(R"({"strokes": [{"points": [[1, 2]]}, {"points": [[1, 2], [3]]}]})", "p.json",
              {"p.json:", "strokes[1].points[1]", "[x, y]"});
  expectError(R"({"strokes": [{"points": [[1, 2], [3, 4]], "t": [0]}]})", "t.json",
              {"t.json:", "strokes[0].t", "1 values for 2 points"});
  expectError(R"({"strokes": [{"points": [[1, 2]], "pressure": ["hard"]}]})", "pr.json",
              {"pr.json:", "strokes[0].pressure[0]"});
  expectError(R"({"strokes": [{"points": []}]})", "none.json", {"none.json: no points"});
  expectError(R"({"strokes": [{"points": [[1, 2]], "profile": "yes"}]})", "pf.json",
              {"pf.json:", "strokes[0].profile", "true or false"});
}

TEST(PointFileJson, NumberOutOfRangeNamesFileLineAndNumber) {
  // nlohmann throws out_of_range (not parse_error) for these: the message had neither
  // the file nor a position, and was no PointFileError.
  expectError("{\"strokes\": [{\"points\": [[0, 0],\n [1e400, 1]]}]}", "big.json",
              {"big.json:2:3:", "out of range", "1e400"});
  expectError("{\"strokes\": [{\"points\": [[1, 1], [0, 0]], \"t\": [1, -1e4000]}]}", "t.json",
              {"t.json:1:52:", "out of range", "-1e4000"});
}

// ------------------------------------------------------------------ SVG

TEST(PointFileSvg, PolylineKeepsItsVerticesAndSamplesItsEdges) {
  const std::vector<Stroke> strokes = svg("<polyline fill='none' points='0,0 10,0 10,10'/>");
  ASSERT_EQ(strokes.size(), 1u);
  const std::vector<Vec2> points = pointsOf(strokes[0]);
  const std::vector<Vec2> vertices{{0, 0}, {10, 0}, {10, 10}};
  EXPECT_EQ(points.front(), vertices.front());
  EXPECT_EQ(points.back(), vertices.back());
  EXPECT_EQ(distanceToPoints(vertices[1], points), 0.0);
  for (const Vec2& p : points) EXPECT_LE(distanceToPolyline(p, vertices), 1e-12) << p.transpose();
  EXPECT_LE(largestStep(points), kSpacingFraction * std::sqrt(200.0));
}

TEST(PointFileSvg, PolygonClosesWithoutRepeatingItsStart) {
  const std::vector<Stroke> strokes = svg("<polygon points=\"0 0, 4 0, 4 3\" />");
  ASSERT_EQ(strokes.size(), 1u);
  const std::vector<Vec2> points = pointsOf(strokes[0]);
  const double spacing = kSpacingFraction * 5.0;
  EXPECT_EQ(points.front(), Vec2(0, 0));
  EXPECT_GT((points.back() - points.front()).norm(), 0.0);
  EXPECT_LE((points.back() - points.front()).norm(), spacing);
  EXPECT_LE(largestStep(points), spacing);
  std::vector<Vec2> triangle{{0, 0}, {4, 0}, {4, 3}, {0, 0}};
  for (const Vec2& p : points) EXPECT_LE(distanceToPolyline(p, triangle), 1e-12) << p.transpose();
  EXPECT_EQ(distanceToPoints(Vec2(4, 0), points), 0.0);
  EXPECT_EQ(distanceToPoints(Vec2(4, 3), points), 0.0);
}

TEST(PointFileSvg, RelativeHorizontalVerticalAndClose) {
  const std::vector<Stroke> strokes = svg("<path d='M10 10 h 5 v 5 H 10 z'/>");
  ASSERT_EQ(strokes.size(), 1u);
  const std::vector<Vec2> points = pointsOf(strokes[0]);
  const std::vector<Vec2> square{{10, 10}, {15, 10}, {15, 15}, {10, 15}, {10, 10}};
  for (const Vec2& corner : square) EXPECT_EQ(distanceToPoints(corner, points), 0.0) << corner.transpose();
  for (const Vec2& p : points) EXPECT_LE(distanceToPolyline(p, square), 1e-12) << p.transpose();
  EXPECT_NE(points.back(), points.front());
  EXPECT_LE((points.back() - points.front()).norm(), kSpacingFraction * std::sqrt(50.0));
}

TEST(PointFileSvg, ShorthandsRelativeFormsAndCompactNumbersMatchExplicitCommands) {
  expectSamePath("M0 0 C 0 1 1 1 1 0 S 2 -1 2 0", "M0 0 C 0 1 1 1 1 0 C 1 -1 2 -1 2 0");
  expectSamePath("m0 0 c 0 1 1 1 1 0 s 1 -1 1 0", "M0 0 C 0 1 1 1 1 0 C 1 -1 2 -1 2 0");
  expectSamePath("M0 0 S 1 1 2 0", "M0 0 C 0 0 1 1 2 0");  // S without a C before: first control = current
  expectSamePath("M0 0 Q 1 2 2 0 T 4 0 T 6 0", "M0 0 Q 1 2 2 0 Q 3 -2 4 0 Q 5 2 6 0");
  expectSamePath("m0 0 q 1 2 2 0 t 2 0", "M0 0 Q 1 2 2 0 Q 3 -2 4 0");
  expectSamePath("M1.5.5L1e-3-2", "M 1.5 0.5 L 0.001 -2");
  expectSamePath("M0,0 1,0 1,1", "M0 0 L1 0 L1 1");  // implicit lineto after moveto
  expectSamePath("m1 1 1 0 0 1", "M1 1 L2 1 L2 2");
  expectSamePath("M0 0L1 0 2 1,3 0", "M0 0 L1 0 L2 1 L3 0");
  expectSamePath("M0 0a1 1 0 0 1 2 0", "M0 0 A1 1 0 0 1 2 0");
  expectSamePath("M0 0A1 1 0 012 0", "M0 0 A1 1 0 0 1 2 0");  // flags need no separator
  expectSamePath("M0 0 l 1 1 z l 2 0", "M0 0 L 1 1 Z M 0 0 L 2 0");  // after Z: back at the start
}

TEST(PointFileSvg, TwoArcsMakeACircle) {
  // Circle of radius 1 about (1, 0); the sweep flag 1 runs the first half through y < 0.
  const std::vector<Stroke> strokes = svg("<path d=\"M 0 0 A 1 1 0 0 1 2 0 A 1 1 0 0 1 0 0 Z\"/>");
  ASSERT_EQ(strokes.size(), 1u);
  const std::vector<Vec2> points = pointsOf(strokes[0]);
  const Vec2 centre(1, 0);
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    EXPECT_NEAR((p - centre).norm(), 1.0, 1e-9) << p.transpose();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double spacing = kSpacingFraction * std::sqrt(8.0);
  const double sag = spacing * spacing / 8.0;  // an extreme can fall between two points
  EXPECT_NEAR(lo.x(), 0.0, 1e-12);
  EXPECT_NEAR(hi.x(), 2.0, 1e-12);
  EXPECT_NEAR(lo.y(), -1.0, sag);
  EXPECT_NEAR(hi.y(), 1.0, sag);
  EXPECT_LT(points[1].y(), 0.0);
  EXPECT_LE(largestStep(points), spacing);
  EXPECT_GT((points.back() - points.front()).norm(), 0.0);  // the start is not repeated
  EXPECT_LE((points.back() - points.front()).norm(), spacing);
  EXPECT_EQ(distanceToPoints(Vec2(2, 0), points), 0.0);
}

TEST(PointFileSvg, RotatedEllipseArcAndRadiiScaledUp) {
  // Quarter of the ellipse x'^2/4 + y'^2 = 1 about the origin, axes turned 30 degrees.
  const double phi = std::numbers::pi / 6.0;
  const auto rotated = [&](double x, double y) {
    return Vec2(std::cos(phi) * x - std::sin(phi) * y, std::sin(phi) * x + std::cos(phi) * y);
  };
  const Vec2 from = rotated(2, 0), to = rotated(0, 1);
  char d[256];
  std::snprintf(d, sizeof d, "M %.17g %.17g A 2 1 30 0 1 %.17g %.17g", from.x(), from.y(), to.x(), to.y());
  const std::vector<Stroke> strokes = svg(std::string("<path d='") + d + "'/>");
  ASSERT_EQ(strokes.size(), 1u);
  ASSERT_GE(strokes[0].samples.size(), 5u);
  for (const StrokeSample& s : strokes[0].samples) {
    const Vec2 local(std::cos(phi) * s.p.x() + std::sin(phi) * s.p.y(), -std::sin(phi) * s.p.x() + std::cos(phi) * s.p.y());
    EXPECT_NEAR(local.x() * local.x() / 4.0 + local.y() * local.y(), 1.0, 1e-9) << s.p.transpose();
    EXPECT_GE(local.x(), -1e-12);  // the short arc, in the first quadrant
    EXPECT_GE(local.y(), -1e-12);
  }
  // Radii too small for the chord are scaled up (SVG F.6.6): a semicircle of radius 1.
  const std::vector<Stroke> small = svg("<path d='M0 0 A 0.1 0.1 0 0 0 2 0'/>");
  ASSERT_EQ(small.size(), 1u);
  for (const StrokeSample& s : small[0].samples) EXPECT_NEAR((s.p - Vec2(1, 0)).norm(), 1.0, 1e-9);
  // A zero radius makes a straight line.
  const std::vector<Stroke> line = svg("<path d='M0 0 A 0 1 0 0 0 2 0'/>");
  ASSERT_EQ(line.size(), 1u);
  for (const StrokeSample& s : line[0].samples) EXPECT_EQ(s.p.y(), 0.0);
}

TEST(PointFileSvg, ScannerSkipsWhatIsNotDrawn) {
  const std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<!DOCTYPE svg [ <!ATTLIST path kvg:type CDATA #IMPLIED > ]>\n"
      "<svg xmlns='http://www.w3.org/2000/svg'>\n"
      "<!-- <path d='M 99 99 L 98 98'/> -->\n"
      "<defs><path id='hidden' d='M 50 50 L 60 60'/><clipPath><polygon points='0 0 1 1 2 0'/></clipPath></defs>\n"
      "<style>path { stroke: red } /* <path d='junk'> */</style>\n"
      "<g transform='scale(2)'>\n"
      "  <path stroke=\"black\" d=\"M0 0 L 1 0\" id='a>b'/>\n"
      "  <circle cx='5' cy='5' r='1'/>\n"
      "  <svg:path d='M 0 1 L 1 1'></svg:path>\n"
      "  <polyline points='3 3'/>\n"
      "  <path d='M 5 5'/>\n"
      "</g>\n"
      "</svg>\n";
  const std::vector<Stroke> strokes = parseStrokes(text, "skip.svg");
  ASSERT_EQ(strokes.size(), 2u);  // the one-point polyline and the lone moveto draw nothing
  EXPECT_EQ(strokes[0].samples.front().p, Vec2(0, 0));
  EXPECT_EQ(strokes[0].samples.back().p, Vec2(1, 0));  // transforms are ignored
  EXPECT_EQ(strokes[1].samples.front().p, Vec2(0, 1));
}

TEST(PointFileSvg, EachSubpathIsAStrokeAndCurvesGetSeveralPoints) {
  // Two subpaths far apart; the second curve is tiny against the bounding box.
  const std::vector<Stroke> strokes = svg("<path d='M0 0 L 100 0 M 50 50 q 0.01 0.01 0.02 0'/>");
  ASSERT_EQ(strokes.size(), 2u);
  EXPECT_LE(largestStep(pointsOf(strokes[0])), kSpacingFraction * std::hypot(100.0, 50.0));
  EXPECT_EQ(strokes[1].samples.size(), 5u);  // 4 pieces at least
}

TEST(PointFileSvg, ErrorsNameTheLine) {
  expectError("<svg>\n<!-- <path d='junk'/> -->\n<path d='M0 0 L 1 x'/>\n</svg>", "e1.svg",
              {"e1.svg:3:", "bad path data near 'x'"});
  // Data spread over lines: the line of the bad data.
  expectError("<svg>\n<path\n  d='M0 0\n     L 1 1\n     K 2 2'/>\n</svg>", "e2.svg", {"e2.svg:5:", "near 'K 2 2'"});
  expectError("<svg>\n\n<path d='L 1 1'/></svg>", "e3.svg", {"e3.svg:3:", "bad path data"});  // no moveto first
  expectError("<svg><path d='M0 0 A 1 1 0 2 1 2 0'/></svg>", "e4.svg", {"e4.svg:1:", "near '2 1 2 0'"});
  expectError("<svg><path d='M0 0 Z 1 1'/></svg>", "e5.svg", {"e5.svg:1:", "near '1 1'"});
  expectError("<svg><path d='M0 0 L 1 1,,2 2'/></svg>", "e5b.svg", {"e5b.svg:1:", "near ',,2 2'"});
  expectError("<svg>\n<polyline points='0 0 1 1 2'/></svg>", "e6.svg", {"e6.svg:2:", "odd number of coordinates"});
  expectError("<svg>\n<path d='M0 0 L 1 1\n/></svg>", "e7.svg", {"e7.svg:2:", "unterminated attribute"});
  expectError("<svg>\n<!-- never closed\n<path d='M0 0 L 1 1'/></svg>", "e8.svg", {"e8.svg:2:", "unterminated comment"});
  expectError("<svg><rect width='3' height='3'/></svg>", "e9.svg", {"e9.svg: no points"});
  expectError("<svg><path d='M0 0 L 1e999 0'/></svg>", "e10.svg", {"e10.svg:1:", "near '1e999 0'"});
}

TEST(PointFileSvg, CoordinatesBeyondDoubleRangeAreErrors) {
  // Each number finite, the sum of relative steps not: the points went to infinity.
  expectError("<svg>\n<path d='M1.7e308 0 l 1.7e308 0 l 0 5'/></svg>", "rel.svg",
              {"rel.svg:2:", "bad path data", "coordinate out of range"});
  // A reflected control point (S after C) can overflow too.
  expectError("<svg><path d='M0 0 C 0 0 -1.7e308 0 1.7e308 0 S 5 5 6 6'/></svg>", "refl.svg",
              {"refl.svg:1:", "out of range"});
  // Finite points whose distances overflow: the spacing was NaN, cast to int (undefined).
  expectError("<svg><path d='M-1e308 -1e308 L 1e308 1e308 L 1e308 -1e308'/></svg>", "huge.svg",
              {"huge.svg:1:", "coordinates too large"});
  expectError("<svg><polyline points='0,0 1.7e308,0 1.7e308,1.7e308'/></svg>", "poly.svg",
              {"poly.svg:1:", "bad points data", "coordinates too large"});
  // 400 digits are not 0.
  expectError("<svg><path d='M0 0 L " + std::string(400, '9') + " 1 L 5 5'/></svg>", "digits.svg",
              {"digits.svg:1:", "bad path data"});
}

TEST(PointFileSvg, ArcsWithExtremeRadiiOrRotationStayOnTheirCurve) {
  // Radii 1e300 for a chord of 14: the arc is its chord. The squared radii overflowed
  // and the centre landed on the chord's midpoint, drawing a circle of radius 1e300.
  const std::vector<Stroke> flat = svg("<path d='M0 0 A 1e300 1e300 0 0 1 10 10'/>");
  ASSERT_EQ(flat.size(), 1u);
  for (const Vec2& q : pointsOf(flat[0])) {
    EXPECT_NEAR(q.x(), q.y(), 1e-9);
    EXPECT_TRUE(q.x() >= -1e-9 && q.x() <= 10 + 1e-9) << q.transpose();
  }
  EXPECT_EQ(pointsOf(flat[0]).back(), Vec2(10, 10));
  // A rotation of 1e308 degrees: times pi it overflowed to inf, the arc was dropped.
  const double reduced = std::fmod(1e308, 360.0);
  std::ostringstream reference;
  reference.precision(17);
  reference << "M0 0 A 5 3 " << reduced << " 0 1 10 10";
  expectSamePath("M0 0 A 5 3 1e308 0 1 10 10", reference.str());
  EXPECT_GT(svg("<path d='M0 0 A 5 3 1e308 0 1 10 10'/>")[0].samples.size(), 4u);
  // Ordinary radii read as before: a half circle of radius 5 through its top.
  const std::vector<Stroke> half = svg("<path d='M0 0 A 5 5 0 0 1 10 0'/>");
  for (const Vec2& q : pointsOf(half[0])) EXPECT_NEAR((q - Vec2(5, 0)).norm(), 5.0, 1e-9);
}

// ------------------------------------------------------------------ real files

TEST(PointFileRealData, EveryCsvReads) {
  int files = 0;
  for (const char* folder : {"strokes", "curves"})
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(kData / folder)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".csv") continue;
      ++files;
      std::vector<Stroke> strokes;
      EXPECT_NO_THROW(strokes = readStrokes(entry.path())) << entry.path();
      // The files have no header and one blank line between strokes: count independently.
      std::ifstream in(entry.path());
      std::string line;
      std::size_t expected_strokes = 0, expected_points = 0;
      bool in_stroke = false;
      while (std::getline(in, line)) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) {
          in_stroke = false;
          continue;
        }
        if (!in_stroke) ++expected_strokes;
        in_stroke = true;
        ++expected_points;
      }
      std::size_t points = 0;
      for (const Stroke& s : strokes) points += s.samples.size();
      EXPECT_EQ(strokes.size(), expected_strokes) << entry.path();
      EXPECT_EQ(points, expected_points) << entry.path();
    }
  EXPECT_GE(files, 100);  // 48 $1 + 16 MMG + 36 Omniglot + 3 KanjiVG + 9 glyphs
  const std::vector<Stroke> caret =
      readStrokes(kData / "strokes/dollar1_unistroke_s01_pilot/csv/medium/caret.csv");
  EXPECT_EQ(caret.size(), 2u);
  EXPECT_EQ(caret[0].samples[0].t, 0.0);  // x,y,t
  const std::vector<Stroke> mmg = readStrokes(kData / "strokes/mmg_s10_stylus_medium/csv/10-stylus-medium-D-01.csv");
  EXPECT_EQ(mmg[0].samples[0].pressure, 128.0);  // x,y,t,pressure
}

TEST(PointFileRealData, OmniglotOriginalsMatchTheirCsv) {
  int files = 0;
  const fs::path root = kData / "strokes/omniglot_small1_sample";
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root / "txt")) {
    if (!entry.is_regular_file() || entry.path().extension() != ".txt") continue;
    ++files;
    fs::path csv = root / "csv" / fs::relative(entry.path(), root / "txt");
    csv.replace_extension(".csv");
    const std::vector<Stroke> original = readStrokes(entry.path());
    const std::vector<Stroke> copy = readStrokes(csv);
    ASSERT_EQ(original.size(), copy.size()) << entry.path();
    for (std::size_t i = 0; i < original.size(); ++i) {
      ASSERT_EQ(original[i].samples.size(), copy[i].samples.size()) << entry.path() << " stroke " << i;
      for (std::size_t j = 0; j < original[i].samples.size(); ++j) {
        EXPECT_EQ(original[i].samples[j].p, copy[i].samples[j].p);
        EXPECT_EQ(original[i].samples[j].t, copy[i].samples[j].t);
      }
    }
  }
  EXPECT_EQ(files, 36);
}

TEST(PointFileRealData, AirfoilsAreOneProfileEach) {
  const std::vector<std::pair<std::string, std::size_t>> files{
      {"clark-y.dat", 33}, {"naca-m6.dat", 35}, {"xfoil_naca2412.dat", 160}, {"xfoil_naca0012.dat", 160}};
  for (const auto& [file, documented] : files) {
    const fs::path path = kData / "curves/airfoils" / file;
    // Count the "x y" lines independently of the reader.
    std::ifstream in(path);
    std::string line;
    std::size_t numeric_lines = 0;
    while (std::getline(in, line)) {
      std::istringstream fields(line);
      double x = 0.0, y = 0.0;
      if (fields >> x >> y) ++numeric_lines;
    }
    EXPECT_EQ(numeric_lines, documented) << file << " (SOURCES.md)";
    const std::vector<Stroke> strokes = readStrokes(path);
    ASSERT_EQ(strokes.size(), 1u) << file;
    EXPECT_EQ(strokes[0].samples.size(), numeric_lines) << file;
    EXPECT_NEAR(strokes[0].samples.front().p.x(), 1.0, 1e-12) << file;  // starts at the trailing edge
  }
}

TEST(PointFileRealData, KanjiVgFlattensOntoTheDenseSamples) {
  for (const char* code : {"0306e", "03057", "04e59"}) {
    SCOPED_TRACE(code);
    const fs::path svg_path = kData / "curves/kanjivg" / (std::string(code) + ".svg");
    const std::string text = slurp(svg_path);
    std::size_t paths = 0;
    for (std::size_t at = text.find("<path"); at != std::string::npos; at = text.find("<path", at + 1)) ++paths;
    const std::vector<Stroke> flattened = readStrokes(svg_path);
    const std::vector<Stroke> samples = readStrokes(kData / "curves/kanjivg/csv" / (std::string(code) + ".csv"));
    ASSERT_EQ(flattened.size(), paths);
    ASSERT_EQ(samples.size(), paths);
    for (std::size_t i = 0; i < paths; ++i) {
      const std::vector<Vec2> ours = pointsOf(flattened[i]);
      const std::vector<Vec2> theirs = pointsOf(samples[i]);
      const double spacing = kSpacingFraction * diagonalOf(ours);
      EXPECT_LE(largestStep(ours), spacing);
      // Both are on the same Beziers: every sample lies on our polyline and vice versa
      // (within chord sag), and the nearest of our points is at most half a spacing off.
      double worst_theirs = 0.0, worst_ours = 0.0, worst_vertex = 0.0;
      for (const Vec2& q : theirs) {
        worst_theirs = std::max(worst_theirs, distanceToPolyline(q, ours));
        worst_vertex = std::max(worst_vertex, distanceToPoints(q, ours));
      }
      for (const Vec2& q : ours) worst_ours = std::max(worst_ours, distanceToPolyline(q, theirs));
      EXPECT_LE(worst_theirs, 0.05) << "CSV samples off our flattening (units)";
      EXPECT_LE(worst_ours, 0.05) << "our points off the CSV polyline (units)";
      EXPECT_LE(worst_vertex, 0.5 * spacing + 0.05) << "CSV sample to nearest flattened point (units)";
      EXPECT_EQ(ours.front(), theirs.front());
      EXPECT_LE((ours.back() - theirs.back()).norm(), 1e-3);
    }
  }
}

TEST(PointFileRealData, DejaVuOHasTwoClosedContours) {
  std::ifstream in(kData / "curves/glyphs_dejavusans/DejaVuSans_outlines_svgpath.tsv");
  std::string line, path_data;
  while (std::getline(in, line))
    if (line.rfind("O\t", 0) == 0) path_data = line.substr(line.rfind('\t') + 1);
  ASSERT_FALSE(path_data.empty());
  const std::vector<Stroke> strokes = parseStrokes("<svg><path d=\"" + path_data + "\"/></svg>", "O.svg");
  ASSERT_EQ(strokes.size(), 2u);
  const std::vector<Stroke> samples = readStrokes(kData / "curves/glyphs_dejavusans/DejaVuSans_O.csv");
  ASSERT_EQ(samples.size(), 2u);
  double diagonal = 0.0;
  for (const Stroke& s : strokes) diagonal = std::max(diagonal, diagonalOf(pointsOf(s)));
  const double spacing = kSpacingFraction * diagonal;
  for (std::size_t i = 0; i < 2; ++i) {
    const std::vector<Vec2> ours = pointsOf(strokes[i]);
    const double gap = (ours.back() - ours.front()).norm();
    EXPECT_GT(gap, 0.0) << "contour " << i << ": start repeated";
    EXPECT_LE(gap, spacing) << "contour " << i << ": not closed";
    EXPECT_LE(largestStep(ours), spacing);
    // The CSV samples the same quadratics ~10 font units apart, closing edge included.
    std::vector<Vec2> theirs = pointsOf(samples[i]);
    theirs.push_back(theirs.front());
    double worst = 0.0;
    for (const Vec2& q : ours) worst = std::max(worst, distanceToPolyline(q, theirs));
    EXPECT_LE(worst, 0.5) << "contour " << i << " off the CSV samples (font units)";
  }
}

// ReadLimits: each limit is checked as the file is read, and the message names the
// line (or key), the limit and the lafit flag that raises it; one under the limit reads.
TEST(ReadLimits, PointsPerStrokeAndStrokesPerFile) {
  ReadLimits limits;
  limits.max_points_per_stroke = 3;
  EXPECT_EQ(parseStrokes("1,2\n3,4\n5,7\n", "ok.csv", limits).size(), 1u);
  expectError("1,2\n3,4\n5,7\n8,9\n", "a.csv", {"a.csv:4:", "stroke 1 has more than 3 points", "--max-points"},
              limits);
  expectError(R"({"strokes": [{"points": [[0,0],[1,1],[2,0],[3,1]]}]})", "a.json",
              {"a.json: strokes[0].points: 4 points, more than 3", "--max-points"}, limits);
  limits = {};
  limits.max_strokes = 2;
  EXPECT_EQ(parseStrokes("1,2\n3,4\n\n5,6\n7,9\n", "ok.csv", limits).size(), 2u);
  expectError("1,2\n3,4\n\n5,6\n7,9\n\n1,1\n2,5\n", "b.csv", {"b.csv:8:", "more than 2 strokes", "--max-strokes"},
              limits);
  expectError(R"({"strokes": [{"points": [[0,0]]}, {"points": [[0,0]]}, {"points": [[0,0]]}]})", "b.json",
              {"b.json: 3 strokes, more than 2", "--max-strokes"}, limits);
  const std::string three_paths = "<svg>\n<path d='M0 0 L1 1'/>\n<path d='M0 0 L1 2'/>\n<path d='M0 0 L2 1'/>\n</svg>";
  expectError(three_paths, "b.svg", {"b.svg:4:", "more than 2 strokes", "--max-strokes"}, limits);
}

TEST(ReadLimits, NestingOfJsonAndSvg) {
  ReadLimits limits;
  limits.max_nesting = 5;  // a stroke file's own depth: {"strokes": [{"points": [[x, y]]}]}
  EXPECT_EQ(parseStrokes(R"({"strokes": [{"points": [[0,0],[1,1],[2,0]]}]})", "ok.json", limits).size(), 1u);
  // (brackets inside strings do not count)
  EXPECT_EQ(parseStrokes(R"({"note": "[[[[[[", "strokes": [{"points": [[0,0],[1,1],[2,0]]}]})", "ok.json", limits).size(),
            1u);
  expectError("{\"strokes\": [{\"points\": [[[0]]]}]}", "deep.json", {"deep.json:1:27:", "nested deeper than 5", "--max-nesting"},
              limits);
  // a million open brackets are refused before nlohmann parses (or recurses into) them
  expectError(std::string(1'000'000, '['), "huge.json", {"huge.json:1:6:", "nested deeper than 5"}, limits);
  expectError(std::string(1'000'000, '['), "huge.json", {"huge.json:1:257:", "nested deeper than 256"});
  const std::string groups = "<svg>\n<g>\n<g>\n<g>\n<g><path d='M0 0 L1 1 L2 0'/></g></g></g></g></svg>";
  limits.max_nesting = 4;
  expectError(groups, "deep.svg", {"deep.svg:5:", "elements nested deeper than 4", "--max-nesting"}, limits);
  limits.max_nesting = 5;
  EXPECT_EQ(parseStrokes(groups, "ok.svg", limits).size(), 1u);
}

// A 4 KB path of 200 back-and-forth curves flattens to about 50,000 points: over a
// limit of 20,000 it is refused as the points are counted, before they are made.
TEST(ReadLimits, SvgFlatteningIsRefusedBeforeTheWork) {
  std::string d = "M 0 0";
  for (int i = 0; i < 200; ++i) d += i % 2 ? " C 0 50 100 -50 0 0" : " C 100 50 0 -50 100 0";
  ReadLimits limits;
  limits.max_svg_points = 20'000;
  const std::string text = "<svg>\n<path d='" + d + "'/>\n</svg>";
  expectError(text, "zig.svg", {"zig.svg:2:", "<path> flattens to more than 20000 points", "--max-svg-points"}, limits);
  limits.max_svg_points = 200'000;
  const std::vector<Stroke> strokes = parseStrokes(text, "zig.svg", limits);
  ASSERT_EQ(strokes.size(), 1u);
  EXPECT_GT(strokes[0].samples.size(), 20'000u);
  EXPECT_LE(strokes[0].samples.size(), 200'000u);
}

}  // namespace
}  // namespace la
