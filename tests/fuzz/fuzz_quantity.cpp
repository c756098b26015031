// libFuzzer target: the unit parser (parse_quantity, parse_quantity_as for every dimension a
// scene uses, length_unit_in_metres). Anything but std::invalid_argument, or a non-finite
// accepted value, aborts.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mppm::fuzz::feed_quantity({reinterpret_cast<const char*>(data), size});
  return 0;
}
