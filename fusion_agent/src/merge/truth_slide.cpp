#include "mrslam/fusion/merge/truth_slide.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace mrslam::fusion {

namespace {

// Whether `candidate` disagrees less than `best` (ties: the larger overlap; then the first).
bool cleaner(const Agreement& candidate, const Agreement& best) {
  if (candidate.disagreement != best.disagreement) {
    return candidate.disagreement < best.disagreement;
  }
  return candidate.overlap() > best.overlap();
}

// One placement of `from`: the truth shifted by whole cells, and how it compares.
struct Placement {
  Eigen::Vector2i shift = Eigen::Vector2i::Zero();
  Agreement agreement;
};

// The placements of the truth's basin (within one cell) and of every slide of min_slide to
// reach cells, in row order.
std::vector<Placement> placements(const std::vector<CellSample>& samples, const CodeImage& to,
                                  const GridTransform& T_to_from, const ComparisonTables& tables,
                                  const TruthSlideSettings& settings) {
  std::vector<Placement> placed;
  for (int dy = -settings.reach; dy <= settings.reach; ++dy) {
    for (int dx = -settings.reach; dx <= settings.reach; ++dx) {
      const int distance = std::max(std::abs(dx), std::abs(dy));
      if (distance > 1 && distance < settings.min_slide) {
        continue;
      }
      GridTransform T = T_to_from;
      T.t_cells += Eigen::Vector2d(dx, dy);
      placed.push_back({{dx, dy}, compareAt(samples, to, T, tables, false)});
    }
  }
  return placed;
}

// The cleanest of `placed` whose shift lies within [least, most] cells (max norm) and whose
// overlap reaches `least_overlap`; null when none does.
const Placement* cleanest(const std::vector<Placement>& placed, int least, int most,
                          double least_overlap) {
  const Placement* best = nullptr;
  for (const Placement& placement : placed) {
    const int distance = placement.shift.cwiseAbs().maxCoeff();
    if (distance < least || distance > most ||
        static_cast<double>(placement.agreement.overlap()) < least_overlap) {
      continue;
    }
    if (best == nullptr || cleaner(placement.agreement, best->agreement)) {
      best = &placement;
    }
  }
  return best;
}

}  // namespace

TruthSlide truthSlide(const GridMap& from, const GridMap& to, const GridTransform& T_to_from,
                      const TruthSlideSettings& settings) {
  if (settings.reach < 1 || settings.min_slide < 2 || settings.min_slide > settings.reach) {
    throw std::invalid_argument(
        "truth slide: the reach must be at least 1 and the least slide between 2 and the reach");
  }
  const ComparisonTables tables(settings.similarity);
  const std::vector<Placement> placed =
      placements(knownCells(from, tables), codeImage(to, 0, tables), T_to_from, tables, settings);
  TruthSlide slide;
  const Placement* truth = cleanest(placed, 0, 1, 0.0);  // the basin is never empty
  slide.at_truth = truth->agreement;
  slide.truth_shift = truth->shift;
  const double least_overlap =
      settings.min_overlap_share * static_cast<double>(slide.at_truth.overlap());
  if (const Placement* slid = cleanest(placed, settings.min_slide, settings.reach, least_overlap)) {
    slide.slid_found = true;
    slide.slid = slid->agreement;
    slide.slide = slid->shift;
  }
  return slide;
}

}  // namespace mrslam::fusion
