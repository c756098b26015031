// libFuzzer target: the scene parser (parse_scene) on arbitrary text, without and with the
// `--set` overrides written in the input as "#--set key.path=value" lines, and the resolved
// scene writer on whatever it accepts. Anything but an InputError naming the file aborts.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mppm::fuzz::feed_scene({reinterpret_cast<const char*>(data), size}, "fuzz/scene.yaml");
  return 0;
}
