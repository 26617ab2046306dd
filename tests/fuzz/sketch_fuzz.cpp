// libFuzzer target: the input as the app's sketch file (la::parseSketch,
// app/io/sketch_file.h), which must then write and read back unchanged.
// Allowed outcomes and invariants: tests/fuzz/fuzz_entries.h.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  la::fuzz::sketch(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
