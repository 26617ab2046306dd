// libFuzzer target: the input as an SVG file (la::parseStrokes with "x.svg",
// app/io/point_file.h: the hand-written XML scanner, path data, arc conversion and
// flattening).
// Allowed outcomes and invariants: tests/fuzz/fuzz_entries.h.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  la::fuzz::svg(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
