#include "mrslam/robot/ekf_estimator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "full_turn_scan.hpp"

namespace mrslam::robot {
namespace {

constexpr double kDeg = M_PI / 180.0;

DiffDriveParams platform() {
  DiffDriveParams p;
  p.wheel_radius_m = 0.1;
  p.track_width_m = 0.5;
  p.ticks_per_revolution = 1000;
  return p;
}

// Ticks for a wheel travel in metres on platform().
std::int64_t ticksFor(double metres) {
  return std::llround(metres / (2.0 * M_PI * 0.1) * 1000.0);
}

// Drives the wheels by (left, right) metres in `steps` equal readings, one per 20 ms.
void drive(EkfEstimator& ekf, double left_m, double right_m, int steps, std::int64_t& t_ns,
           double& left_total, double& right_total) {
  for (int i = 0; i < steps; ++i) {
    left_total += left_m / steps;
    right_total += right_m / steps;
    t_ns += 20'000'000;
    ekf.addWheelTicks({Stamp{t_ns}, ticksFor(left_total), ticksFor(right_total)});
  }
}

EkfSettings noLaser() {
  EkfSettings settings;
  settings.scan_matching.enabled = false;
  return settings;
}

TEST(EkfEstimatorTest, StraightDriveFromWheelTicks) {
  EkfEstimator ekf(platform(), SensorMounting{}, noLaser());
  std::int64_t t = 0;
  double l = 0.0;
  double r = 0.0;
  ekf.addWheelTicks({Stamp{t}, 0, 0});
  drive(ekf, 2.0, 2.0, 100, t, l, r);
  EXPECT_NEAR(ekf.pose().x(), 2.0, 2e-3);
  EXPECT_NEAR(ekf.pose().y(), 0.0, 1e-9);
  EXPECT_NEAR(ekf.pose().theta(), 0.0, 1e-9);
  const Eigen::Matrix3d P = ekf.covariance();
  EXPECT_GT(P(0, 0), 0.0);
  EXPECT_GT(P(2, 2), 0.0);  // equal wheel noise on both wheels makes the heading uncertain
  EXPECT_EQ(ekf.counters().predictions, 100u);
}

TEST(EkfEstimatorTest, TurnInPlaceFromWheelTicks) {
  EkfEstimator ekf(platform(), SensorMounting{}, noLaser());
  std::int64_t t = 0;
  double l = 0.0;
  double r = 0.0;
  ekf.addWheelTicks({Stamp{t}, 0, 0});
  const double arc = 0.25 * M_PI / 2;  // a quarter turn on a 0.5 m track
  drive(ekf, -arc, arc, 50, t, l, r);
  EXPECT_NEAR(ekf.pose().x(), 0.0, 1e-3);
  EXPECT_NEAR(ekf.pose().y(), 0.0, 1e-3);
  EXPECT_NEAR(ekf.pose().theta(), M_PI / 2, 0.5 * kDeg);
}

TEST(EkfEstimatorTest, ArcFromWheelTicksEndsOnTheCircle) {
  // The centre on a circle of radius 1 m: a quarter turn ends at (1, 1) facing +y.
  EkfEstimator ekf(platform(), SensorMounting{}, noLaser());
  std::int64_t t = 0;
  double l = 0.0;
  double r = 0.0;
  ekf.addWheelTicks({Stamp{t}, 0, 0});
  drive(ekf, 0.75 * M_PI / 2, 1.25 * M_PI / 2, 80, t, l, r);
  EXPECT_NEAR(ekf.pose().x(), 1.0, 3e-3);
  EXPECT_NEAR(ekf.pose().y(), 1.0, 3e-3);
  EXPECT_NEAR(ekf.pose().theta(), M_PI / 2, 0.3 * kDeg);
}

TEST(EkfEstimatorTest, ScanDelayHoldsTheFilterWhereTheScanWasTaken) {
  EkfSettings settings = noLaser();
  settings.scan_delay_s = 0.5;
  EkfEstimator ekf(platform(), SensorMounting{}, settings);
  // 1 m/s straight ahead, readings every 0.25 s: the filter stays half a second behind.
  for (int i = 0; i <= 8; ++i) {
    const double metres = 0.25 * i;
    ekf.addWheelTicks({Stamp{i * 250'000'000LL}, ticksFor(metres), ticksFor(metres)});
  }
  EXPECT_NEAR(ekf.pose().x(), 1.5, 2e-3);
  LaserScan scan;
  scan.stamp = Stamp{2'100'000'000};  // taken at 1.6 s: the filter moves on to there
  ekf.addScan(scan, OccupancyGrid(0.05));
  EXPECT_NEAR(ekf.pose().x(), 1.6, 2e-3);
}

TEST(EkfEstimatorTest, OdometryPosesNeedNoTimeStep) {
  // csail-like: every stamp equal; intel-like: a stamp going backwards.
  EkfEstimator ekf(platform(), SensorMounting{}, noLaser());
  const Stamp same{1'000'000'000};
  ekf.addOdometry({same, SE2(5.0, 5.0, M_PI / 2)});
  ekf.addOdometry({same, SE2(5.0, 6.0, M_PI / 2)});
  ekf.addOdometry({Stamp{0}, SE2(5.0, 6.0, M_PI)});
  EXPECT_NEAR(ekf.pose().x(), 1.0, 1e-12);
  EXPECT_NEAR(ekf.pose().y(), 0.0, 1e-12);
  EXPECT_NEAR(ekf.pose().theta(), M_PI / 2, 1e-12);
  EXPECT_TRUE(ekf.covariance().allFinite());
  EXPECT_EQ(ekf.counters().predictions, 2u);
}

ImuSample imuAt(std::int64_t t_ns, double yaw, double rate) {
  ImuSample imu;
  imu.stamp = Stamp{t_ns};
  imu.yaw_rad = yaw;
  imu.angular_rate_rad_s = Eigen::Vector3d(0.0, 0.0, rate);
  return imu;
}

TEST(EkfEstimatorTest, ImuHeadingCorrectsTheOdometryHeadingAndAnOutlierIsGatedOut) {
  EkfSettings settings = noLaser();
  settings.imu.use_yaw_rate = false;
  settings.imu.heading_sigma_rad = 0.01;
  settings.odometry.rotation_per_rad = 0.5;  // odometry that turns poorly
  EkfEstimator ekf(platform(), SensorMounting{}, settings);
  // The IMU's world heading of the start is 1 rad; its readings are relative to the first.
  ekf.addImu(imuAt(0, 1.0, 0.0));
  // Odometry says the robot turned 10° more than it did (5° per step); the IMU knows.
  for (int i = 1; i <= 10; ++i) {
    ekf.addOdometry({Stamp{i * 100'000'000LL}, SE2(0.0, 0.0, (i - 1) * 5.0 * kDeg)});
    if (i > 1) {
      ekf.addImu(imuAt(i * 100'000'000LL, 1.0 + (i - 1) * 4.0 * kDeg, 0.0));
    }
  }
  EXPECT_NEAR(ekf.pose().theta(), 36.0 * kDeg, 1.0 * kDeg);
  EXPECT_EQ(ekf.counters().heading_rejections, 0u);
  // A reading 90° off is an outlier: gated out, counted, the heading unchanged.
  const double before = ekf.pose().theta();
  ekf.addImu(imuAt(1'100'000'000LL, 1.0 + 36.0 * kDeg + M_PI / 2, 0.0));
  EXPECT_EQ(ekf.counters().heading_rejections, 1u);
  EXPECT_EQ(ekf.pose().theta(), before);
}

TEST(EkfEstimatorTest, AHeadingGoneAstrayIsPulledBackByTheImuAfterTheRecoveryTime) {
  EkfSettings settings = noLaser();
  settings.imu.use_yaw_rate = false;
  settings.imu.heading_sigma_rad = 0.01;
  settings.imu.heading_recovery_s = 2.0;
  settings.odometry.rotation_per_rad = 0.01;  // odometry trusted on turns, as after ICP
  EkfEstimator ekf(platform(), SensorMounting{}, settings);
  ekf.addImu(imuAt(0, 0.0, 0.0));
  // The estimate turns 30° that the robot did not (a wrong match); the IMU says 0 throughout.
  ekf.addOdometry({Stamp{100'000'000}, SE2()});
  ekf.addOdometry({Stamp{200'000'000}, SE2(0.0, 0.0, 30.0 * kDeg)});
  std::int64_t t = 200'000'000;
  for (int i = 1; i <= 15; ++i) {  // 1.5 s: the readings are gated out, the heading stays
    t += 100'000'000;
    ekf.addOdometry({Stamp{t}, SE2(0.0, 0.0, 30.0 * kDeg)});
    ekf.addImu(imuAt(t, 0.0, 0.0));
  }
  EXPECT_NEAR(ekf.pose().theta(), 30.0 * kDeg, 1.0 * kDeg);
  EXPECT_EQ(ekf.counters().heading_recoveries, 0u);
  for (int i = 1; i <= 15; ++i) {  // past 2 s of disagreement the IMU pulls it back
    t += 100'000'000;
    ekf.addOdometry({Stamp{t}, SE2(0.0, 0.0, 30.0 * kDeg)});
    ekf.addImu(imuAt(t, 0.0, 0.0));
  }
  EXPECT_EQ(ekf.counters().heading_recoveries, 1u);
  EXPECT_NEAR(ekf.pose().theta(), 0.0, 2.0 * kDeg);
  EXPECT_GT(ekf.counters().heading_updates, 5u);
}

TEST(EkfEstimatorTest, YawRateEstimatesTheGyroBias) {
  EkfSettings settings = noLaser();
  settings.imu.heading_sigma_rad = 0.005;
  settings.imu.yaw_rate_sigma_rad_s = 0.002;
  EkfEstimator ekf(platform(), SensorMounting{}, settings);
  // Standing still for 20 s: the heading says 0, the gyro says 0.01 rad/s: that is its bias.
  std::int64_t t = 0;
  ekf.addWheelTicks({Stamp{t}, 0, 0});
  for (int i = 0; i < 1000; ++i) {
    t += 20'000'000;
    ekf.addWheelTicks({Stamp{t}, 0, 0});
    ekf.addImu(imuAt(t, 0.3, 0.01));
  }
  EXPECT_NEAR(ekf.gyroBias(), 0.01, 0.001);
  EXPECT_NEAR(ekf.pose().theta(), 0.0, 0.2 * kDeg);
  EXPECT_GT(ekf.counters().yaw_rate_updates, 990u);
}

TEST(EkfEstimatorTest, YawRateAloneTracksATurn) {
  EkfSettings settings = noLaser();
  settings.imu.use_heading = false;
  settings.wheel_noise_fraction = 0.2;  // poor wheels
  EkfEstimator ekf(platform(), SensorMounting{}, settings);
  std::int64_t t = 0;
  double l = 0.0;
  double r = 0.0;
  ekf.addWheelTicks({Stamp{t}, 0, 0});
  ekf.addImu(imuAt(t, 0.0, 0.0));
  // The wheels claim a quarter turn over 1 s; the gyro measured a third of a turn.
  const double arc = 0.25 * M_PI / 2;
  for (int i = 0; i < 50; ++i) {
    drive(ekf, -arc / 50, arc / 50, 1, t, l, r);
    ekf.addImu(imuAt(t, 0.0, (M_PI * 2 / 3)));
  }
  // The gyro wins; a little of the disagreement goes into its bias estimate.
  EXPECT_NEAR(ekf.pose().theta(), M_PI * 2 / 3, 5.0 * kDeg);
}

TEST(EkfEstimatorTest, LateImuSamplesAreDroppedAndCounted) {
  EkfEstimator ekf(platform(), SensorMounting{}, noLaser());
  ekf.addImu(imuAt(1'000'000'000, 0.0, 0.0));
  ekf.addOdometry({Stamp{2'000'000'000}, SE2()});
  ekf.addImu(imuAt(1'500'000'000, 0.5, 0.0));  // older than the odometry: late
  EXPECT_EQ(ekf.counters().late_imu, 1u);
  EXPECT_EQ(ekf.counters().heading_updates, 0u);
  ekf.addImu(imuAt(2'000'000'000, 0.0, 0.0));  // equal stamps are not late
  EXPECT_EQ(ekf.counters().late_imu, 1u);
  EXPECT_EQ(ekf.counters().heading_updates, 1u);
}

TEST(EkfEstimatorTest, ImuGapsGiveNoYawRateUpdate) {
  EkfEstimator ekf(platform(), SensorMounting{}, noLaser());
  ekf.addImu(imuAt(0, 0.0, 0.0));
  ekf.addImu(imuAt(2'000'000'000, 0.0, 0.0));  // 2 s > max_gap_s
  EXPECT_EQ(ekf.counters().imu_gaps, 1u);
  EXPECT_EQ(ekf.counters().yaw_rate_updates, 0u);
  ekf.addImu(imuAt(2'020'000'000, 0.0, 0.0));
  EXPECT_EQ(ekf.counters().yaw_rate_updates, 1u);
}

// A laser at (x, y), heading 0, in the room −3 ≤ x ≤ 3, −2 ≤ y ≤ 2: 360 beams over the full turn.
LaserScan roomScan(std::int64_t t_ns, double x, double y) {
  LaserScan scan = test::fullTurnScan([x, y](double angle) {
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    double range = test::kFullTurnRangeMaxM;
    if (std::abs(c) > 1e-9) {
      range = std::min(range, ((c > 0.0 ? 3.0 : -3.0) - x) / c);
    }
    if (std::abs(s) > 1e-9) {
      range = std::min(range, ((s > 0.0 ? 2.0 : -2.0) - y) / s);
    }
    return static_cast<float>(range);
  });
  scan.stamp = Stamp{t_ns};
  return scan;
}

// Two scans 10 cm apart; the second ICP is given a single iteration, so it ends unconverged
// (kNotConverged, still at the first, wide pair gate) with every point paired.
EkfCounters countersWithOneIcpIteration(bool accept_unconverged) {
  EkfSettings settings;
  settings.scan_matching.icp.max_iterations = 1;
  settings.scan_matching.accept_unconverged = accept_unconverged;
  EkfEstimator ekf(platform(), SensorMounting{}, settings);
  const OccupancyGrid map(0.05);
  ekf.addOdometry({Stamp{0}, SE2()});
  ekf.addScan(roomScan(0, 0.0, 0.0), map);
  ekf.addOdometry({Stamp{100'000'000}, SE2(0.1, 0.0, 0.0)});
  ekf.addScan(roomScan(100'000'000, 0.1, 0.0), map);
  EXPECT_TRUE(ekf.lastScanMatch().has_value());
  EXPECT_EQ(ekf.lastScanMatch()->icp.status, IcpStatus::kNotConverged);
  return ekf.counters();
}

TEST(EkfEstimatorTest, AnUnconvergedMatchIsAFailureUnlessAccepted) {
  const EkfCounters refused = countersWithOneIcpIteration(false);
  EXPECT_EQ(refused.scan_match_failures, 1u);
  EXPECT_EQ(refused.scan_updates, 0u);
  const EkfCounters accepted = countersWithOneIcpIteration(true);
  EXPECT_EQ(accepted.scan_match_failures, 0u);
  EXPECT_EQ(accepted.scan_updates, 1u);
}

TEST(EkfEstimatorTest, CovarianceStaysSymmetricAndPositive) {
  EkfEstimator ekf(platform(), SensorMounting{}, noLaser());
  std::int64_t t = 0;
  double l = 0.0;
  double r = 0.0;
  ekf.addWheelTicks({Stamp{t}, 0, 0});
  for (int i = 0; i < 200; ++i) {
    drive(ekf, 0.01 + 0.005 * std::sin(0.1 * i), 0.01, 1, t, l, r);
    ekf.addImu(imuAt(t, 0.001 * i, 0.0));
  }
  const Eigen::Matrix3d P = ekf.covariance();
  EXPECT_NEAR((P - P.transpose()).norm(), 0.0, 1e-12);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(P).eigenvalues().minCoeff(), 0.0);
}

}  // namespace
}  // namespace mrslam::robot
