#include "route_follower.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace mrslam::drivers {
namespace {

constexpr double kReachedRadiusM = 0.05;   // a waypoint this close counts as reached
constexpr double kPassedRadiusM = 0.25;    // ... as does one passed by this close
constexpr double kCreepSpeedM_S = 0.03;    // least speed while closing in on a waypoint
constexpr double kHeadingCutoffRad = 0.6;  // drive only when facing the waypoint within this
constexpr double kTurnGain = 2.0;          // turn rate per radian of heading error (1/s)
constexpr double kPlanningShare = 0.5;     // share of the acceleration limits used for planning

double moveTowards(double value, double goal, double max_step) {
  return value + std::clamp(goal - value, -max_step, max_step);
}

}  // namespace

RouteFollower::RouteFollower(std::vector<Eigen::Vector2d> route, const MotionLimits& limits)
    : route_(std::move(route)), limits_(limits) {
  if (route_.size() < 2) {
    throw std::invalid_argument("RouteFollower: a route needs at least two waypoints");
  }
}

double RouteFollower::cornerSpeed() const {
  // Speed allowed at the target waypoint: full for a straight pass, none for a right angle.
  const Eigen::Vector2d& before = route_[(target_ + route_.size() - 1) % route_.size()];
  const Eigen::Vector2d& at = route_[target_];
  const Eigen::Vector2d& after = route_[(target_ + 1) % route_.size()];
  const Eigen::Vector2d in = at - before;
  const Eigen::Vector2d out = after - at;
  const double turn = std::abs(std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out)));
  return limits_.max_speed_m_s * std::clamp(1.0 - turn / (0.5 * M_PI), 0.0, 1.0);
}

VelocityCommand RouteFollower::update(const SE2& pose, const VelocityCommand& now, double dt) {
  const Eigen::Vector2d position = pose.translation();
  const Eigen::Vector2d& previous = route_[(target_ + route_.size() - 1) % route_.size()];
  const double distance = (route_[target_] - position).norm();
  const bool passed = (position - route_[target_]).dot(route_[target_] - previous) > 0.0;
  if (distance < kReachedRadiusM || (passed && distance < kPassedRadiusM)) {
    target_ = (target_ + 1) % route_.size();
  }

  const Eigen::Vector2d to_target = route_[target_] - position;
  const double remaining = to_target.norm();
  const double heading_error = wrapAngle(std::atan2(to_target.y(), to_target.x()) - pose.theta());

  // Turn rate: proportional, but never faster than a braking profile that stops on the heading.
  const double alpha = kPlanningShare * limits_.max_angular_acceleration_rad_s2;
  const double turn_rate =
      std::min({limits_.max_turn_rate_rad_s, kTurnGain * std::abs(heading_error),
                std::sqrt(2.0 * alpha * std::abs(heading_error))});
  const double omega_goal = std::copysign(turn_rate, heading_error);

  // Speed: brake so as to reach the waypoint at its corner speed; drive only when facing it.
  const double a = kPlanningShare * limits_.max_acceleration_m_s2;
  const double corner = cornerSpeed();
  const double approach =
      std::max(kCreepSpeedM_S,
               std::sqrt(corner * corner + 2.0 * a * std::max(0.0, remaining - kReachedRadiusM)));
  const double facing = std::clamp(1.0 - std::abs(heading_error) / kHeadingCutoffRad, 0.0, 1.0);
  const double v_goal = std::min(limits_.max_speed_m_s, approach) * facing;

  VelocityCommand next;
  next.v_m_s = moveTowards(now.v_m_s, v_goal, limits_.max_acceleration_m_s2 * dt);
  next.omega_rad_s =
      moveTowards(now.omega_rad_s, omega_goal, limits_.max_angular_acceleration_rad_s2 * dt);
  return next;
}

}  // namespace mrslam::drivers
