#include "mrslam/fusion/merge/merge_cases.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kAttemptsPerCase = 2000;

/// Seeded draws that give the same numbers with every standard library.
class Draw {
 public:
  explicit Draw(std::uint32_t seed) : engine_(seed) {}
  double uniform(double low, double high) {
    return low + (high - low) * (static_cast<double>(engine_()) / 4294967296.0);
  }
  int integer(int low, int high) {  ///< inclusive
    return low + static_cast<int>(engine_() % static_cast<std::uint32_t>(high - low + 1));
  }

 private:
  std::mt19937 engine_;
};

/// Known-cell counts of any window in O(1), from a summed-area table.
class KnownCounter {
 public:
  explicit KnownCounter(const GridMap& map)
      : width_(map.geometry.width), height_(map.geometry.height) {
    sums_.assign(static_cast<std::size_t>(width_ + 1) * static_cast<std::size_t>(height_ + 1), 0);
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) {
        sum(x + 1, y + 1) = sum(x, y + 1) + sum(x + 1, y) - sum(x, y) + (map.at(x, y) >= 0);
      }
    }
  }
  /// Known cells in [x0, x1) × [y0, y1), clipped to the map.
  std::size_t count(int x0, int y0, int x1, int y1) const {
    x0 = std::clamp(x0, 0, width_);
    x1 = std::clamp(x1, 0, width_);
    y0 = std::clamp(y0, 0, height_);
    y1 = std::clamp(y1, 0, height_);
    if (x1 <= x0 || y1 <= y0) {
      return 0;
    }
    return sumAt(x1, y1) - sumAt(x0, y1) - sumAt(x1, y0) + sumAt(x0, y0);
  }
  std::size_t count(const CropSpec& w) const {
    return count(w.corner.x(), w.corner.y(), w.corner.x() + w.size, w.corner.y() + w.size);
  }
  double overlap(const CropSpec& a, const CropSpec& b) const {
    const std::size_t smaller = std::min(count(a), count(b));
    const int x0 = std::max(a.corner.x(), b.corner.x());
    const int y0 = std::max(a.corner.y(), b.corner.y());
    const int x1 = std::min(a.corner.x() + a.size, b.corner.x() + b.size);
    const int y1 = std::min(a.corner.y() + a.size, b.corner.y() + b.size);
    return smaller == 0 ? 0.0
                        : static_cast<double>(count(x0, y0, x1, y1)) / static_cast<double>(smaller);
  }

 private:
  std::size_t& sum(int x, int y) {
    return sums_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_ + 1) +
                 static_cast<std::size_t>(x)];
  }
  std::size_t sumAt(int x, int y) const {
    return sums_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_ + 1) +
                 static_cast<std::size_t>(x)];
  }
  int width_;
  int height_;
  std::vector<std::size_t> sums_;
};

/// A source map with its known-cell table and the bounding box of its known cells.
struct PreparedSource {
  const SourceMap* source;
  KnownCounter known;
  Eigen::Vector2i low;
  Eigen::Vector2i high;
};

PreparedSource prepare(const SourceMap& source) {
  PreparedSource prepared{&source, KnownCounter(source.map), Eigen::Vector2i::Zero(),
                          Eigen::Vector2i::Zero()};
  const GridGeometry& g = source.map.geometry;
  Eigen::Vector2i low(g.width, g.height);
  Eigen::Vector2i high(-1, -1);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      if (source.map.at(x, y) >= 0) {
        low = low.cwiseMin(Eigen::Vector2i(x, y));
        high = high.cwiseMax(Eigen::Vector2i(x, y));
      }
    }
  }
  prepared.low = low;
  prepared.high = high.cwiseMax(low);
  return prepared;
}

/// Crop side along one axis: at least the turned window's extent, of the window's parity (so a
/// crop turned by 0 is an exact shifted copy).
int turnedSide(int size, double theta_rad) {
  const double extent = size * (std::abs(std::cos(theta_rad)) + std::abs(std::sin(theta_rad)));
  const int side = static_cast<int>(std::ceil(extent - 1e-9));
  return side + ((side - size) % 2 != 0 ? 1 : 0);
}

