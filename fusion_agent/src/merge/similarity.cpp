#include "mrslam/fusion/merge/similarity.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace mrslam::fusion {

namespace {

double binaryEntropy(double p) {
  if (p <= 0.0 || p >= 1.0) {
    return 0.0;
  }
  return -p * std::log2(p) - (1.0 - p) * std::log2(1.0 - p);
}

std::uint8_t codeOf(std::int8_t value) {
  return value < 0 || value > 100 ? kUnknownCode : static_cast<std::uint8_t>(value);
}

// A sample placed in the padded code image: its index there, its code and its class.
struct PlacedSample {
  std::ptrdiff_t index;
  std::uint8_t code;
  std::uint8_t class_row;  // 3 · class: the row of the packed agreement table
};

// Where samples of `from` land in the padded code image of `to` (CellRounding), kept when they
// stay inside the padded image for every shift within ±reach.
class CellPlacer {
 public:
  CellPlacer(const GridTransform& T_to_from, const CodeImage& to, int reach)
      : rounding_(T_to_from),
        low_(reach - to.pad),
        high_x_(to.codes.cols - to.pad - 1 - reach),
        high_y_(to.codes.rows - to.pad - 1 - reach),
        pad_(to.pad),
        columns_(to.codes.cols) {}

  /// The sample's index in the padded image, or -1 when it lands too near its border or off it.
  std::ptrdiff_t index(const CellSample& sample) {
    const cv::Point cell = rounding_.landing(sample.x, sample.y);
    if (cell.x < low_ || cell.y < low_ || cell.x > high_x_ || cell.y > high_y_) {
      return -1;
    }
    return static_cast<std::ptrdiff_t>(cell.y + pad_) * columns_ + cell.x + pad_;
  }

 private:
  CellRounding rounding_;
  int low_;
  int high_x_;
  int high_y_;
  int pad_;
  std::ptrdiff_t columns_;
};

// Places every sample that stays inside the padded image for all shifts within ±reach.
std::vector<PlacedSample> place(const std::vector<CellSample>& samples, const CodeImage& to,
                                const GridTransform& T_to_from, int reach,
                                const ComparisonTables& tables) {
  std::vector<PlacedSample> placed;
  placed.reserve(samples.size());
  CellPlacer placer(T_to_from, to, reach);
  for (const CellSample& sample : samples) {
    const std::ptrdiff_t index = placer.index(sample);
    if (index >= 0) {
      placed.push_back(
          {index, sample.code, static_cast<std::uint8_t>(3 * tables.classOf(sample.code))});
    }
  }
  return placed;
}

// agr (low 32 bits) and dis (high 32 bits) summed from the packed agreement table, unpacked.
Agreement unpacked(std::uint64_t packed, double entropy_change) {
  Agreement sums;
  sums.agreement = static_cast<long long>(packed & 0xffffffffu);
  sums.disagreement = static_cast<long long>(packed >> 32);
  sums.entropy_change = entropy_change;
  return sums;
}

// agr and dis of the placed samples shifted by `shift` (one table read per sample).
Agreement countShifted(const std::vector<PlacedSample>& placed, const CodeImage& to,
                       std::ptrdiff_t shift, const ComparisonTables& tables) {
  const std::uint8_t* classes = to.classes.ptr<std::uint8_t>(0) + shift;
  std::uint64_t packed = 0;
  for (const PlacedSample& sample : placed) {
    packed += tables.packedAgreement(sample.class_row + classes[sample.index]);
  }
  return unpacked(packed, 0.0);
}

// The same and the entropy change of the merge.
Agreement compareShifted(const std::vector<PlacedSample>& placed, const CodeImage& to,
                         std::ptrdiff_t shift, const ComparisonTables& tables) {
  const std::uint8_t* classes = to.classes.ptr<std::uint8_t>(0) + shift;
  const std::uint8_t* codes = to.codes.ptr<std::uint8_t>(0) + shift;
  std::uint64_t packed = 0;
  double entropy_change = 0.0;
  for (const PlacedSample& sample : placed) {
    packed += tables.packedAgreement(sample.class_row + classes[sample.index]);
    entropy_change += tables.entropyChange(sample.code, codes[sample.index]);
  }
  return unpacked(packed, entropy_change);
}

GridTransform shifted(const GridTransform& T, int dx, int dy) {
  GridTransform result = T;
  result.t_cells += Eigen::Vector2d(dx, dy);
  return result;
}

}  // namespace

