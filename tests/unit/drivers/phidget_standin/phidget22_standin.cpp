// A stand-in for the vendor's libphidget22, built as a real shared library so the tests exercise
// the adapter's dlopen/dlsym code. It exports the functions the adapter uses with the signatures
// of phidget22.h and simulates one HighSpeed encoder board:
//   - serial number MRSLAM_PHIDGET_STANDIN_SERIAL (default 12345), channels 0..3, any hub port;
//   - MRSLAM_PHIDGET_STANDIN_ATTACH=fail: no board attaches (EPHIDGET_TIMEOUT);
//   - test hooks (mrslam_standin_*) move an input, which calls the position-change handler on
//     a thread of the library, as the real library does.
// Built with MRSLAM_STANDIN_WITHOUT_GET_POSITION it lacks PhidgetEncoder_getPosition.

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace {

constexpr int kOk = 0x0;            // EPHIDGET_OK
constexpr int kTimeout = 0x3;       // EPHIDGET_TIMEOUT
constexpr int kInvalidArg = 0x15;   // EPHIDGET_INVALIDARG
constexpr int kNotAttached = 0x34;  // EPHIDGET_NOTATTACHED
constexpr int kChannels = 4;

}  // namespace

extern "C" {

struct StandinChannel;
using PositionChangeHandler = void (*)(StandinChannel*, void*, int, double, int);

struct StandinChannel {
  std::int32_t serial_number = -1;
  int hub_port = -1;
  int channel = -1;
  bool attached = false;
  std::int64_t position = 0;
  std::uint32_t data_interval_ms = 256;
  PositionChangeHandler handler = nullptr;
  void* context = nullptr;
};

}  // extern "C"

namespace {

std::mutex registry_mutex;
std::set<StandinChannel*> live_channels;

int boardSerial() {
  const char* text = std::getenv("MRSLAM_PHIDGET_STANDIN_SERIAL");
  return text != nullptr ? std::atoi(text) : 12345;
}

bool attachRefused() {
  const char* text = std::getenv("MRSLAM_PHIDGET_STANDIN_ATTACH");
  return text != nullptr && std::strcmp(text, "fail") == 0;
}

bool isLive(StandinChannel* channel) {
  return channel != nullptr && live_channels.count(channel) > 0;
}

}  // namespace

extern "C" {

int PhidgetEncoder_create(StandinChannel** channel) {
  if (channel == nullptr) {
    return kInvalidArg;
  }
  std::lock_guard<std::mutex> lock(registry_mutex);
  *channel = new StandinChannel;
  live_channels.insert(*channel);
  return kOk;
}

int PhidgetEncoder_delete(StandinChannel** channel) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (channel == nullptr || !isLive(*channel)) {
    return kInvalidArg;
  }
  live_channels.erase(*channel);
  delete *channel;
  *channel = nullptr;
  return kOk;
}

int Phidget_setDeviceSerialNumber(StandinChannel* channel, std::int32_t serial_number) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->serial_number = serial_number;
  return kOk;
}

int Phidget_setHubPort(StandinChannel* channel, int hub_port) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->hub_port = hub_port;
  return kOk;
}

int Phidget_setChannel(StandinChannel* channel, int index) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->channel = index;
  return kOk;
}

int Phidget_openWaitForAttachment(StandinChannel* channel, std::uint32_t /*timeout_ms*/) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  const bool serial_matches =
      channel->serial_number == -1 || channel->serial_number == boardSerial();
  const bool channel_exists = channel->channel >= -1 && channel->channel < kChannels;
  if (attachRefused() || !serial_matches || !channel_exists) {
    return kTimeout;
  }
  channel->attached = true;
  return kOk;
}

int Phidget_close(StandinChannel* channel) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->attached = false;
  return kOk;
}

int PhidgetEncoder_setOnPositionChangeHandler(StandinChannel* channel,
                                              PositionChangeHandler handler, void* context) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->handler = handler;
  channel->context = context;
  return kOk;
}

#ifndef MRSLAM_STANDIN_WITHOUT_GET_POSITION
int PhidgetEncoder_getPosition(StandinChannel* channel, std::int64_t* position) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (!isLive(channel) || position == nullptr) {
    return kInvalidArg;
  }
  if (!channel->attached) {
    return kNotAttached;
  }
  *position = channel->position;
  return kOk;
}
#endif

int PhidgetEncoder_setDataInterval(StandinChannel* channel, std::uint32_t interval_ms) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  if (!channel->attached) {
    return kNotAttached;
  }
  if (interval_ms < 8 || interval_ms > 1000) {
    return kInvalidArg;
  }
  channel->data_interval_ms = interval_ms;
  return kOk;
}

int Phidget_getErrorDescription(int code, const char** text) {
  if (text == nullptr) {
    return kInvalidArg;
  }
  switch (code) {
    case kOk:
      *text = "Success";
      return kOk;
    case kTimeout:
      *text = "Timed Out";
      return kOk;
    case kInvalidArg:
      *text = "Invalid Argument";
      return kOk;
    case kNotAttached:
      *text = "Not Attached";
      return kOk;
    default:
      return kInvalidArg;
  }
}

// ---- test hooks ----

/// Moves input `index` of the board: calls the handler of the attached channel on a library
/// thread and waits for it. Returns 0, or -1 when no attached channel reads that input.
int mrslam_standin_move(int index, int position_change, double time_change_ms,
                        int index_triggered) {
  PositionChangeHandler handler = nullptr;
  void* context = nullptr;
  StandinChannel* target = nullptr;
  {
    std::lock_guard<std::mutex> lock(registry_mutex);
    for (StandinChannel* channel : live_channels) {
      if (channel->attached && channel->channel == index) {
        target = channel;
      }
    }
    if (target == nullptr) {
      return -1;
    }
    target->position += position_change;
    handler = target->handler;
    context = target->context;
  }
  if (handler != nullptr) {
    std::thread library_thread(
        [=] { handler(target, context, position_change, time_change_ms, index_triggered); });
    library_thread.join();
  }
  return 0;
}

/// Channel handles created and not yet deleted.
int mrslam_standin_live_handles() {
  std::lock_guard<std::mutex> lock(registry_mutex);
  return static_cast<int>(live_channels.size());
}

/// Channels attached now.
int mrslam_standin_attached_channels() {
  std::lock_guard<std::mutex> lock(registry_mutex);
  int count = 0;
  for (const StandinChannel* channel : live_channels) {
    count += channel->attached ? 1 : 0;
  }
  return count;
}

/// The data interval set on the attached channel reading input `index` (0: none).
unsigned mrslam_standin_data_interval(int index) {
  std::lock_guard<std::mutex> lock(registry_mutex);
  for (const StandinChannel* channel : live_channels) {
    if (channel->attached && channel->channel == index) {
      return channel->data_interval_ms;
    }
  }
  return 0;
}

}  // extern "C"
