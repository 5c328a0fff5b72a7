#pragma once
// The built-in simulator: a differential-drive robot follows one of three built-in routes through
// the built-in building (builtInFloorPlan) and its laser, wheel encoders and IMU are simulated
// with seeded noise. It is a SampleSource like a log reader, so the robot pipeline cannot tell.
//
// How a sample is made:
//  1. Motion: a waypoint follower commands (v, ω) at 100 Hz, limited in speed, turn rate and
//     acceleration, slowing for turns; between commands the true pose moves along an exact arc.
//  2. Laser (Hokuyo figures of the seed paper): 513 beams 0.36° apart centred on the laser's x
//     axis, each a ray cast from the true laser pose, plus Gaussian range noise.
//  3. Wheel encoders: the true wheel rotations times a per-wheel scale error, plus per-step slip
//     noise, accumulated as fractional counts and emitted as whole cumulative ticks.
//  4. IMU: yaw = true heading in the world frame + mounting.imu_yaw_offset_rad + noise; yaw rate
//     = true turn rate + constant bias + noise; level attitude; gravity plus the true forward and
//     centripetal acceleration, all in the IMU's frame.
// Samples come in time order; at equal stamps: wheel ticks, then IMU, then laser.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "mrslam/common/config.hpp"
#include "mrslam/common/platform.hpp"
#include "mrslam/common/samples.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/drivers/floor_plan.hpp"
#include "mrslam/drivers/sample_source.hpp"

namespace mrslam::drivers {

class RouteFollower;

/// Number of built-in routes (robot indices 0 … kBuiltInRouteCount − 1).
constexpr int kBuiltInRouteCount = 3;
/// Radius of the simulated robot's footprint: the routes keep at least this clearance to walls.
constexpr double kSimulatedRobotRadiusM = 0.25;

/// The simulated laser (Hokuyo as in the seed paper): beam i points at kLaserAngleMinRad + i·inc.
constexpr int kLaserBeamCount = 513;
constexpr double kLaserAngleIncrementRad = 0.36 * M_PI / 180.0;
constexpr double kLaserAngleMinRad = -256 * kLaserAngleIncrementRad;
constexpr double kLaserRangeMinM = 0.02;
constexpr double kLaserRangeMaxM = 4.5;

/// The built-in routes (corridor centre line y = 5.1; rooms circled round their furniture):
///  0: starts in the west corridor at (2.05, 5.1) facing east; corridor → S2 → back west → N1.
///  1: starts in the east corridor at (15.45, 5.1) facing west; corridor → N3 → back east → S3.
///  2: starts in room N2 at (7.9, 7.5) facing north; N2 → corridor east → N4 → back west → N2.
/// Waypoints of a built-in route in the world frame of builtInFloorPlan(): a closed loop (after
/// the last waypoint the robot heads for the first again), starting at the first. Throws
/// std::invalid_argument for a robot index outside 0…2.
std::vector<Eigen::Vector2d> builtInRoute(int robot);
/// The true start pose T_world_robot of a built-in route: at its first waypoint, facing the next.
SE2 builtInStartPose(int robot);

struct SimulatorSettings {
  int robot_index = 0;        ///< built-in route to drive: 0, 1 or 2
  std::uint64_t seed = 1;     ///< seed of every random draw of this simulator
  double duration_s = 60.0;   ///< simulated time: samples are stamped in [start, start + this)
  double start_time_s = 0.0;  ///< stamp of the first samples
  bool noise_enabled = true;  ///< false: ideal sensors (no noise, bias, scale error or slip)

  double max_speed_m_s = 0.4;                    ///< top forward speed
  double max_turn_rate_rad_s = 1.0;              ///< top turn rate
  double max_acceleration_m_s2 = 0.5;            ///< forward acceleration and braking limit
  double max_angular_acceleration_rad_s2 = 3.0;  ///< turn-rate change limit

  double laser_rate_hz = 10.0;        ///< scans per second
  double laser_range_sigma_m = 0.01;  ///< σ of the Gaussian range noise

  double encoder_rate_hz = 50.0;       ///< wheel tick readings per second
  double encoder_scale_sigma = 0.002;  ///< σ of each wheel's constant scale error (0.002 = 0.2 %)
  double encoder_slip_sigma = 0.03;    ///< σ of each reading's slip, as a fraction of its rotation