ComparisonTables::ComparisonTables(const SimilaritySettings& settings)
    : similarity_(kCodeCount * kCodeCount, 0), entropy_change_(kCodeCount * kCodeCount, 0.0f) {
  std::array<double, kCodeCount> log_odds{};
  for (int code = 0; code <= 100; ++code) {
    class_[static_cast<std::size_t>(code)] =
        code >= settings.occupied_threshold ? 2 : (code <= settings.free_threshold ? 1 : 0);
    const double p =
        std::clamp(code / 100.0, 1.0 - settings.cell_certainty, settings.cell_certainty);
    cell_entropy_[static_cast<std::size_t>(code)] = binaryEntropy(p);
    log_odds[static_cast<std::size_t>(code)] = std::log(p / (1.0 - p));
  }
  for (int a = 0; a <= 100; ++a) {
    for (int b = 0; b <= 100; ++b) {
      const std::size_t i = index(static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(b));
      const auto class_a = class_[static_cast<std::size_t>(a)];
      const auto class_b = class_[static_cast<std::size_t>(b)];
      if (class_a != 0 && class_b != 0) {
        similarity_[i] = class_a == class_b ? 1 : -1;
        packed_[static_cast<std::size_t>(3 * class_a + class_b)] =
            class_a == class_b ? 1u : (std::uint64_t{1} << 32);
      }
      const double fused = 1.0 / (1.0 + std::exp(-(log_odds[static_cast<std::size_t>(a)] +
                                                   log_odds[static_cast<std::size_t>(b)])));
      entropy_change_[i] =
          static_cast<float>(binaryEntropy(fused) - cell_entropy_[static_cast<std::size_t>(a)] -
                             cell_entropy_[static_cast<std::size_t>(b)]);
    }
  }
}

std::vector<CellSample> knownCells(const GridMap& map, const ComparisonTables& tables) {
  std::vector<CellSample> samples;
  samples.reserve(map.cells.size() / 2);
  for (int y = 0; y < map.geometry.height; ++y) {
    const std::int8_t* row = &map.cells[map.geometry.index(0, y)];
    for (int x = 0; x < map.geometry.width; ++x) {
      const std::uint8_t code = codeOf(row[x]);
      if (tables.isKnown(code)) {
        samples.push_back({x, y, code});
      }
    }
  }
  return samples;
}

KnownCellSampler::KnownCellSampler(const std::vector<CellSample>& known,
                                   const ComparisonTables& tables)
    : known_(known) {
  for (std::size_t i = 0; i < known.size(); ++i) {
    (tables.isOccupied(known[i].code) ? occupied_ : free_).push_back(i);
  }
}

std::vector<std::size_t> KnownCellSampler::picks(const std::vector<std::size_t>& cells, int count) {
  // The j-th pick is the first of the class's cells at or after the running share
  // next_j = next_(j-1) + step, and after the pick before it.
  const auto size = static_cast<double>(cells.size());
  const double step = std::max(1.0, size / std::max(1, count));
  std::vector<std::size_t> picked;
  double next = 0.0;
  double at = 0.0;  // the class's cell number of the next possible pick
  while (true) {
    at = std::max(at, std::ceil(next));
    if (at >= size) {
      return picked;
    }
    picked.push_back(cells[static_cast<std::size_t>(at)]);
    at += 1.0;
    next += step;
  }
}

