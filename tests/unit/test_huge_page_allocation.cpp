// The solver's global operator new (solver/huge_page_allocation.cpp): large allocations advised for
// 2 MiB pages without gaps of alignment, medium ones in advised arenas, the contents as malloc gives
// them, and operator new's failure contract.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
constexpr bool replaced = true;
#else
constexpr bool replaced = false;  // the sanitizer's operator new is kept
#endif

constexpr std::uintptr_t huge_page = std::uintptr_t{2} << 20;

// The VmFlags line of the mapping that holds `address` (/proc/self/smaps), empty if none.
std::string vm_flags_at(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream range(line);
    if (range >> std::hex >> begin >> dash >> end && dash == '-') inside = begin <= a && a < end;
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return {};
}

TEST(HugePageAllocation, LargeArraysAreAdvisedForHugePages) {
  if (!replaced) GTEST_SKIP() << "sanitizer build: operator new is the sanitizer's";
  if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage"))
    GTEST_SKIP() << "this kernel has no transparent huge pages: the advice is refused, the memory is the same";
  std::vector<double> state(std::size_t{1} << 20, 0.0);  // 8 MiB, like a point-state array
  // "hg": the mapping carries MADV_HUGEPAGE, whatever the system setting then grants.
  for (const double* at : {state.data(), state.data() + state.size() - 1})
    EXPECT_NE(vm_flags_at(at).find(" hg"), std::string::npos) << vm_flags_at(at);
}

// The resident size of this process (VmRSS of /proc/self/status), in bytes.
std::uint64_t resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

// Large arrays cost their size in resident memory, not a huge page more each. Aligned to 2 MiB,
// each left a free gap of up to 2 MiB before it in malloc's heap, made resident as a whole by the
// header malloc writes into it when the heap's range is on huge pages: four arrays of 4.5 MiB took
// 24 MiB instead of 18. Two huge pages of slack: the first array's and the last one's partly used
// spans at their ends.
TEST(HugePageAllocation, LargeArraysTakeNoMoreMemoryThanTheirSize) {
  if (!replaced) GTEST_SKIP() << "sanitizer build: operator new is the sanitizer's";
  const std::size_t values = (std::size_t{9} << 20) / 2 / sizeof(double);  // 4.5 MiB
  // A medium array first, as a model's point arrays come before its bonds: malloc grows its heap
  // by a reserve of 32 MiB, advised ahead, and the large arrays come from that reserve.
  const std::vector<double> medium(std::size_t{1} << 17, 0.5);
  std::vector<std::vector<double>> arrays;
  arrays.reserve(4);
  const std::uint64_t before = resident_bytes();
  for (int a = 0; a < 4; ++a) arrays.emplace_back(values, 1.0 + a);
  const std::uint64_t grown = resident_bytes() - before;
  const std::uint64_t size = 4 * values * sizeof(double);
  EXPECT_LT(grown, size + 2 * huge_page) << "resident growth " << grown / 1048576.0 << " MiB for " << size / 1048576.0
                                         << " MiB of arrays";
}

// A small model's arrays (here 256 KiB, a 16 000-point plate's) come from malloc's arenas, which
// are advised: on the main thread and on another (a thread's own arena), and the next one too (the
// advice reaches ahead of the allocation, since malloc writes beside a block before handing it out).
TEST(HugePageAllocation, MediumArraysLieInAdvisedArenas) {
  if (!replaced) GTEST_SKIP() << "sanitizer build: operator new is the sanitizer's";
  if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage"))
    GTEST_SKIP() << "this kernel has no transparent huge pages: the advice is refused, the memory is the same";
  const std::size_t values = std::size_t{32} << 10;
  auto check = [&](const char* where) {
    std::vector<double> first(values, 1.0), second(values, 2.0);
    for (const auto* v : {&first, &second})
      EXPECT_NE(vm_flags_at(v->data()).find(" hg"), std::string::npos) << where << ": " << vm_flags_at(v->data());
  };
  check("main thread");
  std::thread other([&] { check("another thread"); });
  other.join();
}

TEST(HugePageAllocation, SmallAllocationsAndTheirContentsAreUnchanged) {
  std::vector<double> small(100, 2.5);
  std::vector<double> large(std::size_t{3} << 20, 2.5);  // 24 MiB
  for (double v : small) ASSERT_EQ(v, 2.5);
  for (double v : large) ASSERT_EQ(v, 2.5);
  large.resize(std::size_t{4} << 20, -1.0);  // moves to a new block, kept by value
  EXPECT_EQ(large.front(), 2.5);
  EXPECT_EQ(large.back(), -1.0);
}

// operator new throws std::bad_alloc when the memory cannot be had (and no new-handler helps);
// the nothrow form returns null.
TEST(HugePageAllocation, ImpossibleAllocationsFailAsTheStandardSays) {
  const std::size_t impossible = std::numeric_limits<std::size_t>::max() / 4;
  EXPECT_THROW((void)::operator new(impossible), std::bad_alloc);
  EXPECT_EQ(::operator new(impossible, std::nothrow), nullptr);
  EXPECT_EQ(::operator new[](impossible, std::nothrow), nullptr);
}

}  // namespace
