#pragma once
// Ctrl-C and SIGTERM as a flag that main loops poll.

#include <atomic>

namespace mrslam {

/// Installs SIGINT/SIGTERM handlers (once) and returns the flag they set.
const std::atomic<bool>& shutdownRequested();

}  // namespace mrslam
