// The strongest peaks of a correlation on a torus: the same peaks, in the same order, as taking
// the maximum and clearing its wrapped neighbourhood in turn.

#include "mrslam/fusion/merge/torus_peaks.hpp"

#include <gtest/gtest.h>

#include <random>

namespace mrslam::fusion {
namespace {

// The definition: the maximum (cv::minMaxLoc), its square of `separation` cells cleared with
// wrapping, until `count` are taken or no positive score is left.
std::vector<TorusPeak> clearingInTurn(cv::Mat scores, int count, int separation) {
  std::vector<TorusPeak> peaks;
  while (static_cast<int>(peaks.size()) < count) {
    double best = 0.0;
    cv::Point at;
    cv::minMaxLoc(scores, nullptr, &best, nullptr, &at);
    if (best <= 0.0) {
      break;
    }
    peaks.push_back({at, static_cast<float>(best)});
    for (int dy = -separation; dy <= separation; ++dy) {
      for (int dx = -separation; dx <= separation; ++dx) {
        scores.at<float>((at.y + dy + scores.rows) % scores.rows,
                         (at.x + dx + scores.cols) % scores.cols) = 0.0f;
      }
    }
  }
  return peaks;
}

void expectTheSamePeaks(const std::vector<TorusPeak>& found,
                        const std::vector<TorusPeak>& reference) {
  ASSERT_EQ(found.size(), reference.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    EXPECT_EQ(found[i].cell, reference[i].cell) << "peak " << i;
    EXPECT_EQ(found[i].score, reference[i].score) << "peak " << i;
  }
}

TEST(TorusPeaksTest, TakeWhatClearingEachMaximumInTurnTakes) {
  std::mt19937 random(11);
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(7, 5), cv::Size(40, 33), cv::Size(96, 96)}) {
    for (const int levels : {0, 6}) {  // continuous scores, or few levels: many ties
      cv::Mat scores(size, CV_32F);
      std::uniform_real_distribution<float> score(-1.0f, 2.0f);
      for (int y = 0; y < size.height; ++y) {
        for (int x = 0; x < size.width; ++x) {
          const float value = score(random);
          scores.at<float>(y, x) = levels == 0 ? value : std::round(value * levels) / levels;
        }
      }
      for (const int separation : {0, 1, 2, 4}) {
        for (const int count : {1, 5, 8, 9, 100, 5000}) {
          SCOPED_TRACE(testing::Message() << size << " levels " << levels << " separation "
                                          << separation << " count " << count);
          expectTheSamePeaks(strongestTorusPeaks(scores, count, separation),
                             clearingInTurn(scores.clone(), count, separation));
        }
      }
    }
  }
}

TEST(TorusPeaksTest, ANeighbourAcrossTheWrappedEdgeIsCleared) {
  cv::Mat scores(10, 12, CV_32F, cv::Scalar(0.0f));
  scores.at<float>(0, 0) = 5.0f;   // the strongest
  scores.at<float>(9, 11) = 4.0f;  // one cell from it across both edges
  scores.at<float>(0, 9) = 3.0f;   // three columns from it across the left edge
  scores.at<float>(5, 5) = -1.0f;  // never a peak
  const std::vector<TorusPeak> peaks = strongestTorusPeaks(scores, 10, 2);
  ASSERT_EQ(peaks.size(), 2u);
  EXPECT_EQ(peaks[0].cell, cv::Point(0, 0));
  EXPECT_EQ(peaks[1].cell, cv::Point(9, 0));
  EXPECT_EQ(peaks[1].score, 3.0f);
  EXPECT_EQ(strongestTorusPeaks(scores, 10, 0).size(), 3u) << "no clearing: every positive score";
}

TEST(TorusPeaksTest, EqualScoresComeInRowMajorOrder) {
  cv::Mat scores(6, 6, CV_32F, cv::Scalar(0.0f));
  scores.at<float>(4, 1) = 2.0f;
  scores.at<float>(1, 4) = 2.0f;
  scores.at<float>(1, 2) = 2.0f;
  const std::vector<TorusPeak> peaks = strongestTorusPeaks(scores, 3, 0);
  ASSERT_EQ(peaks.size(), 3u);
  EXPECT_EQ(peaks[0].cell, cv::Point(2, 1));
  EXPECT_EQ(peaks[1].cell, cv::Point(4, 1));
  EXPECT_EQ(peaks[2].cell, cv::Point(1, 4));
}

TEST(TorusPeaksTest, AViewIntoALargerImageIsReadAsItsOwnCells) {
  cv::Mat whole(8, 8, CV_32F, cv::Scalar(0.0f));
  whole.at<float>(2, 3) = 1.0f;  // inside the view at (1, 1)
  whole.at<float>(0, 0) = 9.0f;  // outside it
  const std::vector<TorusPeak> peaks = strongestTorusPeaks(whole(cv::Rect(2, 1, 4, 4)), 5, 1);
  ASSERT_EQ(peaks.size(), 1u);
  EXPECT_EQ(peaks[0].cell, cv::Point(1, 1));
}

}  // namespace
}  // namespace mrslam::fusion
