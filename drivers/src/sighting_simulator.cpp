#include "mrslam/drivers/sighting_simulator.hpp"

#include <cmath>

namespace mrslam::drivers {

namespace {

constexpr std::uint64_t kSightingSeedOffset = 0x5167'4e71'0000'0001ULL;  ///< own random stream

/// Advances a teammate's simulator until its latest sample is at `stamp` or later.
void advanceTo(Simulator& motion, Stamp stamp) {
  while (true) {
    const std::optional<Sample> sample = motion.next();
    if (!sample || !(stampOf(*sample) < stamp)) {
      return;
    }
  }
}

}  // namespace

SightingSettings loadSightingSettings(const Config& section) {
  SightingSettings settings;
  settings.max_range_m = section.getDouble("max_range_m", settings.max_range_m, {0.1, 100.0});
  settings.period_s = section.getDouble("period_s", settings.period_s, {0.0, 3600.0});
  settings.range_sigma_m = section.getDouble("range_sigma_m", settings.range_sigma_m, {0.0, 1.0});
  settings.bearing_sigma_rad =
      section.getDouble("bearing_sigma_rad", settings.bearing_sigma_rad, {0.0, 1.0});
  for (const Config& robot : section.sectionList("robots")) {
    SimulatedTeammate teammate;
    teammate.id = robot.requireString("id");
    if (!isValidRobotId(teammate.id)) {
      robot.fail("id", "'" + teammate.id + "' is not a robot id (1-64 of A-Z a-z 0-9 _ -)");
    }
    teammate.robot_index = static_cast<int>(
        robot.requireInt("robot_index", {0.0, static_cast<double>(kBuiltInRouteCount - 1)}));
    settings.robots.push_back(teammate);
  }
  return settings;
}

SightingSimulator::SightingSimulator(const SimulatorSettings& settings,
                                     const SightingSettings& sightings,
                                     const DiffDriveParams& drive, const SensorMounting& mounting)
    : robot_(settings, drive, mounting),
      settings_(sightings),
      rng_(settings.seed ^ kSightingSeedOffset) {
  for (const SimulatedTeammate& who : sightings.robots) {
    if (who.robot_index == settings.robot_index) {
      throw std::invalid_argument("simulator.sightings: robot " + who.id +
                                  " drives this robot's own route " +
                                  std::to_string(who.robot_index));
    }
    SimulatorSettings motion = settings;
    motion.robot_index = who.robot_index;
    motion.noise_enabled = false;
    motion.laser_rate_hz = 1.0;  // its scans are never used: cast as few rays as allowed
    teammates_.push_back({who, std::make_unique<Simulator>(motion, drive, mounting), {}, false});
  }
}

SightingSimulator::~SightingSimulator() = default;

std::optional<Sample> SightingSimulator::next() {
  if (!pending_.empty()) {
    const RobotSighting sighting = pending_.front();
    pending_.erase(pending_.begin());
    return sighting;
  }
  std::optional<Sample> sample = robot_.next();
  if (sample && std::holds_alternative<LaserScan>(*sample)) {
    lookForTeammates(stampOf(*sample));
  }
  return sample;
}

void SightingSimulator::lookForTeammates(Stamp stamp) {
  const SE2 T_world_robot = robot_.truePose();
  for (Teammate& teammate : teammates_) {
    if (teammate.seen && secondsBetween(teammate.last_seen, stamp) < settings_.period_s) {
      continue;
    }
    advanceTo(*teammate.motion, stamp);
    const Eigen::Vector2d p_world_other = teammate.motion->truePose().translation();
    if (!inSight(T_world_robot, p_world_other)) {
      continue;
    }
    const Eigen::Vector2d p_robot_other = T_world_robot.inverse() * p_world_other;
    std::normal_distribution<double> range_noise(0.0, settings_.range_sigma_m);
    std::normal_distribution<double> bearing_noise(0.0, settings_.bearing_sigma_rad);
    RobotSighting sighting;
    sighting.stamp = stamp;
    sighting.observed_id = teammate.who.id;
    sighting.range_m = p_robot_other.norm() + range_noise(rng_);
    sighting.bearing_rad =
        wrapAngle(std::atan2(p_robot_other.y(), p_robot_other.x()) + bearing_noise(rng_));
    pending_.push_back(sighting);
    teammate.seen = true;
    teammate.last_seen = stamp;
  }
}

bool SightingSimulator::inSight(const SE2& T_world_robot,
                                const Eigen::Vector2d& p_world_other) const {
  const Eigen::Vector2d offset = p_world_other - T_world_robot.translation();
  const double distance = offset.norm();
  if (distance > settings_.max_range_m || distance < 1e-6) {
    return false;
  }
  const double angle = std::atan2(offset.y(), offset.x());
  const std::optional<double> wall =
      robot_.floorPlan().castRay(T_world_robot.translation(), angle, distance);
  return !wall || *wall >= distance;
}

}  // namespace mrslam::drivers