/// A window of a random side centred at `centre`, turned and padded at random.
CropSpec drawSpec(Draw& draw, const CaseSettings& settings, const Eigen::Vector2d& centre) {
  CropSpec spec;
  spec.size = draw.integer(settings.min_size, settings.max_size);
  spec.corner = (centre - Eigen::Vector2d::Constant(spec.size / 2.0)).array().round().cast<int>();
  spec.theta_rad = draw.uniform(-kPi, kPi);
  spec.pad_low =
      Eigen::Vector2i(draw.integer(0, settings.max_pad), draw.integer(0, settings.max_pad));
  spec.pad_high =
      Eigen::Vector2i(draw.integer(0, settings.max_pad), draw.integer(0, settings.max_pad));
  return spec;
}

Eigen::Vector2d drawKnownCentre(Draw& draw, const PreparedSource& source) {
  return Eigen::Vector2d(draw.uniform(source.low.x(), source.high.x()),
                         draw.uniform(source.low.y(), source.high.y()));
}

/// Moves window B away from A's centre along a random direction until the overlap falls to the
/// target; false when the crossing misses the tolerance or B holds too few known cells.
bool placeSecondWindow(Draw& draw, const PreparedSource& source, const CaseSettings& settings,
                       const CropSpec& a, double target, CropSpec& b) {
  const Eigen::Vector2d centre = a.corner.cast<double>() + Eigen::Vector2d::Constant(a.size / 2.0);
  const double direction = draw.uniform(-kPi, kPi);
  const Eigen::Vector2d step(std::cos(direction), std::sin(direction));
  const Eigen::Vector2d half = Eigen::Vector2d::Constant(b.size / 2.0);
  for (int d = 0; d <= a.size + b.size; ++d) {
    b.corner = (centre + d * step - half).array().round().cast<int>();
    const double overlap = source.known.overlap(a, b);
    if (overlap <= target) {
      return target - overlap <= settings.overlap_tolerance &&
             source.known.count(b) >= settings.min_known;
    }
  }
  return false;
}

MergeCase positiveCase(Draw& draw, const std::vector<PreparedSource>& sources,
                       const CaseSettings& settings, double target) {
  for (int attempt = 0; attempt < kAttemptsPerCase; ++attempt) {
    const PreparedSource& source =
        sources[static_cast<std::size_t>(draw.integer(0, static_cast<int>(sources.size()) - 1))];
    const CropSpec a = drawSpec(draw, settings, drawKnownCentre(draw, source));
    CropSpec b = drawSpec(draw, settings, Eigen::Vector2d::Zero());
    if (source.known.count(a) < settings.min_known ||
        !placeSecondWindow(draw, source, settings, a, target, b)) {
      continue;
    }
    return makeCase(*source.source, a, *source.source, b);
  }
  throw std::invalid_argument("merge cases: no window pair reaches an overlap of " +
                              std::to_string(target) + " with enough known cells");
}

MergeCase negativeCase(Draw& draw, const std::vector<PreparedSource>& sources,
                       const CaseSettings& settings) {
  const int last = static_cast<int>(sources.size()) - 1;
  for (int attempt = 0; attempt < kAttemptsPerCase; ++attempt) {
    const PreparedSource& first = sources[static_cast<std::size_t>(draw.integer(0, last))];
    const PreparedSource& second = sources[static_cast<std::size_t>(draw.integer(0, last))];
    const CropSpec a = drawSpec(draw, settings, drawKnownCentre(draw, first));
    const CropSpec b = drawSpec(draw, settings, drawKnownCentre(draw, second));
    if (first.source->building != second.source->building &&
        first.known.count(a) >= settings.min_known && second.known.count(b) >= settings.min_known) {
      return makeCase(*first.source, a, *second.source, b);
    }
  }
  throw std::invalid_argument("merge cases: negative cases need maps of two buildings");
}

}  // namespace

GridTransform compose(const GridTransform& T2, const GridTransform& T1) {
  GridTransform result;
  result.theta_rad = T1.theta_rad + T2.theta_rad;
  result.t_cells = T2.apply(T1.t_cells);
  return result;
}

