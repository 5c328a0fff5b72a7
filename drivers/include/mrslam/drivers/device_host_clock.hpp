#pragma once
// The host clock device samples are stamped on (GX1, Phidget encoders): Unix-epoch nanoseconds
// that never go back: the system clock read once, advanced by the steady clock.

#include <chrono>

#include "mrslam/common/stamp.hpp"

namespace mrslam::drivers::device_clock {

inline Stamp hostNow() {
  using namespace std::chrono;
  static const system_clock::time_point system_start = system_clock::now();
  static const steady_clock::time_point steady_start = steady_clock::now();
  const auto since_epoch = system_start.time_since_epoch() + (steady_clock::now() - steady_start);
  return Stamp::fromNanoseconds(duration_cast<nanoseconds>(since_epoch).count());
}

}  // namespace mrslam::drivers::device_clock
