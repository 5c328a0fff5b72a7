#pragma once
// The strongest peaks of a correlation on a torus (a DFT's scores): take the highest score, clear
// the square of `separation` cells about it (wrapping), and repeat. So found for a few peaks;
// many are found in one pass and a heap rather than a pass over the image per peak.

#include <opencv2/core.hpp>
#include <vector>

namespace mrslam::fusion {

/// A peak: its cell (column, row) and score.
struct TorusPeak {
  cv::Point cell;
  float score = 0.0f;
};

/// The `count` highest positive scores of `scores` (CV_32F), best first, each more than
/// `separation` cells (wrapping, in columns or rows) from every higher one kept; on equal scores
/// the first in row-major order comes first (as cv::minMaxLoc takes it). Fewer when the positive
/// scores run out. A negative `separation` counts as 0 (each peak clears its own cell).
/// `scores` are spent: for up to 8 peaks they are cleared about each peak in place (pass a clone
/// to keep them).
std::vector<TorusPeak> strongestTorusPeaks(cv::Mat& scores, int count, int separation);

}  // namespace mrslam::fusion
