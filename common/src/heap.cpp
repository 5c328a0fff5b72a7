#include "mrslam/common/heap.hpp"

#include <limits>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mrslam {

bool retainHeapForReuse(std::size_t mmap_threshold_bytes, std::size_t keep_bytes) {
#if defined(__GLIBC__)
  constexpr std::size_t kLargest = static_cast<std::size_t>(std::numeric_limits<int>::max());
  if (mmap_threshold_bytes > kLargest || keep_bytes > kLargest) {
    return false;  // mallopt takes an int
  }
  return mallopt(M_MMAP_THRESHOLD, static_cast<int>(mmap_threshold_bytes)) == 1 &&
         mallopt(M_TRIM_THRESHOLD, static_cast<int>(keep_bytes)) == 1;
#else
  (void)mmap_threshold_bytes;
  (void)keep_bytes;
  return false;
#endif
}

}  // namespace mrslam
