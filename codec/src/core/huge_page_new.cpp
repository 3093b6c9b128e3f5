// The global operator new of meshwave's programs (the CLI, the server, the
// benchmarks; never the libraries, which leave the allocator to their
// application): large blocks ask the kernel for transparent huge pages.
//
// Why: a mesh's arrays (positions, the hierarchy's tables, stencils,
// octrees, pyramids) are tens of megabytes, allocated fresh and touched
// once. With 4 KiB pages every 4 KiB of first touch is a page fault; on
// this project's virtual machines a page fault costs several microseconds
// (profiles of an encode and a decode showed 28-35 % of the time in the
// hypervisor's fault path). Debian's default THP mode is `madvise`: huge
// pages only where a program asks, which is what this does for blocks of
// 2 MiB or more (docs/BENCHMARKS.md, "Huge pages"). Blocks from 64 KiB up to
// that have their small pages faulted in by one madvise(MADV_POPULATE_WRITE)
// when allocated: a decode's 5,700 page faults became 820 and its CPU time
// fell by a third (bunny prefix, 139 -> 86 ms); such blocks are vectors
// about to be filled, so the pages populated are pages that were to be
// touched.
//
// The plain and array forms of new and delete are replaced, on malloc,
// aligned_alloc and free (so a tool that watches malloc sees pairs); the
// aligned forms stay the library's, which pair among themselves.
// Set MESHWAVE_HUGE_PAGES=0 in the environment to leave pages small and
// faulted in on first touch.
#include <sys/mman.h>

// Under ASan or TSan the sanitizer's own operator new stays (it checks
// new/delete pairing): this file is then empty.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MESHWAVE_SANITIZED_BUILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define MESHWAVE_SANITIZED_BUILD 1
#endif
#endif

#ifndef MESHWAVE_SANITIZED_BUILD

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;
// Blocks from this size up to a huge page have their small pages faulted in
// by one call rather than one fault per page.
constexpr std::size_t kPrefault = std::size_t{64} << 10;
constexpr std::size_t kSmallPage = std::size_t{4} << 10;
#ifndef MADV_POPULATE_WRITE
#define MADV_POPULATE_WRITE 23  // Linux 5.14; older kernels refuse it, harmlessly
#endif

bool HugePagesWanted() {
  static const bool wanted = [] {
    const char* v = std::getenv("MESHWAVE_HUGE_PAGES");
    return v == nullptr || v[0] != '0';
  }();
  return wanted;
}

// A block of a huge page or more starts on a huge-page boundary and is
// rounded up to whole huge pages (as glibc's own glibc.malloc.hugetlb=1
// does), so all of it can be backed by huge pages; free() takes it back
// like any aligned_alloc'd block. The rounding costs at most one huge
// page of memory per block, and only where it is touched.
void* TryAllocate(std::size_t n) {
  if (n >= kHugePage && HugePagesWanted()) {
    const std::size_t size = (n + kHugePage - 1) & ~(kHugePage - 1);
    void* p = std::aligned_alloc(kHugePage, size);
    // Advice only: where the kernel has no huge page to give it keeps small
    // ones.
    if (p != nullptr) ::madvise(p, size, MADV_HUGEPAGE);
    return p;
  }
  void* p = std::malloc(n == 0 ? 1 : n);
  if (p != nullptr && n >= kPrefault && HugePagesWanted()) {
    // The whole pages inside the block: its ends may share pages with
    // other blocks, which the advice would fault in too (harmless).
    const auto begin = (reinterpret_cast<std::uintptr_t>(p) + kSmallPage - 1) & ~(kSmallPage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(p) + n) & ~(kSmallPage - 1);
    if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
  }
  return p;
}

void* Allocate(std::size_t n) {
  for (;;) {
    if (void* p = TryAllocate(n)) return p;
    const std::new_handler handler = std::get_new_handler();
    if (handler == nullptr) return nullptr;
    handler();  // may free memory, throw, or end the program
  }
}

}  // namespace

void* operator new(std::size_t n) {
  if (void* p = Allocate(n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  if (void* p = Allocate(n)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return Allocate(n);
  } catch (...) {  // a new_handler that throws
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return Allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}

#endif  // MESHWAVE_SANITIZED_BUILD
