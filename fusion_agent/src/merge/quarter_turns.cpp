#include "mrslam/fusion/merge/quarter_turns.hpp"

namespace mrslam::fusion {

namespace {

int wrapped(int v, int side) {
  return (v % side + side) % side;
}

}  // namespace

cv::Mat turnedOnTorus(const cv::Mat& image, int side, int quarters) {
  cv::Mat turned(side, side, CV_32F, cv::Scalar(0.0f));
  for (int y = 0; y < image.rows; ++y) {
    const float* row = image.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) {
      // U(R^-q p) = T(p), R^-1 (x, y) = (y, -x); cv::Point is (column, row).
      const cv::Point at = quarters == 1   ? cv::Point(y, wrapped(-x, side))
                           : quarters == 2 ? cv::Point(wrapped(-x, side), wrapped(-y, side))
                                           : cv::Point(wrapped(-y, side), x);
      turned.at<float>(at) = row[x];
    }
  }
  return turned;
}

cv::Mat quarterTurnScores(const cv::Mat& scores, int canvas, int quarters) {
  const int side = scores.rows;
  const int back = canvas - 1;
  cv::Mat out(scores.size(), CV_32F);
  for (int s2 = 0; s2 < side; ++s2) {
    float* row = out.ptr<float>(s2);
    for (int s1 = 0; s1 < side; ++s1) {
      // f(s) = (s2, -back - s1), f²(s) = (-back - s1, -back - s2), f³(s) = (-back - s2, s1).
      const cv::Point read = quarters == 1 ? cv::Point(s2, wrapped(-back - s1, side))
                             : quarters == 2
                                 ? cv::Point(wrapped(-back - s1, side), wrapped(-back - s2, side))
                                 : cv::Point(wrapped(-back - s2, side), s1);
      row[s1] = scores.at<float>(read);
    }
  }
  return out;
}

}  // namespace mrslam::fusion
