// The solver's global operator new (solver/huge_page_allocation.cpp): large allocations aligned to
// and advised for 2 MiB pages, medium ones in advised arenas, the contents as malloc gives them, and
// operator new's failure contract.
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

TEST(HugePageAllocation, LargeArraysAreAlignedAndAdvisedForHugePages) {
  if (!replaced) GTEST_SKIP() << "sanitizer build: operator new is the sanitizer's";
  std::vector<double> state(std::size_t{1} << 20, 0.0);  // 8 MiB, like a point-state array
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(state.data()) % huge_page, 0u);
  if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage"))
    GTEST_SKIP() << "this kernel has no transparent huge pages: the advice is refused, the memory is the same";
  // "hg": the mapping carries MADV_HUGEPAGE, whatever the system setting then grants.
  EXPECT_NE(vm_flags_at(state.data()).find(" hg"), std::string::npos) << vm_flags_at(state.data());
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
