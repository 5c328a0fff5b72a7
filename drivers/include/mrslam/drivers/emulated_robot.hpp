#pragma once
// An emulated robot: a sample source (the simulator or a log) played in real time through
// emulated devices, so a robot agent reads them exactly as on a robot — the laser as a Hokuyo
// answering SCIP 2.0 on a pseudo-terminal, the IMU as a 3DM-GX1 on another, the wheel encoders
// through the emulated Phidget board (libphidget22_emulator.so reading a feed file).
//
// Each scan of the source becomes what the Hokuyo emulator streams until the next one; each IMU
// sample becomes the GX1's state (in the device's own axes); each wheel-tick reading (or, for
// logs with odometry poses, the wheel travel that pose change takes) becomes the board's counts.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/platform.hpp"
#include "mrslam/common/result.hpp"
#include "mrslam/common/samples.hpp"
#include "mrslam/drivers/gx1_codec.hpp"
#include "mrslam/drivers/sample_source.hpp"
#include "mrslam/drivers/scip_responder.hpp"

namespace mrslam::drivers {

/// Where the emulated devices appear and how they are mounted (from the robot agent's config).
struct EmulatedDevices {
  std::string laser_path;         ///< link to the Hokuyo's pty; empty: no laser
  std::string imu_path;           ///< link to the 3DM-GX1's pty; empty: no IMU
  std::string encoder_feed_path;  ///< the Phidget board's feed file; empty: no encoders
  int left_channel = 0;           ///< board input of the left wheel
  int right_channel = 1;
  int left_direction = 1;  ///< the robot config's sign: board count = direction × wheel ticks
  int right_direction = 1;
  bool imu_z_down = true;  ///< as the robot config's imu.device_z_down
};

struct EmulatedRobotSettings {
  double speed = 1.0;                ///< source seconds per wall-clock second
  std::optional<double> duration_s;  ///< stop after this much source time
  DiffDriveParams drive;             ///< wheel geometry: odometry poses → encoder counts
};

struct EmulatedRobotCounters {
  std::uint64_t scans = 0;  ///< scans handed to the Hokuyo emulator
  std::uint64_t imu_samples = 0;
  std::uint64_t tick_readings = 0;  ///< encoder feed updates
  std::uint64_t hokuyo_scans_sent = 0;
  std::uint64_t gx1_frames_sent = 0;
  double source_time_s = 0.0;  ///< source time played
};

/// The Hokuyo whose scans look like `scan`: URG-04LX or UBG-05LN when the geometry is theirs,
/// else a model with the scan's own step (ARES = 2π / increment), front step and range limits.
/// Fails when no whole-step geometry fits the scan (e.g. a start angle between two steps).
Result<HokuyoModel> hokuyoModelFor(const LaserScan& scan, double scan_rate_hz);
/// A scan as the model's raw values (steps AMIN…AMAX): hits in mm, kNoReturn above DMAX,
/// kInvalid as an error code (1).
std::vector<std::uint32_t> rawRangesOf(const LaserScan& scan, const HokuyoModel& model);
/// What a 3DM-GX1 mounted like `devices` reads when the robot's IMU reads `sample`.
gx1::DeviceState gx1StateOf(const ImuSample& sample, bool z_down);

/// Writes the emulated Phidget board's feed file (atomically: a temporary file, then rename);
/// removes it when destroyed (the board detaches).
class PhidgetFeedWriter {
 public:
  explicit PhidgetFeedWriter(std::string path);
  ~PhidgetFeedWriter();
  PhidgetFeedWriter(const PhidgetFeedWriter&) = delete;
  PhidgetFeedWriter& operator=(const PhidgetFeedWriter&) = delete;
  /// The four inputs' cumulative counts. Throws std::runtime_error when it cannot write.
  void write(const std::vector<std::int64_t>& counts);

 private:
  std::string path_;
};

class EmulatedRobot {
 public:
  /// Called at each scan handed to the laser with the host time (Unix s) and the scan.
  using ScanObserver = std::function<void(double host_time_s, const LaserScan& scan)>;

  EmulatedRobot(std::unique_ptr<SampleSource> source, EmulatedDevices devices,
                EmulatedRobotSettings settings);
  ~EmulatedRobot();
  EmulatedRobot(const EmulatedRobot&) = delete;
  EmulatedRobot& operator=(const EmulatedRobot&) = delete;

  /// Reads the source up to its second scan (the laser's model and rate come from them) and
  /// brings up the devices whose samples the source has; a device whose first sample comes later
  /// appears then. Throws std::runtime_error naming what failed.
  void start();
  /// Plays the source in real time until it ends, the duration is reached or `stop` is set;
  /// then the devices go away.
  EmulatedRobotCounters run(const std::atomic<bool>& stop, const ScanObserver& observer = {});
  /// The laser's model (after start()).
  const HokuyoModel& laserModel() const;

 private:
  struct Devices;
  void route(const Sample& sample, const ScanObserver& observer);
  void bringUpImu(const ImuSample& first);
  void bringUpEncoders();

  std::unique_ptr<SampleSource> source_;
  EmulatedDevices devices_;
  EmulatedRobotSettings settings_;
  std::vector<Sample> pending_;  ///< read by start() before the first scan, played first
  std::unique_ptr<Devices> live_;
  EmulatedRobotCounters counters_;
};

}  // namespace mrslam::drivers
