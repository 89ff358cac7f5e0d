#include "base/huge_page_buffer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

namespace cutaway {
namespace {

// A buffer of at least a huge page starts on a huge-page boundary (so the kernel can map it
// 2 MiB at a time) and holds what is written to it; a small one is ordinary memory. Copies and
// growth work as with std::vector.
TEST(HugePageBuffer, LargeBuffersStartOnAHugePageAndHoldTheirContents) {
  HugePageVector<uint64_t> large(3 * kHugePageBytes / sizeof(uint64_t) + 5);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(large.data()) % kHugePageBytes, 0u);
  std::iota(large.begin(), large.end(), uint64_t{7});
  HugePageVector<uint64_t> copy = large;
  copy.push_back(1);  // grows past its capacity: a new block, the old one freed
  ASSERT_EQ(copy.size(), large.size() + 1);
  for (size_t i = 0; i < large.size(); ++i) ASSERT_EQ(copy[i], i + 7);

  HugePageVector<uint8_t> small(100, 3);
  EXPECT_EQ(small[99], 3);
  small.assign(kHugePageBytes, 1);  // from a small block to a large one
  EXPECT_EQ(reinterpret_cast<uintptr_t>(small.data()) % kHugePageBytes, 0u);
  EXPECT_EQ(small.back(), 1);
}

}  // namespace
}  // namespace cutaway
