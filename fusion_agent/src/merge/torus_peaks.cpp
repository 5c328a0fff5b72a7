#include "mrslam/fusion/merge/torus_peaks.hpp"

#include <algorithm>
#include <cstdlib>

namespace mrslam::fusion {

namespace {

// A score and its index in row-major order.
struct ScoredCell {
  float score;
  int index;
};

// Whether `a` is taken before `b`: the higher score, the first in row-major order on a tie.
bool takenBefore(const ScoredCell& a, const ScoredCell& b) {
  return a.score > b.score || (a.score == b.score && a.index < b.index);
}

// Whether two cells of a `cols` × `rows` torus lie within `separation` of each other in both
// directions.
bool withinOnTorus(int a, int b, int cols, int rows, int separation) {
  const int dx = std::abs(a % cols - b % cols);
  const int dy = std::abs(a / cols - b / cols);
  return std::min(dx, cols - dx) <= separation && std::min(dy, rows - dy) <= separation;
}

// Up to this many peaks, clearing each maximum in turn (a vectorised pass over the image a peak)
// is quicker than collecting every positive score into a heap.
constexpr int kClearedInTurnUpTo = 8;

std::vector<TorusPeak> clearedInTurn(cv::Mat& image, int count, int separation) {
  std::vector<TorusPeak> peaks;
  while (static_cast<int>(peaks.size()) < count) {
    double best = 0.0;
    cv::Point at;
    cv::minMaxLoc(image, nullptr, &best, nullptr, &at);
    if (best <= 0.0) {
      break;
    }
    peaks.push_back({at, static_cast<float>(best)});
    // A separation may exceed the rows or columns (up to the larger side): wrap any distance.
    const auto wrapped = [](int index, int size) { return ((index % size) + size) % size; };
    for (int dy = -separation; dy <= separation; ++dy) {
      float* row = image.ptr<float>(wrapped(at.y + dy, image.rows));
      for (int dx = -separation; dx <= separation; ++dx) {
        row[wrapped(at.x + dx, image.cols)] = 0.0f;
      }
    }
  }
  return peaks;
}

}  // namespace

std::vector<TorusPeak> strongestTorusPeaks(cv::Mat& scores, int count, int separation) {
  CV_Assert(scores.type() == CV_32F);
  separation = std::clamp(separation, 0, std::max(scores.rows, scores.cols));  // the same peaks
  if (count <= kClearedInTurnUpTo) {
    return clearedInTurn(scores, count, separation);
  }
  const cv::Mat image = scores.isContinuous() ? scores : scores.clone();
  std::vector<ScoredCell> positive;
  const auto* values = image.ptr<float>(0);
  for (int i = 0; i < static_cast<int>(image.total()); ++i) {
    if (values[i] > 0.0f) {
      positive.push_back({values[i], i});
    }
  }
  const auto later = [](const ScoredCell& a, const ScoredCell& b) { return takenBefore(b, a); };
  std::make_heap(positive.begin(), positive.end(), later);
  std::vector<int> kept;
  std::vector<TorusPeak> peaks;
  while (static_cast<int>(peaks.size()) < count && !positive.empty()) {
    std::pop_heap(positive.begin(), positive.end(), later);
    const ScoredCell next = positive.back();
    positive.pop_back();
    const bool cleared = std::any_of(kept.begin(), kept.end(), [&](int index) {
      return withinOnTorus(index, next.index, image.cols, image.rows, separation);
    });
    if (!cleared) {
      kept.push_back(next.index);
      peaks.push_back({cv::Point(next.index % image.cols, next.index / image.cols), next.score});
    }
  }
  return peaks;
}

}  // namespace mrslam::fusion
