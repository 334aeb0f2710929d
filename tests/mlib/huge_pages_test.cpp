// mlib::HugePageAllocator: large arrays start on a huge-page boundary and, on Linux with
// transparent huge pages not disabled, lie in memory the kernel may back with huge pages
// (read back from /proc/self/smaps); small arrays are ordinary allocations; a vector keeps
// its contents across growth from one kind to the other.
#include "mlib/huge_pages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

namespace mlib {
namespace {

struct alignas(64) Line {
  std::uint32_t word[16];
};

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

TEST(HugePages, LargeArraysStartOnAHugePageAndSmallOnesOnTheirAlignment) {
  HugePageAllocator<Line> alloc;
  const std::size_t large = kHugePageBytes / sizeof(Line) + 1;  // just over one huge page
  Line* big = alloc.allocate(large);
  EXPECT_EQ(address(big) % kHugePageBytes, 0u);
  big[0].word[0] = 1;  // the whole range is usable, to the last byte
  big[large - 1].word[15] = 2;
  EXPECT_EQ(big[0].word[0] + big[large - 1].word[15], 3u);
  alloc.deallocate(big, large);

  Line* small = alloc.allocate(3);
  EXPECT_EQ(address(small) % alignof(Line), 0u);
  small[2].word[15] = 7;
  EXPECT_EQ(small[2].word[15], 7u);
  alloc.deallocate(small, 3);
}

TEST(HugePages, VectorKeepsItsContentsGrowingPastTheThresholdAndBack) {
  HugePageVector<std::uint32_t> v;
  const std::size_t n = 3 * kHugePageBytes / sizeof(std::uint32_t);
  for (std::size_t i = 0; i < n; ++i) v.push_back(static_cast<std::uint32_t>(i * 2654435761u));
  EXPECT_EQ(address(v.data()) % kHugePageBytes, 0u);
  HugePageVector<std::uint32_t> copy = v;
  ASSERT_EQ(copy.size(), n);
  for (std::size_t i = 0; i < n; i += 4099)
    EXPECT_EQ(copy[i], static_cast<std::uint32_t>(i * 2654435761u));
  copy.resize(10);
  copy.shrink_to_fit();  // back to an ordinary allocation
  EXPECT_EQ(copy[9], 9u * 2654435761u);
}

#if defined(__linux__)
// The kernel's policy for transparent huge pages: "always", "madvise" or "never" (the
// bracketed word of /sys/kernel/mm/transparent_hugepage/enabled), or "" without THP.
std::string thp_policy() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(f, line);
  const auto open = line.find('['), close = line.find(']');
  if (open == std::string::npos || close == std::string::npos) return "";
  return line.substr(open + 1, close - open - 1);
}

// The THPeligible field of the mapping in /proc/self/smaps that holds p: 1 when the kernel
// may back it with huge pages, 0 when not, -1 when smaps does not say.
int thp_eligible(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    unsigned long lo, hi;
    char dash;
    std::istringstream head(line);
    if (head >> std::hex >> lo >> dash >> hi && dash == '-') {  // a mapping's first line
      inside = lo <= address(p) && address(p) < hi;
    } else if (inside && line.rfind("THPeligible:", 0) == 0) {
      return std::stoi(line.substr(12));
    }
  }
  return -1;
}

TEST(HugePages, LargeArraysAreEligibleForHugePagesWhereOrdinaryMemoryIsNot) {
  const std::string policy = thp_policy();
  if (policy != "madvise" && policy != "always")
    GTEST_SKIP() << "transparent huge pages are not enabled here (policy '" << policy << "')";
  HugePageVector<Line> tree(4 * kHugePageBytes / sizeof(Line));
  tree[0].word[0] = 1;
  if (thp_eligible(tree.data()) == -1) GTEST_SKIP() << "/proc/self/smaps has no THPeligible";
  EXPECT_EQ(thp_eligible(tree.data()), 1);
  if (policy == "madvise") {  // the oracle: the same size unadvised is not eligible
    std::vector<Line> plain(tree.size());
    plain[0].word[0] = 1;
    EXPECT_EQ(thp_eligible(plain.data()), 0);
  }
}
#endif

}  // namespace
}  // namespace mlib
