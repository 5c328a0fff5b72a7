#pragma once
// The process heap tuned for programs that merge maps again and again (fusion agent, merge tools,
// benchmarks).

#include <cstddef>

namespace mrslam {

/// Keeps freed memory in the process heap for the next allocation of the same size.
///
/// A map merge allocates and frees the same large images and cell lists (0.1–1 MB each for a
/// 400 × 400 map) every time it runs. glibc serves blocks above 128 KiB by mmap and gives them back
/// to the kernel when freed, and trims the heap's top, so every merge faults the same pages in
/// again. This serves blocks below `mmap_threshold_bytes` from the heap and keeps up to
/// `keep_bytes` of freed memory at the heap's top. Returns false (and changes nothing) where the C
/// library has no such setting.
bool retainHeapForReuse(std::size_t mmap_threshold_bytes = std::size_t{32} << 20,
                        std::size_t keep_bytes = std::size_t{512} << 20);

}  // namespace mrslam