Crop cutCrop(const GridMap& source, const CropSpec& spec) {
  const int side = turnedSide(spec.size, spec.theta_rad);
  GridGeometry geometry = source.geometry;
  geometry.width = spec.pad_low.x() + side + spec.pad_high.x();
  geometry.height = spec.pad_low.y() + side + spec.pad_high.y();
  geometry.origin_m = Eigen::Vector2d::Zero();
  Crop crop{GridMap(geometry, GridMap::kUnknown), GridTransform()};
  const Eigen::Vector2d window_centre =
      spec.corner.cast<double>() + Eigen::Vector2d::Constant((spec.size - 1) / 2.0);
  const Eigen::Vector2d crop_centre =
      spec.pad_low.cast<double>() + Eigen::Vector2d::Constant((side - 1) / 2.0);
  // q = R (p − c_window) + c_crop.
  GridTransform turn;
  turn.theta_rad = spec.theta_rad;
  crop.T_crop_source.theta_rad = spec.theta_rad;
  crop.T_crop_source.t_cells = crop_centre - turn.apply(window_centre);
  const GridTransform T_source_crop = crop.T_crop_source.inverse();
  for (int y = 0; y < geometry.height; ++y) {
    for (int x = 0; x < geometry.width; ++x) {
      const Eigen::Vector2d p = T_source_crop.apply(Eigen::Vector2d(x, y));
      const Eigen::Vector2i cell = p.array().round().cast<int>();
      const Eigen::Vector2i offset = cell - spec.corner;
      if (offset.minCoeff() >= 0 && offset.maxCoeff() < spec.size &&
          source.geometry.contains(cell.x(), cell.y())) {
        crop.map.at(x, y) = source.at(cell.x(), cell.y());
      }
    }
  }
  return crop;
}

MergeCase makeCase(const SourceMap& source_a, const CropSpec& a, const SourceMap& source_b,
                   const CropSpec& b) {
  MergeCase merge_case;
  merge_case.source_a = source_a.name;
  merge_case.source_b = source_b.name;
  merge_case.spec_a = a;
  merge_case.spec_b = b;
  Crop crop_a = cutCrop(source_a.map, a);
  Crop crop_b = cutCrop(source_b.map, b);
  merge_case.a = std::move(crop_a.map);
  merge_case.b = std::move(crop_b.map);
  merge_case.T_b_a = compose(crop_b.T_crop_source, crop_a.T_crop_source.inverse());
  merge_case.positive = source_a.name == source_b.name;
  merge_case.overlap = merge_case.positive ? windowOverlap(source_a.map, a, b) : 0.0;
  return merge_case;
}

std::size_t knownCellsIn(const GridMap& map, const Eigen::Vector2i& corner, int size) {
  std::size_t known = 0;
  for (int y = corner.y(); y < corner.y() + size; ++y) {
    for (int x = corner.x(); x < corner.x() + size; ++x) {
      known += map.geometry.contains(x, y) && map.at(x, y) >= 0;
    }
  }
  return known;
}

double windowOverlap(const GridMap& source, const CropSpec& a, const CropSpec& b) {
  return KnownCounter(source).overlap(a, b);
}

std::vector<MergeCase> generateCases(const std::vector<SourceMap>& sources,
                                     const CaseSettings& settings) {
  std::vector<PreparedSource> prepared;
  for (const SourceMap& source : sources) {
    prepared.push_back(prepare(source));
  }
  if (prepared.empty()) {
    throw std::invalid_argument("merge cases: no source maps");
  }
  Draw draw(settings.seed);
  std::vector<MergeCase> cases;
  for (int i = 0; i < settings.positive_cases; ++i) {
    const double band_low = 0.2 + 0.2 * (i % 3);
    cases.push_back(positiveCase(draw, prepared, settings, draw.uniform(band_low, band_low + 0.2)));
  }
  for (int i = 0; i < settings.negative_cases; ++i) {
    cases.push_back(negativeCase(draw, prepared, settings));
  }
  for (std::size_t i = 0; i < cases.size(); ++i) {
    cases[i].id = static_cast<int>(i);
  }
  return cases;
}

CaseError caseError(const MergeCase& merge_case, const GridTransform& T_b_a) {
  const Eigen::Vector2d centroid = knownCentroid(merge_case.a);
  CaseError error;
  const double difference = T_b_a.theta_rad - merge_case.T_b_a.theta_rad;
  error.angle_rad = std::abs(std::remainder(difference, 2.0 * kPi));
  error.distance_cells = (T_b_a.apply(centroid) - merge_case.T_b_a.apply(centroid)).norm();
  return error;
}

bool isCorrect(const CaseError& error) {
  return error.distance_cells <= kSuccessDistanceCells && error.angle_rad <= kSuccessAngleRad;
}

bool isNearMiss(const CaseError& error) {
  return !isCorrect(error) && error.distance_cells <= kNearMissDistanceCells &&
         error.angle_rad <= kNearMissAngleRad;
}

}  // namespace mrslam::fusion
