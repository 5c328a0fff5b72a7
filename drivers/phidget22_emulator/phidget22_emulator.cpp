// An emulated Phidget HighSpeed encoder board behind the vendor's libphidget22 interface: a real
// shared library exporting the functions the adapter uses, with the signatures of phidget22.h,
// so the adapter's run-time loading (dlopen / dlsym) runs as on a robot.
//   - serial number MRSLAM_PHIDGET_EMULATOR_SERIAL (default 12345), channels 0..3, any hub port;
//   - MRSLAM_PHIDGET_EMULATOR_ATTACH=fail: no board attaches (EPHIDGET_TIMEOUT);
//   - MRSLAM_PHIDGET_EMULATOR_FEED=FILE: the inputs follow FILE, written by an emulated robot
//     (mrslam_emulated_robot): the board attaches only while FILE exists, and a thread of the
//     library reads it every data interval and reports each channel's change to its handler;
//   - test hooks (mrslam_phidget_emulator_*) move an input, which calls the position-change
//     handler on a thread of the library, as the real library does.
// Built with MRSLAM_PHIDGET_EMULATOR_WITHOUT_GET_POSITION it lacks PhidgetEncoder_getPosition.
//
// The feed file is text: the line `mrslam-phidget-feed 1`, then one line of the four inputs'
// cumulative positions; the writer replaces it atomically (rename).

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int kOk = 0x0;            // EPHIDGET_OK
constexpr int kTimeout = 0x3;       // EPHIDGET_TIMEOUT
constexpr int kInvalidArg = 0x15;   // EPHIDGET_INVALIDARG
constexpr int kNotAttached = 0x34;  // EPHIDGET_NOTATTACHED
constexpr int kChannels = 4;

}  // namespace

extern "C" {

struct EmulatedChannel;
using PositionChangeHandler = void (*)(EmulatedChannel*, void*, int, double, int);

struct EmulatedChannel {
  std::int32_t serial_number = -1;
  int hub_port = -1;
  int channel = -1;
  bool attached = false;
  std::int64_t position = 0;
  std::int64_t feed_base = 0;  ///< the feed's count of this input when the channel attached
  std::chrono::steady_clock::time_point last_change{};
  std::uint32_t data_interval_ms = 256;
  PositionChangeHandler handler = nullptr;
  void* context = nullptr;
};

}  // extern "C"

