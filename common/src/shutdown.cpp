#include "mrslam/common/shutdown.hpp"

#include <csignal>

namespace mrslam {

namespace {

std::atomic<bool> g_shutdown{false};

extern "C" void onShutdownSignal(int) {
  g_shutdown.store(true);
}

}  // namespace

const std::atomic<bool>& shutdownRequested() {
  static const bool installed = [] {
    std::signal(SIGINT, onShutdownSignal);
    std::signal(SIGTERM, onShutdownSignal);
    return true;
  }();
  (void)installed;
  return g_shutdown;
}

}  // namespace mrslam
