// libFuzzer target: the input read as CSV, .dat, SVG or stroke JSON (by its first
// character), then la::fitStroke (fitting/pipeline.h) on its first strokes, capped to a
// few hundred samples, with a time budget; the curve it returns must be finite.
// Allowed outcomes and invariants: tests/fuzz/fuzz_entries.h.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  la::fuzz::fit(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
