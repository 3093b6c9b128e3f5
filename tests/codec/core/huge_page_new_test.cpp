// The programs' operator new (codec/src/core/huge_page_new.cpp): blocks of
// a huge page or more start on a huge-page boundary in a mapping the kernel
// may back with huge pages; blocks from 64 KiB are present when new
// returns; small ones are plain malloc; the new_handler contract holds. Linked into this binary as into the programs.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "test_data.h"

namespace meshwave {
namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

bool ThpAdvisable() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(in, modes);
  return modes.find("[always]") != std::string::npos ||
         modes.find("[madvise]") != std::string::npos;
}

// The THPeligible line of /proc/self/smaps for the mapping holding `p`
// (-1 when not found).
int ThpEligible(const void* p) {
  const auto address = reinterpret_cast<std::uintptr_t>(p);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream head(line);
    if (head >> std::hex >> begin >> dash >> end && dash == '-') {
      inside = begin <= address && address < end;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0)
      return std::stoi(line.substr(12));
  }
  return -1;
}

#ifdef MESHWAVE_HUGE_PAGES_REPLACED_NEW
TEST(HugePageNewTest, LargeBlocksStartOnAHugePageInAnEligibleMapping) {
  if (!ThpAdvisable())
    GTEST_SKIP() << "transparent huge pages are off on this machine";
  std::vector<char> big(3 * kHugePage + 5, 1);  // not a multiple: rounded up
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % kHugePage, 0u);
  EXPECT_EQ(ThpEligible(big.data()), 1);
  EXPECT_EQ(big.back(), 1);  // usable to its last byte
}

// Whether this kernel takes MADV_POPULATE_WRITE (Linux 5.14).
bool KernelPopulates() {
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  void* p = ::mmap(nullptr, page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return false;
  const bool ok = ::madvise(p, page, 23 /* MADV_POPULATE_WRITE */) == 0;
  ::munmap(p, page);
  return ok;
}

TEST(HugePageNewTest, MidSizeBlocksArePresentBeforeTheirFirstTouch) {
  if (!KernelPopulates()) GTEST_SKIP() << "this kernel has no MADV_POPULATE_WRITE";
  const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  for (std::size_t size : {std::size_t{64} << 10, std::size_t{700} << 10, kHugePage - 8}) {
    char* block = static_cast<char*>(::operator new(size));
    // The whole pages inside the block, untouched by this test.
    const auto begin = (reinterpret_cast<std::uintptr_t>(block) + page - 1) / page * page;
    const auto end = (reinterpret_cast<std::uintptr_t>(block) + size) / page * page;
    std::vector<unsigned char> resident((end - begin) / page);
    ASSERT_EQ(::mincore(reinterpret_cast<void*>(begin), end - begin, resident.data()), 0);
    std::size_t present = 0;
    for (unsigned char r : resident) present += r & 1;
    EXPECT_EQ(present, resident.size()) << size;
    ::operator delete(block);
  }
}
#endif

TEST(HugePageNewTest, SmallBlocksAreOrdinaryAndFreedAlike) {
  for (int i = 0; i < 1000; ++i) {
    auto p = std::make_unique<int[]>(static_cast<std::size_t>(i) + 1);
    p[static_cast<std::size_t>(i)] = i;
    EXPECT_EQ(p[static_cast<std::size_t>(i)], i);
  }
  auto large =
      std::make_unique<double[]>(kHugePage);  // 16 MiB, freed by delete[]
  large[kHugePage - 1] = 2.5;
  EXPECT_EQ(large[kHugePage - 1], 2.5);
}

// An allocation that cannot succeed: the handler runs, then bad_alloc, or
// nullptr from the nothrow form.
TEST(HugePageNewTest, FailureCallsTheNewHandlerThenThrows) {
  // (A sanitizer's own operator new reports such a size and stops.)
  if (testing::kUnderSanitizer)
    GTEST_SKIP() << "the sanitizer's allocator refuses 2^62 bytes";
  static int calls = 0;
  calls = 0;
  std::set_new_handler([] {
    if (++calls == 3) std::set_new_handler(nullptr);
  });
  const std::size_t impossible = std::size_t{1} << 62;
  EXPECT_THROW(static_cast<void>(::operator new(impossible)), std::bad_alloc);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(::operator new(impossible, std::nothrow), nullptr);
}

}  // namespace
}  // namespace meshwave
