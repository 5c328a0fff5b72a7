#pragma once
// Wheel encoders on a Phidget HighSpeed encoder board through the vendor's libphidget22,
// loaded at run time (dlopen): one binary runs with or without the library installed. Each
// wheel is one encoder channel (serial number, hub port, channel). The library calls a
// position-change handler on its own thread with (positionChange, timeChange in ms,
// indexTriggered); the adapter adds the changes up under a lock, times them on the host clock,
// and poll() hands out cumulative counts. Ticks → wheel travel is the platform's job
// (DiffDriveParams); the adapter only applies each wheel's direction sign.

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/result.hpp"
#include "mrslam/common/samples.hpp"

namespace mrslam {
class Config;
}

namespace mrslam::drivers {

namespace phidget {
struct Library;
}

struct PhidgetChannelSettings {
  int serial_number = -1;  ///< board serial number; -1: any (PHIDGET_SERIALNUMBER_ANY)
  int hub_port = -1;       ///< VINT hub port; -1: any (PHIDGET_HUBPORT_ANY)
  int channel = 0;         ///< encoder input on the board
  int direction = 1;       ///< +1 or -1: the sign that makes forward travel count up
};

struct PhidgetEncoderSettings {
  /// Tried in order with dlopen (names searched as the loader does, or paths).
  std::vector<std::string> library_names = {"libphidget22.so.0", "libphidget22.so"};
  PhidgetChannelSettings left{-1, -1, 0, 1};
  PhidgetChannelSettings right{-1, -1, 1, 1};
  std::chrono::milliseconds attach_timeout{2000};  ///< per channel
  int data_interval_ms = 8;  ///< PhidgetEncoder_setDataInterval; 0 keeps the board's default

  /// Reads a config section: library (a name or a list), attach_timeout_s, data_interval_ms,
  /// left and right: {serial_number, hub_port, channel, direction}.
  static PhidgetEncoderSettings fromConfig(const Config& section);
  /// Empty when usable, else what is wrong.
  std::string check() const;
};

enum class Wheel { kLeft = 0, kRight = 1 };

struct PhidgetEncoderCounters {
  std::array<std::uint64_t, 2> position_changes{};  ///< handler calls per wheel
  std::array<std::uint64_t, 2> index_triggers{};    ///< index pulses seen per wheel
  std::array<double, 2> device_time_s{};            ///< Σ timeChange per wheel (device clock)
};

class PhidgetEncoders {
 public:
  /// Loads the library, opens both channels and waits for them to attach. The failure reason
  /// says what is missing (library, symbol, device) so the caller can fall back.
  static Result<std::unique_ptr<PhidgetEncoders>> open(const PhidgetEncoderSettings& settings);
  /// Closes and deletes both channel handles (the library stays loaded: it keeps threads).
  ~PhidgetEncoders();
  PhidgetEncoders(const PhidgetEncoders&) = delete;
  PhidgetEncoders& operator=(const PhidgetEncoders&) = delete;

  /// Cumulative counts since open (direction applied) when they changed since the last call,
  /// stamped on the host clock at the latest position change.
  std::optional<WheelTicks> poll();
  /// Speed of the latest change of a wheel in counts/s (positionChange / timeChange), direction
  /// applied; 0 before the first change.
  double speedCountsPerSecond(Wheel wheel) const;
  /// The board's own position count (PhidgetEncoder_getPosition), without direction sign.
  std::optional<std::int64_t> devicePosition(Wheel wheel) const;
  PhidgetEncoderCounters counters() const;
  /// The library that was loaded (as named in the settings).
  const std::string& libraryName() const;

  // Internal, public only for the library's handler function.
  struct State;    ///< what the handler updates, under its lock
  struct Channel;  ///< one open channel handle; the handler's context

 private:
  PhidgetEncoders(std::shared_ptr<const phidget::Library> library, std::unique_ptr<State> state);
  /// Empty when the channel is open and attached, else why not.
  std::string openChannel(Wheel wheel, const PhidgetChannelSettings& channel,
                          const PhidgetEncoderSettings& settings);
  void closeChannel(Channel& channel);

  std::shared_ptr<const phidget::Library> library_;
  std::unique_ptr<State> state_;
  std::array<std::unique_ptr<Channel>, 2> channels_;
};

}  // namespace mrslam::drivers
