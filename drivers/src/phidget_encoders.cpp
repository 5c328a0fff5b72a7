// The Phidget encoder adapter: two channel handles, a handler that adds position changes up.

#include "mrslam/drivers/phidget_encoders.hpp"

#include <spdlog/spdlog.h>

#include <mutex>

#include "mrslam/drivers/device_host_clock.hpp"
#include "phidget_library.hpp"

namespace mrslam::drivers {

/// What the position-change handler updates, from the library's thread.
struct PhidgetEncoders::State {
  mutable std::mutex mutex;
  std::array<std::int64_t, 2> counts{};  ///< direction applied
  std::array<double, 2> speed{};         ///< counts/s of the latest change
  PhidgetEncoderCounters counters;
  bool changed = false;
  Stamp last_change;
};

struct PhidgetEncoders::Channel {
  phidget::EncoderHandle handle = nullptr;
  State* state = nullptr;
  int index = 0;  ///< 0 left, 1 right
  int direction = 1;
  std::string name;  ///< for messages: "left encoder (serial any, hub port any, channel 0)"
};

namespace {

void onPositionChange(phidget::EncoderHandle /*channel*/, void* context, int position_change,
                      double time_change_ms, int index_triggered) {
  const auto* channel = static_cast<const PhidgetEncoders::Channel*>(context);
  PhidgetEncoders::State& state = *channel->state;
  const int i = channel->index;
  const std::int64_t change = static_cast<std::int64_t>(channel->direction) * position_change;
  const Stamp now = device_clock::hostNow();
  std::lock_guard<std::mutex> lock(state.mutex);
  state.counts[i] += change;
  if (time_change_ms > 0.0) {
    state.speed[i] = static_cast<double>(change) / (time_change_ms / 1000.0);
    state.counters.device_time_s[i] += time_change_ms / 1000.0;
  }
  ++state.counters.position_changes[i];
  state.counters.index_triggers[i] += index_triggered != 0 ? 1 : 0;
  state.changed = true;
  state.last_change = now;
}

std::string anyOr(int value) {
  return value < 0 ? "any" : std::to_string(value);
}

std::string channelName(Wheel wheel, const PhidgetChannelSettings& settings) {
  return std::string(wheel == Wheel::kLeft ? "left" : "right") + " encoder (serial " +
         anyOr(settings.serial_number) + ", hub port " + anyOr(settings.hub_port) + ", channel " +
         std::to_string(settings.channel) + ")";
}

}  // namespace

Result<std::unique_ptr<PhidgetEncoders>> PhidgetEncoders::open(
    const PhidgetEncoderSettings& settings) {
  using Opened = Result<std::unique_ptr<PhidgetEncoders>>;
  if (const std::string problem = settings.check(); !problem.empty()) {
    return Opened::failure("Phidget encoder settings: " + problem);
  }
  auto library = phidget::loadLibrary(settings.library_names);
  if (!library) {
    return Opened::failure(library.reason());
  }
  std::unique_ptr<PhidgetEncoders> encoders(
      new PhidgetEncoders(library.value(), std::make_unique<State>()));
  for (const Wheel wheel : {Wheel::kLeft, Wheel::kRight}) {
    const auto& channel = wheel == Wheel::kLeft ? settings.left : settings.right;
    if (const std::string problem = encoders->openChannel(wheel, channel, settings);
        !problem.empty()) {
      return Opened::failure(problem);  // the destructor closes what was opened
    }
  }
  spdlog::info("Phidget encoders: {} and {} attached ({})", encoders->channels_[0]->name,
               encoders->channels_[1]->name, encoders->library_->name);
  return Opened::success(std::move(encoders));
}

PhidgetEncoders::PhidgetEncoders(std::shared_ptr<const phidget::Library> library,
                                 std::unique_ptr<State> state)
    : library_(std::move(library)), state_(std::move(state)) {}

PhidgetEncoders::~PhidgetEncoders() {
  for (auto& channel : channels_) {
    if (channel) {
      closeChannel(*channel);
    }
  }
}

std::string PhidgetEncoders::openChannel(Wheel wheel, const PhidgetChannelSettings& settings,
                                         const PhidgetEncoderSettings& all) {
  const phidget::Library& api = *library_;
  auto channel = std::make_unique<Channel>();
  channel->state = state_.get();
  channel->index = static_cast<int>(wheel);
  channel->direction = settings.direction;
  channel->name = channelName(wheel, settings);
  if (const auto code = api.encoder_create(&channel->handle); code != phidget::kOk) {
    return channel->name + ": PhidgetEncoder_create failed: " + api.describe(code);
  }
  Channel& c = *channel;
  channels_[static_cast<std::size_t>(wheel)] = std::move(channel);
  const phidget::Handle base = phidget::asPhidget(c.handle);
  phidget::ReturnCode code = api.set_device_serial_number(base, settings.serial_number);
  code = code != phidget::kOk ? code : api.set_hub_port(base, settings.hub_port);
  code = code != phidget::kOk ? code : api.set_channel(base, settings.channel);
  code = code != phidget::kOk ? code
                              : api.set_on_position_change_handler(c.handle, &onPositionChange, &c);
  if (code != phidget::kOk) {
    return c.name + ": cannot configure: " + api.describe(code);
  }
  const auto timeout_ms = static_cast<std::uint32_t>(all.attach_timeout.count());
  if (const auto attach = api.open_wait_for_attachment(base, timeout_ms); attach != phidget::kOk) {
    return c.name + ": no device attached within " + std::to_string(timeout_ms) +
           " ms: " + api.describe(attach);
  }
  if (all.data_interval_ms > 0) {
    const auto interval = static_cast<std::uint32_t>(all.data_interval_ms);
    if (const auto set = api.set_data_interval(c.handle, interval); set != phidget::kOk) {
      spdlog::warn("Phidget {}: data interval {} ms refused: {}", c.name, interval,
                   api.describe(set));
    }
  }
  return "";
}

void PhidgetEncoders::closeChannel(Channel& channel) {
  const phidget::Library& api = *library_;
  if (channel.handle == nullptr) {
    return;
  }
  api.set_on_position_change_handler(channel.handle, nullptr, nullptr);
  api.close(phidget::asPhidget(channel.handle));  // no handler call after close returns
  api.encoder_delete(&channel.handle);
  channel.handle = nullptr;
}

std::optional<WheelTicks> PhidgetEncoders::poll() {
  std::lock_guard<std::mutex> lock(state_->mutex);
  if (!state_->changed) {
    return std::nullopt;
  }
  state_->changed = false;
  WheelTicks ticks;
  ticks.stamp = state_->last_change;
  ticks.left = state_->counts[0];
  ticks.right = state_->counts[1];
  return ticks;
}

double PhidgetEncoders::speedCountsPerSecond(Wheel wheel) const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->speed[static_cast<std::size_t>(wheel)];
}

std::optional<std::int64_t> PhidgetEncoders::devicePosition(Wheel wheel) const {
  const Channel& channel = *channels_[static_cast<std::size_t>(wheel)];
  std::int64_t position = 0;
  if (library_->get_position(channel.handle, &position) != phidget::kOk) {
    return std::nullopt;
  }
  return position;
}

PhidgetEncoderCounters PhidgetEncoders::counters() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->counters;
}

const std::string& PhidgetEncoders::libraryName() const {
  return library_->name;
}

}  // namespace mrslam::drivers
