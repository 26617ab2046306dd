// Every input the fuzzers found a bug with, kept in tests/fuzz/regressions/<target>/,
// runs through its target's entry (tests/fuzz/fuzz_entries.h) in the normal build: it
// must be read or refused with the documented error, and a fit must be finite. The
// seed corpus (tests/fuzz/corpus/<target>/) runs too, so each target's entry is
// exercised here even before it has a regression. A finding: add its reproducer file
// to the target's regressions folder (README, "Fuzzing and sanitizers").

#include "tests/fuzz/fuzz_entries.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace la::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(LAFAIR_SOURCE_DIR) / "tests" / "fuzz";
const fs::path kData = LAFAIR_SHARED_DATA_DIR;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<fs::path> filesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// Runs `entry` on every seed and regression input of `target`; returns how many.
std::size_t runAll(const std::string& target, const std::function<void(std::string_view)>& entry) {
  const std::vector<fs::path> seeds = filesIn(kFuzzDir / "corpus" / target);
  EXPECT_FALSE(seeds.empty()) << "no seed inputs in " << (kFuzzDir / "corpus" / target);
  std::vector<fs::path> inputs = seeds;
  for (const fs::path& p : filesIn(kFuzzDir / "regressions" / target)) inputs.push_back(p);
  for (const fs::path& path : inputs) {
    SCOPED_TRACE(path.string());
    const std::string data = slurp(path);
    try {
      entry(data);
    } catch (const std::exception& e) {  // FuzzFinding or an undocumented error: the bug is back
      ADD_FAILURE() << "threw: " << e.what();
    }
  }
  return inputs.size();
}

TEST(FuzzRegression, PointFile) { runAll("point_file", pointFile); }
TEST(FuzzRegression, Svg) { runAll("svg", svg); }
TEST(FuzzRegression, Json) { runAll("json", json); }
TEST(FuzzRegression, Sketch) { runAll("sketch", sketch); }
TEST(FuzzRegression, Fit) { runAll("fit", fit); }

/// The finding: an airfoil .dat with one coordinate mistyped (0.0500 for
/// 50.0000) drove a NaN total turning into fitChain's panel count, an int conversion
/// of NaN (undefined; UBSan's float-cast-overflow). Every shared airfoil, each line
/// holding 0.0500 mistyped in turn: the fit must come back finite or refuse the stroke.
TEST(FuzzRegression, AirfoilWithAMistypedCoordinateFits) {
  std::size_t variants = 0;
  for (const fs::path& path : filesIn(kData / "curves" / "airfoils")) {
    if (path.extension() != ".dat") continue;
    const std::string text = slurp(path);
    for (std::size_t at = text.find("0.0500"); at != std::string::npos; at = text.find("0.0500", at + 1)) {
      std::string mistyped = text;
      mistyped.replace(at, 6, "50.0000");
      SCOPED_TRACE(path.filename().string() + " with 0.0500 at offset " + std::to_string(at) + " read as 50.0000");
      ++variants;
      try {
        fit(mistyped);
      } catch (const std::exception& e) {
        ADD_FAILURE() << "threw: " << e.what();
      }
    }
  }
  EXPECT_GE(variants, 4u) << "the shared airfoils should give several mistyped variants";
}

}  // namespace
}  // namespace la::fuzz
