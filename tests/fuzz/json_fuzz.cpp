// libFuzzer target: the input as the stroke JSON (la::parseStrokes with "x.json",
// app/io/point_file.h) and as a curves document (la::parseCurvesDocument,
// core/curve_json.h), which must then write and read back unchanged.
// Allowed outcomes and invariants: tests/fuzz/fuzz_entries.h.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  la::fuzz::json(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
