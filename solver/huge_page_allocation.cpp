// Large and medium allocations on transparent huge pages: the replaceable global operator new and delete of
// the programs that link this file (mppm-solve and the solver's unit tests).
//
// Why. The solver's arrays (the points' state, the bonds) are written once at start-up, and each
// 4 KiB page's first write is a page fault. On the 3-D benchmark block (216 000 points, 170 MB of
// point state) the phase that fills the point state took 0.40 s of a 1.78 s start-up on the
// virtual machine where mppm is built and tested, nearly all of it in these faults. A 2 MiB page
// takes one fault for 512. Linux gives an allocation huge pages when it asks (madvise
// MADV_HUGEPAGE; the system setting "madvise" or "always"), and
// glibc's malloc asks only when the environment sets the tunable glibc.malloc.hugetlb=1, which a
// user should not have to know. So allocations of at least 4 MiB are advised here, medium ones share
// advised arenas (below), and small ones are malloc's as before. Nothing else changes: the memory
// is still malloc's, freed by free, and its contents and the results are the same bits. Where the
// system does not give huge pages (the setting "never"), the advice is ignored.
//
// A large block is not aligned to 2 MiB: the kernel gives a huge page to every aligned 2 MiB span
// inside an advised range, wherever the block starts, and an aligned block would leave a gap of up
// to 2 MiB before it in malloc's heap (where a large block comes from while the heap's reserve
// holds it), a free chunk whose header, written by malloc, made the whole span resident: on a
// 64 000-point plate 2.8 MiB more peak memory than without huge pages, 3-5 MiB on a 68 000-point
// 3-D block, beyond the memory estimate's program share.
//
// Sanitizer builds keep the sanitizer's own operator new, which checks new/delete pairing.
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t huge_page_bytes = std::size_t{2} << 20;
// A block below two huge pages holds at most one aligned 2 MiB span.
constexpr std::size_t large_allocation_bytes = 2 * huge_page_bytes;

// Medium allocations (64 KiB up to the large ones: a small model's arrays, a reader's buffers)
// share huge pages in malloc's arenas: the main heap and the threads' heaps. malloc is told to
// serve them there (by default it maps each one above 128 KiB on its own, and a mapping freed and
// made again is faulted in again, page by page), to keep what is freed, and to grow the main heap
// by whole huge pages; and the arena around each one is advised. The advice must come before a
// page is first written (a 2 MiB span with one 4 KiB page in it stays in 4 KiB pages), and malloc
// writes its bookkeeping beside a block before handing it out: so the advice reaches ahead, over
// the rest of the arena's 64 MiB (a thread's heap is a 64 MiB-aligned reservation of that size),
// where the next allocations will come from. Only mapped memory takes the advice.
constexpr std::size_t medium_allocation_bytes = std::size_t{64} << 10;
constexpr std::uintptr_t arena_bytes = std::uintptr_t{64} << 20;

const bool malloc_set = [] {
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(large_allocation_bytes));
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mallopt(M_TOP_PAD, 32 << 20);
  return true;
}();

void advise_arena_around(const void* block) noexcept {
  const auto at = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t from = at & ~(std::uintptr_t{huge_page_bytes} - 1);
  const std::uintptr_t to = (at & ~(arena_bytes - 1)) + arena_bytes;
  (void)madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE);
}

// The pages of a large block (madvise takes a page-aligned start: the block's first page may hold
// malloc's header and the end of another block, which the advice does not change).
void advise_block(const void* block, std::size_t bytes) noexcept {
  // (asked here: an allocation may come before this file's static initialisation)
  const auto page_bytes = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto at = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t from = at & ~(page_bytes - 1);
  (void)madvise(reinterpret_cast<void*>(from), at + bytes - from, MADV_HUGEPAGE);
}

void* allocate_once(std::size_t bytes) noexcept {
  void* block = std::malloc(bytes == 0 ? 1 : bytes);
  if (!block) return nullptr;
  // Advice only: a system without huge pages refuses it, and the block is as good.
  if (bytes >= large_allocation_bytes)
    advise_block(block, bytes);
  else if (bytes >= medium_allocation_bytes)
    advise_arena_around(block);
  return block;
}

// operator new's contract: call the new-handler until the allocation succeeds or there is none.
void* allocate(std::size_t bytes) {
  for (;;) {
    if (void* block = allocate_once(bytes)) return block;
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void* allocate_or_null(std::size_t bytes) noexcept {
  try {
    return allocate(bytes);
  } catch (...) {
    return nullptr;
  }
}

}  // namespace

void* operator new(std::size_t bytes) { return allocate(bytes); }
void* operator new[](std::size_t bytes) { return allocate(bytes); }
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept { return allocate_or_null(bytes); }
void* operator new[](std::size_t bytes, const std::nothrow_t&) noexcept { return allocate_or_null(bytes); }

void operator delete(void* block) noexcept { std::free(block); }
void operator delete[](void* block) noexcept { std::free(block); }
void operator delete(void* block, std::size_t) noexcept { std::free(block); }
void operator delete[](void* block, std::size_t) noexcept { std::free(block); }
void operator delete(void* block, const std::nothrow_t&) noexcept { std::free(block); }
void operator delete[](void* block, const std::nothrow_t&) noexcept { std::free(block); }

#endif