  double imu_rate_hz = 50.0;                ///< IMU readings per second
  double imu_yaw_sigma_rad = 0.01;          ///< σ of the heading noise
  double imu_rate_sigma_rad_s = 0.005;      ///< σ of the angular rate noise (each axis)
  double imu_rate_bias_rad_s = 0.002;       ///< constant bias of the yaw rate
  double imu_tilt_sigma_rad = 0.002;        ///< σ of the roll and pitch noise
  double imu_acceleration_sigma_g = 0.005;  ///< σ of the acceleration noise (each axis)
};

/// Reads the `simulator:` section (keys = the field names above); every value is range-checked
/// and a bad one throws ConfigError `file:line: simulator.key: what is wrong`.
SimulatorSettings loadSimulatorSettings(const Config& section);
/// Throws std::invalid_argument naming the first setting outside the range the loader allows.
void checkSimulatorSettings(const SimulatorSettings& settings);

class Simulator : public SampleSource {
 public:
  /// Throws std::invalid_argument for settings or parameters that make no sense (the checks of
  /// loadSimulatorSettings, for settings built in code).
  Simulator(const SimulatorSettings& settings, const DiffDriveParams& drive,
            const SensorMounting& mounting);
  ~Simulator() override;
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// The next sample. Laser scans carry the TRUE robot pose T_world_robot in logged_pose (ground
  /// truth for tests and evaluation; the laser sits at mounting.T_robot_laser on the robot).
  std::optional<Sample> next() override;
  /// E.g. "simulator robot 1 (seed 7, 60 s)".
  std::string describe() const override;
  SourceCounters counters() const override { return counters_; }
  /// Simulated time so far over the run's duration.
  std::optional<double> progress() const override;

  const FloorPlan& floorPlan() const { return plan_; }
  /// The true pose T_world_robot at the stamp of the latest sample.
  SE2 truePose() const { return truth_.pose; }

 private:
  /// The robot's true motion; wheel angles are cumulative (radians).
  struct TrueState {
    SE2 pose;
    double v_m_s = 0.0;
    double omega_rad_s = 0.0;
    double acceleration_m_s2 = 0.0;  ///< forward acceleration of the latest command change
    double left_wheel_rad = 0.0;
    double right_wheel_rad = 0.0;
  };
  /// One periodic sensor: its k-th sample is stamped start + round(k / rate).
  struct Stream {
    double rate_hz = 0.0;
    std::int64_t count = 0;
    std::int64_t next_ns = 0;
  };
  /// What the encoders carry from one reading to the next.
  struct EncoderState {
    double left_scale = 1.0;
    double right_scale = 1.0;
    double left_counts = 0.0;  ///< cumulative counts with their fractional remainder
    double right_counts = 0.0;
    double left_wheel_rad = 0.0;  ///< true wheel angles at the previous reading
    double right_wheel_rad = 0.0;
  };

  void advanceTo(std::int64_t t_ns);
  void integrate(double dt);
  void schedule(Stream& stream) const;

  LaserScan makeScan(Stamp stamp);
  WheelTicks makeTicks(Stamp stamp);
  ImuSample makeImu(Stamp stamp);
  /// A zero-mean Gaussian draw (0 without drawing when noise is off).
  double noise(std::mt19937_64& rng, double sigma) const;

  SimulatorSettings settings_;
  DiffDriveParams drive_;
  SensorMounting mounting_;
  FloorPlan plan_;
  std::unique_ptr<RouteFollower> follower_;

  std::int64_t start_ns_ = 0;
  std::int64_t end_ns_ = 0;  ///< first stamp not emitted
  std::int64_t now_ns_ = 0;
  std::int64_t next_command_ns_ = 0;
  TrueState truth_;

  Stream ticks_stream_;
  Stream imu_stream_;
  Stream laser_stream_;
  std::mt19937_64 laser_rng_;
  std::mt19937_64 encoder_rng_;
  std::mt19937_64 imu_rng_;
  EncoderState encoders_;

  SourceCounters counters_;
};

}  // namespace mrslam::drivers
