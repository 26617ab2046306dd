// libFuzzer target: the input as a CSV/TXT file and as an airfoil .dat
// (la::parseStrokes with "x.csv" and "x.dat", app/io/point_file.h).
// Allowed outcomes and invariants: tests/fuzz/fuzz_entries.h.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  la::fuzz::pointFile(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
