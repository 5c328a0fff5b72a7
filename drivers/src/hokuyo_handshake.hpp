#pragma once
// The start-up exchange with a Hokuyo ranger (baud probe, SCIP 1.1 → 2.0 switch, VV, PP, II,
// TM time sync, BM). Private to the driver.

#include <functional>
#include <string>

#include "hokuyo_link.hpp"
#include "mrslam/common/result.hpp"
#include "mrslam/drivers/hokuyo_driver.hpp"

namespace mrslam::drivers {

/// Counts one problem: kind is a HokuyoCounters name ("timeout", "status", …).
using ProblemReporter = std::function<void(const std::string& kind, const std::string& reason)>;

/// Runs the start-up on an open link. Every problem is reported once; the failure's reason
/// is the one that stopped the start-up.
Result<HokuyoIdentity> runHandshake(HokuyoLink& link, const HokuyoSettings& settings,
                                    SensorClock& clock, const ProblemReporter& report);

}  // namespace mrslam::drivers
