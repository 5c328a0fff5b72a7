#include "mrslam/common/heap.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mrslam {
namespace {

#if defined(__GLIBC__)
// A freed 4 MiB block (above glibc's default 128 KiB mmap threshold) stays in the heap: the heap
// grows by it, and after it is freed the memory is still the heap's, ready for the next one.
TEST(Heap, FreedLargeBlockStaysInTheHeap) {
  ASSERT_TRUE(retainHeapForReuse());
  constexpr std::size_t kBlock = std::size_t{4} << 20;
  const struct mallinfo2 before = mallinfo2();
  {
    std::unique_ptr<char[]> block(new char[kBlock]);
    std::memset(block.get(), 1, kBlock);
    const struct mallinfo2 holding = mallinfo2();
    EXPECT_EQ(holding.hblkhd, before.hblkhd) << "the block was mapped apart from the heap";
    EXPECT_GE(holding.arena, before.arena + kBlock - before.fordblks);
  }
  const struct mallinfo2 after = mallinfo2();
  EXPECT_GE(after.fordblks, kBlock) << "the freed block went back to the kernel";
}
#endif

TEST(Heap, RefusesSettingsTheLibraryCannotHold) {
  EXPECT_FALSE(retainHeapForReuse(std::size_t{1} << 40, std::size_t{1} << 20));
  EXPECT_FALSE(retainHeapForReuse(std::size_t{1} << 20, std::size_t{1} << 40));
}

}  // namespace
}  // namespace mrslam
