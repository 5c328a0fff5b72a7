// PhidgetEncoderSettings: checking, and reading from a config section.

#include <cmath>

#include "mrslam/common/config.hpp"
#include "mrslam/drivers/phidget_encoders.hpp"

namespace mrslam::drivers {

namespace {

PhidgetChannelSettings channelFromConfig(const Config& section, PhidgetChannelSettings s) {
  s.serial_number = static_cast<int>(section.getInt("serial_number", s.serial_number, {-1, 1e9}));
  s.hub_port = static_cast<int>(section.getInt("hub_port", s.hub_port, {-1, 64}));
  s.channel = static_cast<int>(section.getInt("channel", s.channel, {0, 64}));
  s.direction = static_cast<int>(section.getInt("direction", s.direction, {-1, 1}));
  if (s.direction == 0) {
    section.fail("direction", "must be 1 or -1");
  }
  return s;
}

bool sameInput(const PhidgetChannelSettings& a, const PhidgetChannelSettings& b) {
  return a.serial_number == b.serial_number && a.hub_port == b.hub_port && a.channel == b.channel;
}

}  // namespace

std::string PhidgetEncoderSettings::check() const {
  if (library_names.empty()) {
    return "library: no name given";
  }
  for (const auto* channel : {&left, &right}) {
    if (channel->direction != 1 && channel->direction != -1) {
      return "direction: must be 1 or -1";
    }
    if (channel->channel < 0) {
      return "channel: must not be negative";
    }
  }
  if (sameInput(left, right)) {
    return "left and right are the same encoder input";
  }
  if (attach_timeout.count() <= 0 || data_interval_ms < 0) {
    return "attach_timeout must be positive and data_interval_ms not negative";
  }
  return "";
}

PhidgetEncoderSettings PhidgetEncoderSettings::fromConfig(const Config& section) {
  PhidgetEncoderSettings s;
  if (section.has("library")) {
    s.library_names = {section.getExpandedString("library", "")};
  }
  const double timeout_s = section.getDouble("attach_timeout_s", 2.0, {0.001, 60.0});
  s.attach_timeout = std::chrono::milliseconds(std::llround(timeout_s * 1000.0));
  s.data_interval_ms =
      static_cast<int>(section.getInt("data_interval_ms", s.data_interval_ms, {0, 60000}));
  s.left = channelFromConfig(section.section("left"), s.left);
  s.right = channelFromConfig(section.section("right"), s.right);
  if (const std::string problem = s.check(); !problem.empty()) {
    section.fail("right", problem);
  }
  return s;
}

}  // namespace mrslam::drivers
