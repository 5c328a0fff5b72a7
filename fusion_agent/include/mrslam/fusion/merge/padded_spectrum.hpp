#pragma once
// The spectrum of an image padded with zeros, for cross-correlations by DFT (the global search,
// the Radon fallback's translation search).

#include <opencv2/core.hpp>

namespace mrslam::fusion {

/// The DFT (CCS-packed) of `image` (CV_32F) padded with zeros to `size`. The rows of padding are
/// left out of the first pass: their transforms are zeros, so the spectrum is the same.
inline cv::Mat paddedSpectrum(const cv::Mat& image, cv::Size size) {
  cv::Mat padded(size, CV_32F, cv::Scalar(0.0f));
  image.copyTo(padded(cv::Rect(0, 0, image.cols, image.rows)));
  cv::Mat result;
  cv::dft(padded, result, 0, image.rows);
  return result;
}

}  // namespace mrslam::fusion
