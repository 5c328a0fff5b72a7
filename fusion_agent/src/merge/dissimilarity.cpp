#include "mrslam/fusion/merge/dissimilarity.hpp"

#include <algorithm>
#include <cmath>

namespace mrslam::fusion {

namespace {

bool isOfClass(std::int8_t value, PsiClass cell_class, const SimilaritySettings& settings) {
  if (value < 0) {
    return false;  // unknown
  }
  return cell_class == PsiClass::kOccupied ? value >= settings.occupied_threshold
                                           : value <= settings.free_threshold;
}

// d(m1, m2, c): the mean distance, in `to`'s distance map, of `cells` mapped by `T`; the sum and
// count of the cells that land inside (and, with kOnKnown, on a cell that `known` marks) are added
// to `sum` and `count`. Each cell lands where T.apply() puts it, the turn's cosine and sine taken
// once for all cells. The sum of whole distances is kept as an integer: a double would hold every
// partial sum exactly as well.
template <bool kOnKnown>
void addMeanDistance(const std::vector<Eigen::Vector2i>& cells, const DistanceMap& to,
                     const std::vector<std::uint8_t>& known, const GridTransform& T, long long& sum,
                     long long& count) {
  const double c = std::cos(T.theta_rad);
  const double s = std::sin(T.theta_rad);
  const double tx = T.t_cells.x();
  const double ty = T.t_cells.y();
  for (const Eigen::Vector2i& cell : cells) {
    const double cx = cell.x();
    const double cy = cell.y();
    const int x = roundToInt((c * cx - s * cy) + tx);
    const int y = roundToInt((s * cx + c * cy) + ty);
    if (x < 0 || y < 0 || x >= to.width || y >= to.height) {
      continue;
    }
    const std::size_t index = to.index(x, y);
    if (kOnKnown && known[index] == 0) {
      continue;
    }
    const std::int32_t distance = to.distance[index];
    if (distance < DistanceMap::kFar) {
      sum += distance;
      ++count;
    }
  }
}

template <bool kOnKnown>
double meanDistance(const std::vector<Eigen::Vector2i>& cells, const DistanceMap& to,
                    const std::vector<std::uint8_t>& known, const GridTransform& T, bool& landed) {
  long long sum = 0;
  long long count = 0;
  addMeanDistance<kOnKnown>(cells, to, known, T, sum, count);
  landed = landed || count > 0;
  return count > 0 ? static_cast<double>(sum) / static_cast<double>(count) : 0.0;
}

}  // namespace

DistanceMap distanceMap(const GridMap& map, PsiClass cell_class,
                        const SimilaritySettings& settings) {
  DistanceMap result;
  result.width = map.geometry.width;
  result.height = map.geometry.height;
  result.distance.assign(map.cells.size(), DistanceMap::kFar);
  const int w = result.width;
  const auto at = [&](int x, int y) -> std::int32_t& {
    return result.distance[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                           static_cast<std::size_t>(x)];
  };
  for (int y = 0; y < result.height; ++y) {  // first pass: left and upper neighbours
    for (int x = 0; x < w; ++x) {
      std::int32_t& d = at(x, y);
      if (isOfClass(map.at(x, y), cell_class, settings)) {
        d = 0;
        continue;
      }
      if (x > 0) {
        d = std::min(d, at(x - 1, y) + 1);
      }
      if (y > 0) {
        d = std::min(d, at(x, y - 1) + 1);
      }
    }
  }
  for (int y = result.height - 1; y >= 0; --y) {  // second pass: right and lower neighbours
    for (int x = w - 1; x >= 0; --x) {
      std::int32_t& d = at(x, y);
      if (x + 1 < w) {
        d = std::min(d, at(x + 1, y) + 1);
      }
      if (y + 1 < result.height) {
        d = std::min(d, at(x, y + 1) + 1);
      }
    }
  }
  return result;
}

DissimilarityMap prepareDissimilarity(const GridMap& map, const SimilaritySettings& settings) {
  DissimilarityMap prepared;
  prepared.occupied = distanceMap(map, PsiClass::kOccupied, settings);
  prepared.free = distanceMap(map, PsiClass::kFree, settings);
  prepared.known.reserve(map.cells.size());
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      prepared.known.push_back(map.at(x, y) >= 0 ? 1 : 0);
      if (isOfClass(map.at(x, y), PsiClass::kOccupied, settings)) {
        prepared.occupied_cells.emplace_back(x, y);
      } else if (isOfClass(map.at(x, y), PsiClass::kFree, settings)) {
        prepared.free_cells.emplace_back(x, y);
      }
    }
  }
  return prepared;
}

namespace {

template <bool kOnKnown>
double psiOf(const DissimilarityMap& from, const DissimilarityMap& to,
             const GridTransform& T_to_from) {
  const GridTransform T_from_to = T_to_from.inverse();
  bool landed = false;
  const double psi =
      meanDistance<kOnKnown>(from.occupied_cells, to.occupied, to.known, T_to_from, landed) +
      meanDistance<kOnKnown>(to.occupied_cells, from.occupied, from.known, T_from_to, landed) +
      meanDistance<kOnKnown>(from.free_cells, to.free, to.known, T_to_from, landed) +
      meanDistance<kOnKnown>(to.free_cells, from.free, from.known, T_from_to, landed);
  return landed ? psi : std::numeric_limits<double>::infinity();
}

}  // namespace

double dissimilarity(const DissimilarityMap& from, const DissimilarityMap& to,
                     const GridTransform& T_to_from) {
  return psiOf<false>(from, to, T_to_from);
}

double overlapDissimilarity(const DissimilarityMap& from, const DissimilarityMap& to,
                            const GridTransform& T_to_from) {
  return psiOf<true>(from, to, T_to_from);
}

}  // namespace mrslam::fusion
