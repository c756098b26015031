// libFuzzer target: the run directory's snapshot reader (read_snapshot) on arbitrary bytes.
// The input goes through a file because that is the reader's interface (and the user's).
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = mppm::fuzz::write_temporary_input({reinterpret_cast<const char*>(data), size}, ".snap");
  mppm::fuzz::feed_snapshot_file(path);
  return 0;
}
