#include "hokuyo_handshake.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <vector>

#include "mrslam/drivers/scip_codec.hpp"

namespace mrslam::drivers {
namespace {

using scip::LineCheck;

bool linkLost(const CommandResult& result) {
  return result.link == SerialPort::Status::kDisconnected ||
         result.link == SerialPort::Status::kError;
}

std::vector<int> baudsToProbe(const HokuyoSettings& settings) {
  std::vector<int> bauds{settings.baud};
  for (const int baud : settings.probe_bauds) {
    if (std::find(bauds.begin(), bauds.end(), baud) == bauds.end()) {
      bauds.push_back(baud);
    }
  }
  return bauds;
}

struct ProbeOutcome {
  int baud = 0;
  bool switched_from_scip11 = false;
};

/// QT at each rate; where the answer is not SCIP 2.0, "SCIP2.0" and QT again.
Result<ProbeOutcome> probe(HokuyoLink& link, const HokuyoSettings& settings,
                           const ProblemReporter& report) {
  std::string tried;
  const std::uint64_t bytes_before = link.bytesReceived();
  for (const int baud : baudsToProbe(settings)) {
    tried += (tried.empty() ? "" : ", ") + std::to_string(baud);
    if (!link.setBaud(baud)) {
      continue;
    }
    link.discardInput();
    for (const bool switched : {false, true}) {
      if (switched) {
        link.command("SCIP2.0", LineCheck::kData, settings.read_timeout);
      }
      const CommandResult quit = link.command("QT", LineCheck::kData, settings.read_timeout);
      if (quit.parsed()) {
        return Result<ProbeOutcome>::success({baud, switched});
      }
      if (linkLost(quit)) {
        report("disconnect", link.error());
        return Result<ProbeOutcome>::failure("device lost while probing: " + link.error());
      }
    }
  }
  const bool silent = link.bytesReceived() == bytes_before;
  const std::string reason = "no SCIP 2.0 reply at " + tried + " baud: " +
                             (silent ? "the device does not answer"
                                     : "it answers with bytes that are not SCIP 2.0 (garbage)");
  report(silent ? "timeout" : "garbage", reason);
  return Result<ProbeOutcome>::failure(reason);
}

/// One command whose reply must parse and carry a success status.
Result<scip::Reply> exchange(HokuyoLink& link, const std::string& request, LineCheck check,
                             const HokuyoSettings& settings, const ProblemReporter& report) {
  CommandResult result = link.command(request, check, settings.read_timeout);
  std::string kind;
  std::string reason;
  if (result.link == SerialPort::Status::kTimeout) {
    kind = "timeout";
    reason = "no reply to " + request;
  } else if (linkLost(result)) {
    kind = "disconnect";
    reason = "device lost during " + request + ": " + link.error();
  } else if (!result.reply->ok()) {
    kind = scip::errorKindName(result.reply->error());
    reason = request + " reply: " + result.reply->reason();
  } else if (!scip::isSuccessStatus(request.substr(0, 2), result.reply->value().status)) {
    const std::string& status = result.reply->value().status;
    kind = "status";
    reason = request + " status " + status + ": " + scip::statusText(request.substr(0, 2), status);
  } else {
    return Result<scip::Reply>::success(std::move(result.reply->value()));
  }
  report(kind, reason);
  return Result<scip::Reply>::failure(reason);
}

Result<scip::KeyValues> queryKeyValues(HokuyoLink& link, const std::string& request,
                                       const HokuyoSettings& settings,
                                       const ProblemReporter& report) {
  auto reply = exchange(link, request, LineCheck::kKeyValue, settings, report);
  if (!reply) {
    return Result<scip::KeyValues>::failure(reply.reason());
  }
  auto values = scip::parseKeyValues(reply.value());
  if (!values) {
    report(scip::errorKindName(values.error()), request + ": " + values.reason());
    return Result<scip::KeyValues>::failure(request + ": " + values.reason());
  }
  return Result<scip::KeyValues>::success(std::move(values.value()));
}

/// TM0, TM1 × rounds (each a round trip for the clock), TM2. False when unsupported.
bool synchroniseTime(HokuyoLink& link, const HokuyoSettings& settings, SensorClock& clock) {
  if (settings.time_sync_round_trips <= 0) {
    return false;
  }
  const ProblemReporter quiet = [](const std::string&, const std::string&) {};
  if (!exchange(link, "TM0", LineCheck::kData, settings, quiet)) {
    spdlog::info("hokuyo {}: no TM time sync; stamps from scans only", settings.device);
    return false;
  }
  bool synchronised = false;
  for (int round = 0; round < settings.time_sync_round_trips; ++round) {
    const CommandResult result = link.command("TM1", LineCheck::kData, settings.read_timeout);
    if (!result.parsed() || result.reply->value().status != "00" ||
        result.reply->value().data.size() != 1) {
      continue;
    }
    if (const auto raw = scip::decode(result.reply->value().data[0])) {
      clock.addRoundTrip(*raw, result.sent, result.received);
      synchronised = true;
    }
  }
  exchange(link, "TM2", LineCheck::kData, settings, quiet);
  return synchronised;
}

}  // namespace

Result<HokuyoIdentity> runHandshake(HokuyoLink& link, const HokuyoSettings& settings,
                                    SensorClock& clock, const ProblemReporter& report) {
  const auto probed = probe(link, settings, report);
  if (!probed) {
    return Result<HokuyoIdentity>::failure(probed.reason());
  }
  HokuyoIdentity identity;
  identity.baud = probed.value().baud;
  identity.switched_from_scip11 = probed.value().switched_from_scip11;
  auto version = queryKeyValues(link, "VV", settings, report);
  auto parameters = version ? queryKeyValues(link, "PP", settings, report) : version;
  if (!parameters) {
    return Result<HokuyoIdentity>::failure(parameters.reason());
  }
  auto geometry = scip::ScanGeometry::fromParameters(parameters.value());
  if (!geometry) {
    report(scip::errorKindName(geometry.error()), geometry.reason());
    return Result<HokuyoIdentity>::failure(geometry.reason());
  }
  identity.version = std::move(version.value());
  identity.parameters = std::move(parameters.value());
  identity.geometry = geometry.value();
  const ProblemReporter quiet = [](const std::string&, const std::string&) {};
  if (auto state = queryKeyValues(link, "II", settings, quiet)) {
    identity.state = std::move(state.value());
  }
  clock.reset();
  identity.time_synchronised = synchroniseTime(link, settings, clock);
  const auto laser_on = exchange(link, "BM", LineCheck::kData, settings, report);
  if (!laser_on) {
    return Result<HokuyoIdentity>::failure(laser_on.reason());
  }
  return Result<HokuyoIdentity>::success(std::move(identity));
}

}  // namespace mrslam::drivers
