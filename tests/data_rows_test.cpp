// The rows data_benchmark writes and compare_rows reads (tests/benchmarks/data_rows.h):
// written rows read back the same, every malformed line named by file and line, the
// nearest-rank percentiles, and per stroke the fastest of several runs.

#include "tests/benchmarks/data_rows.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace la::test {
namespace {

std::string fileOf(const std::vector<StrokeRow>& rows) {
  std::string text = std::string(kRowsHeader) + "\n";
  for (const StrokeRow& r : rows) text += rowCsv(r);
  return text;
}

TEST(DataRows, WrittenRowsReadBackTheSame) {
  // (a stroke's name with a comma and a quote in it, as a file name may have)
  const std::vector<StrokeRow> rows{{"dollar1", "strokes/a.csv #0", 2.5, 4, 2, 0.756537, 48.4892},
                                    {"glyphs", "curves/x, \"y\".csv #1 variant 3", 51.25, 12, 8, 0.99, 1.0}};
  const std::vector<StrokeRow> read = readRows(fileOf(rows), "rows.csv");
  ASSERT_EQ(read.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(read[i].data_set, rows[i].data_set);
    EXPECT_EQ(read[i].stroke, rows[i].stroke);
    EXPECT_DOUBLE_EQ(read[i].ms, rows[i].ms);
    EXPECT_TRUE(sameFigures(read[i], rows[i]));
  }
}

TEST(DataRows, ReadsTheRowsOfEarlierBuildsWhoseDataSetIsNotQuoted) {
  const std::string text = std::string(kRowsHeader) + "\r\nmmg,\"strokes/m.csv #2\",0.190,1,0,0.595,2.09\r\n";
  const std::vector<StrokeRow> read = readRows(text, "old.csv");
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].data_set, "mmg");
  EXPECT_EQ(read[0].stroke, "strokes/m.csv #2");
  EXPECT_EQ(read[0].segments, 1);
  EXPECT_DOUBLE_EQ(read[0].radius, 2.09);
}

// The message readRows throws for `text` read as "r.csv".
std::string errorOf(const std::string& text) {
  try {
    readRows(text, "r.csv");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(DataRows, AMalformedLineIsNamedByFileLineAndWhatIsWrong) {
  const std::string header = std::string(kRowsHeader) + "\n";
  EXPECT_EQ(errorOf(""), "r.csv: empty");
  EXPECT_EQ(errorOf("x,y\n"), std::string("r.csv:1: not a data_benchmark --rows file (its header is \"") + kRowsHeader + "\")");
  EXPECT_EQ(errorOf(header + "a,\"s #0\",1,2,3,0.5,1\na,\"s #1\",1,two,3,0.5,1\n"), "r.csv:3: segments is not a number: \"two\"");
  EXPECT_EQ(errorOf(header + "a,\"s #0\",1,2,3,0.5\n"), "r.csv:2: 7 fields expected, 6 found");
  EXPECT_EQ(errorOf(header + "a,\"s #0,1,2,3,0.5,1\n"), "r.csv:2: a quoted field is not closed");
  EXPECT_EQ(errorOf(header + "a,\"s\" #0,1,2,3,0.5,1\n"), "r.csv:2: text after a quoted field");
  EXPECT_EQ(errorOf(header + "a,\"s #0\",,2,3,0.5,1\n"), "r.csv:2: ms is not a number: \"\"");
  EXPECT_EQ(errorOf(header + "a,\"s #0\",1,2,3.5,0.5,1\n"), "r.csv:2: extrema_dense is not a number: \"3.5\"");
}

TEST(DataRows, PercentilesAreNearestRank) {
  std::vector<double> values;
  for (int v = 10; v >= 1; --v) values.push_back(v);  // (unsorted)
  EXPECT_EQ(percentile(values, 0.5), 5.0);
  EXPECT_EQ(percentile(values, 0.9), 9.0);  // (0.9 * 10 is the 9th, not rounded up to the 10th)
  EXPECT_EQ(percentile(values, 0.99), 10.0);
  EXPECT_EQ(percentile(values, 1.0), 10.0);
  EXPECT_EQ(percentile({3.0}, 0.5), 3.0);
  // p99 of 232 strokes is the 230th: the third slowest
  std::vector<double> many;
  for (int v = 1; v <= 232; ++v) many.push_back(v);
  EXPECT_EQ(percentile(many, 0.99), 230.0);
}

TEST(DataRows, EachStrokeTakesTheFastestOfItsRunsAndDifferingFiguresAreListed) {
  const std::vector<StrokeRow> run1{{"s", "a #0", 3.0, 4, 2, 0.5, 2.0}, {"s", "b #0", 1.0, 1, 0, 0.25, 9.0}};
  const std::vector<StrokeRow> run2{{"s", "b #0", 0.5, 1, 0, 0.25, 9.0}, {"s", "a #0", 2.0, 4, 2, 0.5, 2.0}};
  const std::vector<StrokeRow> run3{{"s", "a #0", 2.5, 5, 2, 0.5, 2.0}, {"t", "c #0", 7.0, 2, 1, 0.75, 3.0}};
  const FastestRows f = fastestOf({run1, run2, run3});
  ASSERT_EQ(f.rows.size(), 3u);
  EXPECT_EQ(f.rows[0].stroke, "a #0");
  EXPECT_EQ(f.rows[0].ms, 2.0);
  EXPECT_EQ(f.rows[0].segments, 4);  // (the first run's figures)
  EXPECT_EQ(f.rows[1].stroke, "b #0");
  EXPECT_EQ(f.rows[1].ms, 0.5);
  EXPECT_EQ(f.rows[2].data_set, "t");
  EXPECT_EQ(f.differing, std::vector<std::string>{"a #0"});
}

}  // namespace
}  // namespace la::test