std::vector<CellSample> KnownCellSampler::sample(int occupied_count, int free_count) const {
  const std::vector<std::size_t> occupied = picks(occupied_, occupied_count);
  const std::vector<std::size_t> free = picks(free_, free_count);
  std::vector<std::size_t> positions(occupied.size() + free.size());
  std::merge(occupied.begin(), occupied.end(), free.begin(), free.end(), positions.begin());
  std::vector<CellSample> samples;
  samples.reserve(positions.size());
  for (const std::size_t position : positions) {
    samples.push_back(known_[position]);
  }
  return samples;
}

std::vector<CellSample> sampleKnownCells(const std::vector<CellSample>& known,
                                         const ComparisonTables& tables, int occupied_count,
                                         int free_count) {
  return KnownCellSampler(known, tables).sample(occupied_count, free_count);
}

CodeImage codeImage(const GridMap& map, int pad, const ComparisonTables& tables) {
  CodeImage image;
  image.pad = pad;
  image.codes = cv::Mat(map.geometry.height + 2 * pad, map.geometry.width + 2 * pad, CV_8U,
                        cv::Scalar(kUnknownCode));
  image.classes = cv::Mat(image.codes.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < map.geometry.height; ++y) {
    auto* row = image.codes.ptr<std::uint8_t>(y + pad) + pad;
    auto* class_row = image.classes.ptr<std::uint8_t>(y + pad) + pad;
    for (int x = 0; x < map.geometry.width; ++x) {
      row[x] = codeOf(map.at(x, y));
      class_row[x] = static_cast<std::uint8_t>(tables.classOf(row[x]));
    }
  }
  cv::dilate(image.classes == 2, image.near_occupied, cv::Mat::ones(3, 3, CV_8U));
  cv::dilate(image.classes == 0, image.near_unknown, cv::Mat::ones(3, 3, CV_8U));
  return image;
}

double verificationIndex(const Agreement& agreement) {
  const long long overlap = agreement.overlap();
  return overlap > 0 ? static_cast<double>(agreement.agreement) / static_cast<double>(overlap)
                     : 0.0;
}

Agreement compareAt(const std::vector<CellSample>& samples, const CodeImage& to,
                    const GridTransform& T_to_from, const ComparisonTables& tables,
                    bool with_entropy) {
  // place() and compareShifted() at no shift in one pass, without storing the placed samples.
  CellPlacer placer(T_to_from, to, 0);
  const std::uint8_t* classes = to.classes.ptr<std::uint8_t>(0);
  const std::uint8_t* codes = to.codes.ptr<std::uint8_t>(0);
  std::uint64_t packed = 0;
  double entropy_change = 0.0;
  for (const CellSample& sample : samples) {
    const std::ptrdiff_t index = placer.index(sample);
    if (index < 0) {
      continue;
    }
    packed += tables.packedAgreement(3 * tables.classOf(sample.code) + classes[index]);
    if (with_entropy) {
      entropy_change += tables.entropyChange(sample.code, codes[index]);
    }
  }
  return unpacked(packed, entropy_change);
}

bool disagreementRateExceeds(const std::vector<CellSample>& samples, const CodeImage& to,
                             const GridTransform& T_to_from, const ComparisonTables& tables,
                             double rate) {
  constexpr std::size_t kChunk = 2048;  // samples compared between two looks at the bound
  CellPlacer placer(T_to_from, to, 0);
  const std::uint8_t* classes = to.classes.ptr<std::uint8_t>(0);
  std::uint64_t packed = 0;
  for (std::size_t begin = 0; begin < samples.size(); begin += kChunk) {
    const std::size_t end = std::min(samples.size(), begin + kChunk);
    for (std::size_t i = begin; i < end; ++i) {
      const std::ptrdiff_t index = placer.index(samples[i]);
      if (index >= 0) {
        packed += tables.packedAgreement(3 * tables.classOf(samples[i].code) + classes[index]);
      }
    }
    // The least the rate can end at: every sample left lands and agrees.
    const Agreement so_far = unpacked(packed, 0.0);
    const double most_overlap =
        static_cast<double>(so_far.overlap()) + static_cast<double>(samples.size() - end);
    if (end < samples.size() && static_cast<double>(so_far.disagreement) > rate * most_overlap) {
      return true;
    }
  }
  return 1.0 - verificationIndex(unpacked(packed, 0.0)) > rate;
}