namespace {

using Clock = std::chrono::steady_clock;
using FeedCounts = std::array<std::int64_t, kChannels>;

// Never destroyed: the feed thread is detached and may run while the process exits.
std::mutex& registryMutex() {
  static auto* mutex = new std::mutex;
  return *mutex;
}
std::set<EmulatedChannel*>& liveChannels() {
  static auto* channels = new std::set<EmulatedChannel*>;
  return *channels;
}
// Held while the feed thread computes and delivers changes: Phidget_close waits on it, so no
// handler runs for a channel once its close has returned (as the vendor's library promises).
std::mutex& dispatchMutex() {
  static auto* mutex = new std::mutex;
  return *mutex;
}
bool feed_thread_running = false;  // guarded by registryMutex()
bool feed_present = true;          // guarded by registryMutex(): the feed file was readable

const char* feedPath() {
  return std::getenv("MRSLAM_PHIDGET_EMULATOR_FEED");
}

std::optional<FeedCounts> readFeed() {
  std::ifstream file(feedPath());
  std::string magic;
  int version = 0;
  FeedCounts counts{};
  if (!(file >> magic >> version) || magic != "mrslam-phidget-feed" || version != 1) {
    return std::nullopt;
  }
  for (std::int64_t& count : counts) {
    if (!(file >> count)) {
      return std::nullopt;
    }
  }
  return counts;
}

int boardSerial() {
  const char* text = std::getenv("MRSLAM_PHIDGET_EMULATOR_SERIAL");
  return text != nullptr ? std::atoi(text) : 12345;
}

bool attachRefused() {
  const char* text = std::getenv("MRSLAM_PHIDGET_EMULATOR_ATTACH");
  return text != nullptr && std::strcmp(text, "fail") == 0;
}

bool isLive(EmulatedChannel* channel) {
  return channel != nullptr && liveChannels().count(channel) > 0;
}

std::optional<FeedCounts> waitForFeed(std::chrono::milliseconds timeout) {
  const Clock::time_point deadline = Clock::now() + timeout;
  while (true) {
    if (std::optional<FeedCounts> counts = readFeed()) {
      return counts;
    }
    if (Clock::now() >= deadline) {
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

struct PendingChange {
  EmulatedChannel* channel;
  PositionChangeHandler handler;
  void* context;
  int change;
  double time_change_ms;
};

// Under registryMutex(): the changes of every attached channel since the feed was last read.
std::vector<PendingChange> takeFeedChanges(const std::optional<FeedCounts>& feed) {
  std::vector<PendingChange> changes;
  feed_present = feed.has_value();
  if (!feed) {
    return changes;
  }
  const Clock::time_point now = Clock::now();
  for (EmulatedChannel* channel : liveChannels()) {
    if (!channel->attached) {
      continue;
    }
    const std::int64_t target =
        (*feed)[static_cast<std::size_t>(channel->channel)] - channel->feed_base;
    const std::int64_t change = target - channel->position;
    if (change == 0) {
      continue;
    }
    channel->position = target;
    const double time_change_ms =
        std::chrono::duration<double, std::milli>(now - channel->last_change).count();
    channel->last_change = now;
    if (channel->handler != nullptr) {
      changes.push_back(
          {channel, channel->handler, channel->context, static_cast<int>(change), time_change_ms});
    }
  }
  return changes;
}

// Under registryMutex(): the shortest data interval of the attached channels (0: none attached).
std::uint32_t feedInterval() {
  std::uint32_t interval = 0;
  for (const EmulatedChannel* channel : liveChannels()) {
    if (channel->attached && (interval == 0 || channel->data_interval_ms < interval)) {
      interval = channel->data_interval_ms;
    }
  }
  return interval;
}

// The library's thread: reads the feed every data interval while a channel is attached. Handlers
// run on it outside the lock, as the real library's event thread calls them.
void runFeed() {
  while (true) {
    std::uint32_t interval = 0;
    {
      std::lock_guard<std::mutex> lock(registryMutex());
      interval = feedInterval();
      if (interval == 0) {
        feed_thread_running = false;
        return;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(interval));
    const std::optional<FeedCounts> feed = readFeed();
    std::lock_guard<std::mutex> dispatching(dispatchMutex());
    std::vector<PendingChange> changes;
    {
      std::lock_guard<std::mutex> lock(registryMutex());
      changes = takeFeedChanges(feed);
    }
    for (const PendingChange& pending : changes) {
      pending.handler(pending.channel, pending.context, pending.change, pending.time_change_ms, 0);
    }
  }
}

// Under registryMutex().
void startFeedThread() {
  if (!feed_thread_running) {
    feed_thread_running = true;
    std::thread(runFeed).detach();
  }
}

}  // namespace

extern "C" {

int PhidgetEncoder_create(EmulatedChannel** channel) {
  if (channel == nullptr) {
    return kInvalidArg;
  }
  std::lock_guard<std::mutex> lock(registryMutex());
  *channel = new EmulatedChannel;
  liveChannels().insert(*channel);
  return kOk;
}

int PhidgetEncoder_delete(EmulatedChannel** channel) {
  std::lock_guard<std::mutex> lock(registryMutex());
  if (channel == nullptr || !isLive(*channel)) {
    return kInvalidArg;
  }
  liveChannels().erase(*channel);
  delete *channel;
  *channel = nullptr;
  return kOk;
}

int Phidget_setDeviceSerialNumber(EmulatedChannel* channel, std::int32_t serial_number) {
  std::lock_guard<std::mutex> lock(registryMutex());
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->serial_number = serial_number;
  return kOk;
}

int Phidget_setHubPort(EmulatedChannel* channel, int hub_port) {
  std::lock_guard<std::mutex> lock(registryMutex());
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->hub_port = hub_port;
  return kOk;
}

int Phidget_setChannel(EmulatedChannel* channel, int index) {
  std::lock_guard<std::mutex> lock(registryMutex());
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->channel = index;
  return kOk;
}

int Phidget_openWaitForAttachment(EmulatedChannel* channel, std::uint32_t timeout_ms) {
  std::optional<FeedCounts> feed;
  if (feedPath() != nullptr) {
    feed = waitForFeed(std::chrono::milliseconds(timeout_ms));
    if (!feed) {
      return kTimeout;  // no emulated robot feeds this board: nothing attaches
    }
  }
  std::lock_guard<std::mutex> lock(registryMutex());
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  const bool serial_matches =
      channel->serial_number == -1 || channel->serial_number == boardSerial();
  const bool channel_exists = channel->channel >= 0 && channel->channel < kChannels;
  if (attachRefused() || !serial_matches || !channel_exists) {
    return kTimeout;
  }
  channel->attached = true;
  channel->last_change = Clock::now();
  if (feed) {
    channel->feed_base = (*feed)[static_cast<std::size_t>(channel->channel)];
    feed_present = true;
    startFeedThread();
  }
  return kOk;
}

int Phidget_close(EmulatedChannel* channel) {
  {
    std::lock_guard<std::mutex> lock(registryMutex());
    if (!isLive(channel)) {
      return kInvalidArg;
    }
    channel->attached = false;
  }
  std::lock_guard<std::mutex> delivered(dispatchMutex());  // no handler call is under way
  return kOk;
}

int PhidgetEncoder_setOnPositionChangeHandler(EmulatedChannel* channel,
                                              PositionChangeHandler handler, void* context) {
  std::lock_guard<std::mutex> lock(registryMutex());
  if (!isLive(channel)) {
    return kInvalidArg;
  }
  channel->handler = handler;
  channel->context = context;
  return kOk;
}

#ifndef MRSLAM_PHIDGET_EMULATOR_WITHOUT_GET_POSITION
int PhidgetEncoder_getPosition(EmulatedChannel* channel, std::int64_t* position) {
  std::lock_guard<std::mutex> lock(registryMutex());
  if (!isLive(channel) || position == nullptr) {
    return kInvalidArg;
  }
  if (!channel->attached || !feed_present) {
    return kNotAttached;
  }
  *position = channel->position;
  return kOk;
}
#endif

int PhidgetEncoder_setDataInterval(EmulatedChannel* channel, std::uint32_t interval_ms) {
  std::lock_guard<std::mutex> lock(registryMutex());
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
int mrslam_phidget_emulator_move(int index, int position_change, double time_change_ms,
                                 int index_triggered) {
  PositionChangeHandler handler = nullptr;
  void* context = nullptr;
  EmulatedChannel* target = nullptr;
  {
    std::lock_guard<std::mutex> lock(registryMutex());
    for (EmulatedChannel* channel : liveChannels()) {
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
int mrslam_phidget_emulator_live_handles() {
  std::lock_guard<std::mutex> lock(registryMutex());
  return static_cast<int>(liveChannels().size());
}

/// Channels attached now.
int mrslam_phidget_emulator_attached_channels() {
  std::lock_guard<std::mutex> lock(registryMutex());
  int count = 0;
  for (const EmulatedChannel* channel : liveChannels()) {
    count += channel->attached ? 1 : 0;
  }
  return count;
}

/// The data interval set on the attached channel reading input `index` (0: none).
unsigned mrslam_phidget_emulator_data_interval(int index) {
  std::lock_guard<std::mutex> lock(registryMutex());
  for (const EmulatedChannel* channel : liveChannels()) {
    if (channel->attached && channel->channel == index) {
      return channel->data_interval_ms;
    }
  }
  return 0;
}

}  // extern "C"
