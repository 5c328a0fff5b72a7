// The strongest peaks of a correlation on a torus: the same peaks, in the same order, as the
// definition (every positive score in order, each kept unless a kept one lies within the
// separation), for few peaks and for many.

#include "mrslam/fusion/merge/torus_peaks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace mrslam::fusion {
namespace {

// The definition: every positive score, highest first and the first in row-major order on a tie,
// kept when no kept peak lies within `separation` columns and rows (wrapping).
std::vector<TorusPeak> byDefinition(const cv::Mat& scores, int count, int separation) {
  std::vector<TorusPeak> positive;
  for (int y = 0; y < scores.rows; ++y) {
    for (int x = 0; x < scores.cols; ++x) {
      if (scores.at<float>(y, x) > 0.0f) {
        positive.push_back({cv::Point(x, y), scores.at<float>(y, x)});
      }
    }
  }
  std::stable_sort(positive.begin(), positive.end(),
                   [](const TorusPeak& a, const TorusPeak& b) { return a.score > b.score; });
  const auto apart = [](int a, int b, int size) {
    const int d = std::abs(a - b) % size;
    return std::min(d, size - d);
  };
  std::vector<TorusPeak> kept;
  for (const TorusPeak& next : positive) {
    const bool cleared = std::any_of(kept.begin(), kept.end(), [&](const TorusPeak& peak) {
      return apart(peak.cell.x, next.cell.x, scores.cols) <= separation &&
             apart(peak.cell.y, next.cell.y, scores.rows) <= separation;
    });
    if (!cleared && static_cast<int>(kept.size()) < count) {
      kept.push_back(next);
    }
  }
  return kept;
}

void expectTheSamePeaks(const std::vector<TorusPeak>& found,
                        const std::vector<TorusPeak>& reference) {
  ASSERT_EQ(found.size(), reference.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    EXPECT_EQ(found[i].cell, reference[i].cell) << "peak " << i;
    EXPECT_EQ(found[i].score, reference[i].score) << "peak " << i;
  }
}

TEST(TorusPeaksTest, TakeThePeaksTheDefinitionTakes) {
  std::mt19937 random(11);
  for (const cv::Size size :
       {cv::Size(1, 1), cv::Size(7, 5), cv::Size(40, 3), cv::Size(40, 33), cv::Size(96, 96)}) {
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
          cv::Mat spent = scores.clone();
          expectTheSamePeaks(strongestTorusPeaks(spent, count, separation),
                             byDefinition(scores, count, separation));
        }
      }
    }
  }
}

TEST(TorusPeaksTest, ANeighbourAcrossTheWrappedEdgeIsCleared) {
  cv::Mat scores(10, 12, CV_32F, cv::Scalar(0.0f));
  scores.at<float>(0, 0) = 5.0f;     // the strongest
  scores.at<float>(9, 11) = 4.0f;    // one cell from it across both edges
  scores.at<float>(0, 9) = 3.0f;     // three columns from it across the left edge
  scores.at<float>(5, 5) = -1.0f;    // never a peak
  for (const int count : {3, 10}) {  // cleared in turn, and by the heap
    cv::Mat spent = scores.clone();
    const std::vector<TorusPeak> peaks = strongestTorusPeaks(spent, count, 2);
    ASSERT_EQ(peaks.size(), 2u) << count;
    EXPECT_EQ(peaks[0].cell, cv::Point(0, 0));
    EXPECT_EQ(peaks[1].cell, cv::Point(9, 0));
    EXPECT_EQ(peaks[1].score, 3.0f);
    spent = scores.clone();
    EXPECT_EQ(strongestTorusPeaks(spent, count, 0).size(), 3u) << "no clearing: every positive";
  }
}

TEST(TorusPeaksTest, EqualScoresComeInRowMajorOrder) {
  cv::Mat scores(6, 6, CV_32F, cv::Scalar(0.0f));
  scores.at<float>(4, 1) = 2.0f;
  scores.at<float>(1, 4) = 2.0f;
  scores.at<float>(1, 2) = 2.0f;
  for (const int count : {3, 9}) {  // cleared in turn, and by the heap
    cv::Mat spent = scores.clone();
    const std::vector<TorusPeak> peaks = strongestTorusPeaks(spent, count, 0);
    ASSERT_EQ(peaks.size(), 3u) << count;
    EXPECT_EQ(peaks[0].cell, cv::Point(2, 1));
    EXPECT_EQ(peaks[1].cell, cv::Point(4, 1));
    EXPECT_EQ(peaks[2].cell, cv::Point(1, 4));
  }
}

TEST(TorusPeaksTest, AViewIntoALargerImageIsReadAsItsOwnCells) {
  cv::Mat whole(8, 8, CV_32F, cv::Scalar(0.0f));
  whole.at<float>(2, 3) = 1.0f;      // inside the view at (1, 1)
  whole.at<float>(0, 0) = 9.0f;      // outside it
  for (const int count : {5, 50}) {  // cleared in turn, and by the heap
    cv::Mat view = whole.clone()(cv::Rect(2, 1, 4, 4));
    const std::vector<TorusPeak> peaks = strongestTorusPeaks(view, count, 1);
    ASSERT_EQ(peaks.size(), 1u) << count;
    EXPECT_EQ(peaks[0].cell, cv::Point(1, 1));
  }
}

// A separation wider than the view's rows wraps within the view: the cells around it, in the
// larger image, are never written.
TEST(TorusPeaksTest, ClearingAPeakStaysInsideTheScores) {
  cv::Mat whole(10, 10, CV_32F, cv::Scalar(0.5f));
  const cv::Rect inside(2, 4, 6, 2);
  cv::Mat view = whole(inside);
  view.at<float>(0, 3) = 2.0f;
  const std::vector<TorusPeak> peaks = strongestTorusPeaks(view, 3, 3);
  ASSERT_FALSE(peaks.empty());
  EXPECT_EQ(peaks[0].cell, cv::Point(3, 0));
  for (int y = 0; y < whole.rows; ++y) {
    for (int x = 0; x < whole.cols; ++x) {
      if (!inside.contains(cv::Point(x, y))) {
        EXPECT_EQ(whole.at<float>(y, x), 0.5f) << "row " << y << " column " << x;
      }
    }
  }
}

}  // namespace
}  // namespace mrslam::fusion
