#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "mrslam/fusion/merge/edges.hpp"
#include "mrslam/fusion/merge/radon.hpp"

namespace mrslam::fusion {
namespace {

constexpr double kDegree = M_PI / 180.0;

// Cells of a polyline drawn in a size × size image after turning it by `theta` about the centre.
std::vector<cv::Point> drawTurned(const std::vector<std::pair<cv::Point2d, cv::Point2d>>& lines,
                                  double theta, int size) {
  cv::Mat image(size, size, CV_8U, cv::Scalar(0));
  const cv::Point2d centre(0.5 * (size - 1), 0.5 * (size - 1));
  const auto turn = [&](const cv::Point2d& p) {
    const cv::Point2d d = p - centre;
    return cv::Point(
        static_cast<int>(std::lround(centre.x + std::cos(theta) * d.x - std::sin(theta) * d.y)),
        static_cast<int>(std::lround(centre.y + std::sin(theta) * d.x + std::cos(theta) * d.y)));
  };
  for (const auto& [a, b] : lines) {
    cv::line(image, turn(a), turn(b), cv::Scalar(255));
  }
  return nonZeroCells(image);
}

// Rooms: a few walls of different lengths and directions.
std::vector<std::pair<cv::Point2d, cv::Point2d>> rooms() {
  return {{{40, 40}, {160, 40}},   {{160, 40}, {160, 120}}, {{40, 40}, {40, 150}},
          {{40, 150}, {110, 150}}, {{90, 40}, {90, 100}},   {{120, 80}, {150, 130}}};
}

TEST(MergeRadonTest, PeakOfALineIsItsNormalAngleAndDistance) {
  const int size = 101;  // centre (50, 50)
  const double phi = 30.0 * kDegree;
  const double rho = 10.0;
  const cv::Point2d n(std::cos(phi), std::sin(phi));
  const cv::Point2d along(-n.y, n.x);
  const cv::Point2d foot = cv::Point2d(50, 50) + rho * n;
  const std::vector<cv::Point> cells =
      drawTurned({{foot - 40 * along, foot + 40 * along}}, 0.0, size);
  const RadonPeak peak = radonPeak(radonTransform(cells, cv::Size(size, size), 0.5 * kDegree));
  EXPECT_NEAR(peak.angle_rad, phi, 1.0 * kDegree);
  EXPECT_NEAR(peak.rho, rho, 1.5);
  EXPECT_GT(peak.value, 40.0);  // ~70 cells, split between neighbouring ρ bins
}

TEST(MergeRadonTest, TurningALineShiftsItsPeakByTheTurn) {
  const int size = 121;
  const std::vector<std::pair<cv::Point2d, cv::Point2d>> line = {{{20, 40}, {100, 70}}};
  const RadonPeak before =
      radonPeak(radonTransform(drawTurned(line, 0.0, size), cv::Size(size, size), 0.5 * kDegree));
  const RadonPeak after = radonPeak(
      radonTransform(drawTurned(line, 25.0 * kDegree, size), cv::Size(size, size), 0.5 * kDegree));
  EXPECT_NEAR(std::remainder(after.angle_rad - before.angle_rad, M_PI), 25.0 * kDegree,
              1.0 * kDegree);
}

TEST(MergeRadonTest, ProfileIgnoresTranslation) {
  const int size = 200;
  const std::vector<cv::Point> cells = drawTurned(rooms(), 0.0, size);
  std::vector<cv::Point> shifted;
  for (const cv::Point& cell : cells) {
    shifted.push_back(cell + cv::Point(17, -23));
  }
  const std::vector<double> a =
      radonSpectrum(radonTransform(cells, cv::Size(size, size), kDegree), 5.0 * kDegree);
  const std::vector<double> b =
      radonSpectrum(radonTransform(shifted, cv::Size(size, size), kDegree), 5.0 * kDegree);
  ASSERT_EQ(a.size(), 180u);
  const std::vector<double> correlation = spectrumCorrelation(a, b);
  EXPECT_GT(correlation[0], 0.95);  // normalised profiles: 1 when equal
  EXPECT_EQ(std::max_element(correlation.begin(), correlation.end()) - correlation.begin(), 0);
}

TEST(MergeRadonTest, TunesTheRotationNearTheApproximateAngle) {
  const int size = 200;
  const double truth = 37.0 * kDegree;
  const auto profile = [&](double theta) {
    return radonSpectrum(
        radonTransform(drawTurned(rooms(), theta, size), cv::Size(size, size), kDegree),
        5.0 * kDegree);
  };
  const std::vector<double> correlation = spectrumCorrelation(profile(0.0), profile(truth));
  const std::optional<double> tuned = tuneRotation(correlation, 34.0 * kDegree, 5.0 * kDegree);
  ASSERT_TRUE(tuned);
  EXPECT_NEAR(*tuned, truth, 0.5 * kDegree);
  const std::optional<double> other_half =
      tuneRotation(correlation, truth + M_PI + 2.0 * kDegree, 5.0 * kDegree);
  ASSERT_TRUE(other_half);  // keeps the approximate angle's half turn
  EXPECT_NEAR(*other_half, truth + M_PI, 0.5 * kDegree);
  const std::vector<double> candidates = rotationCandidates(correlation, 2);
  ASSERT_FALSE(candidates.empty());
  EXPECT_NEAR(std::remainder(candidates.front() - truth, M_PI / 2.0), 0.0, 1.0 * kDegree);
}

TEST(MergeRadonTest, NoPeakInsideTheWindowGivesNothing) {
  std::vector<double> ramp(180);
  for (std::size_t i = 0; i < ramp.size(); ++i) {
    ramp[i] = static_cast<double>(i < 90 ? i : 180 - i);  // one peak, at 90°
  }
  EXPECT_FALSE(tuneRotation(ramp, 40.0 * kDegree, 5.0 * kDegree));
  const std::optional<double> tuned = tuneRotation(ramp, 88.0 * kDegree, 5.0 * kDegree);
  ASSERT_TRUE(tuned);
  EXPECT_NEAR(*tuned, 90.0 * kDegree, 0.5 * kDegree);
  const std::vector<double> peaks = rotationCandidates(ramp, 3);
  ASSERT_EQ(peaks.size(), 1u);
  EXPECT_NEAR(peaks[0], 90.0 * kDegree, 0.5 * kDegree);
}

TEST(MergeRadonTest, CorrelationOfAProfileWithItselfPeaksAtZero) {
  const int size = 200;
  const std::vector<double> profile = radonSpectrum(
      radonTransform(drawTurned(rooms(), 0.0, size), cv::Size(size, size), kDegree), 5.0 * kDegree);
  const std::vector<double> correlation = spectrumCorrelation(profile, profile);
  EXPECT_EQ(std::max_element(correlation.begin(), correlation.end()) - correlation.begin(), 0);
  EXPECT_NEAR(correlation[0], 1.0, 1e-9);  // normalised profiles
}

// The profile made without the image equals the image's, value for value, on several turns,
// step sizes and image sizes (cells near the image's corners included).
TEST(MergeRadonTest, TheProfileOfCellsEqualsTheProfileOfTheirImage) {
  for (const int size : {200, 137}) {
    for (const double theta : {0.0, 0.3, 1.2}) {
      std::vector<cv::Point> cells = drawTurned(rooms(), theta, size);
      cells.emplace_back(0, 0);
      cells.emplace_back(size - 1, size - 1);
      for (const double step : {kDegree, 0.7 * kDegree}) {
        const cv::Size image(size, size);
        const std::vector<double> of_image =
            radonSpectrum(radonTransform(cells, image, step), 5.0 * kDegree);
        const std::vector<double> of_cells =
            radonSpectrumOfCells(cells, image, step, 5.0 * kDegree);
        ASSERT_EQ(of_cells.size(), of_image.size());
        for (std::size_t j = 0; j < of_image.size(); ++j) {
          EXPECT_EQ(of_cells[j], of_image[j])
              << "size " << size << ", turn " << theta << ", angle " << j;
        }
      }
    }
  }
}

}  // namespace
}  // namespace mrslam::fusion