TranslationSearch searchTranslation(const std::vector<CellSample>& samples, const CodeImage& to,
                                    const GridTransform& T_to_from, int delta,
                                    const ComparisonTables& tables, bool with_entropy, int step) {
  step = std::max(1, step);
  const int reach = std::clamp(delta, 0, std::max(0, to.pad - 1)) / step;  // in steps
  const int side = 2 * reach + 1;
  const std::vector<PlacedSample> placed = place(samples, to, T_to_from, reach * step, tables);
  std::vector<Agreement> sums;
  sums.reserve(static_cast<std::size_t>(side * side));
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const std::ptrdiff_t shift =
          static_cast<std::ptrdiff_t>(dy * step) * to.codes.cols + dx * step;
      sums.push_back(with_entropy ? compareShifted(placed, to, shift, tables)
                                  : countShifted(placed, to, shift, tables));
    }
  }
  std::size_t best = 0;
  std::size_t least = 0;
  for (std::size_t i = 1; i < sums.size(); ++i) {
    best = sums[i].similarity() > sums[best].similarity() ? i : best;
    least = sums[i].entropy_change < sums[least].entropy_change ? i : least;
  }
  const auto shiftOf = [&](std::size_t i) {
    return step * cv::Point(static_cast<int>(i) % side - reach, static_cast<int>(i) / side - reach);
  };
  TranslationSearch search;
  search.at_best_similarity = sums[best];
  search.at_least_entropy = sums[least];
  search.best_similarity = shifted(T_to_from, shiftOf(best).x, shiftOf(best).y);
  search.least_entropy = shifted(T_to_from, shiftOf(least).x, shiftOf(least).y);
  search.runner_up_similarity = sums[best].similarity();
  bool found = false;
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const cv::Point gap = shiftOf(i) - shiftOf(best);
    if (std::max(std::abs(gap.x), std::abs(gap.y)) >= kRunnerUpCells &&
        (!found || sums[i].similarity() > search.runner_up_similarity)) {
      search.runner_up_similarity = sums[i].similarity();
      found = true;
    }
  }
  return search;
}

StructureAgreement structureAgreement(const std::vector<CellSample>& samples, const CodeImage& to,
                                      const GridTransform& T_to_from,
                                      const ComparisonTables& tables) {
  StructureAgreement sums;
  const std::uint8_t* classes = to.classes.ptr<std::uint8_t>(0);
  const std::uint8_t* near = to.near_occupied.ptr<std::uint8_t>(0);
  const std::uint8_t* frontier = to.near_unknown.ptr<std::uint8_t>(0);
  for (const PlacedSample& sample : place(samples, to, T_to_from, 0, tables)) {
    if (sample.class_row == 6 && classes[sample.index] != 0) {
      if (near[sample.index] != 0) {
        ++sums.near;
      } else {
        ++sums.far;
        sums.frontier += frontier[sample.index] != 0 ? 1 : 0;
      }
    }
  }
  return sums;
}

Eigen::Vector2d knownCentroid(const GridMap& map) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double known = 0.0;
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      if (map.at(x, y) != GridMap::kUnknown) {
        sum += Eigen::Vector2d(x, y);
        known += 1.0;
      }
    }
  }
  return sum / std::max(known, 1.0);
}

double mapEntropy(const GridMap& map, const ComparisonTables& tables) {
  double entropy = 0.0;
  for (const std::int8_t value : map.cells) {
    const std::uint8_t code = codeOf(value);
    if (code != kUnknownCode) {
      entropy += tables.cellEntropy(code);
    }
  }
  return entropy;
}

double mergedEntropy(double entropy_from, double entropy_to, const Agreement& full_comparison) {
  return entropy_from + entropy_to + full_comparison.entropy_change;
}

}  // namespace mrslam::fusion
