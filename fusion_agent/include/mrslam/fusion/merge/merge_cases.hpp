#pragma once
// Known-answer merge cases cut from real maps, and the scoring of a merger on them.
//
// A case: two square windows A and B of one source map. Each window is cut out, turned about its
// centre by its own angle and placed at its own offset in a grid of its own (unknown outside the
// window). The truth T_b_a maps cells of crop A to cells of crop B; a merger is run as
// merge(from = a, to = b) and should return it.
//
// Overlap of a case: |K(A) ∩ K(B)| / min(|K(A)|, |K(B)|), where K(W) is the set of known cells of
// the source map inside window W, counted in the source map before any turning: the fraction of
// the smaller crop's known cells that the other crop also holds.
//
// A negative case cuts its two crops from maps of different buildings: any accept is false.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion {

/// A square window of a source map and how its crop is turned and placed.
struct CropSpec {
  Eigen::Vector2i corner = Eigen::Vector2i::Zero();    ///< source cell of the window's low corner
  int size = 0;                                        ///< window side, cells
  double theta_rad = 0.0;                              ///< turn of the crop about the window centre
  Eigen::Vector2i pad_low = Eigen::Vector2i::Zero();   ///< unknown margin before the window
  Eigen::Vector2i pad_high = Eigen::Vector2i::Zero();  ///< unknown margin after the window
};

/// A crop and the transform of source cells into its cells.
struct Crop {
  GridMap map;
  GridTransform T_crop_source;
};

/// Cuts a crop: each crop cell takes the nearest source cell of the window (unknown outside it).
/// With theta 0 the crop is an exact copy of the window shifted by pad_low.
Crop cutCrop(const GridMap& source, const CropSpec& spec);

/// Known cells of `map` inside a window (cells clipped to the map).
std::size_t knownCellsIn(const GridMap& map, const Eigen::Vector2i& corner, int size);
/// The overlap (defined above) of two windows of one source map; 0 if either holds no known cell.
double windowOverlap(const GridMap& source, const CropSpec& a, const CropSpec& b);

struct MergeCase {
  int id = 0;
  std::string source_a;  ///< name of the map crop A comes from
  std::string source_b;  ///< ... and crop B (another building for a negative case)
  bool positive = true;  ///< false: the crops share nothing, any accept is false
  double overlap = 0.0;  ///< positive cases: the overlap defined above
  CropSpec spec_a;       ///< how crop A was cut from source_a
  CropSpec spec_b;       ///< ... and crop B from source_b
  GridMap a;             ///< merge(from = a, to = b)
  GridMap b;
  GridTransform T_b_a;  ///< the truth (positive cases)
};

/// A named source map and the building it shows (negative cases pair different buildings).
struct SourceMap {
  std::string name;
  std::string building;
  GridMap map;
};

/// The case of two windows with their turns and pads as given (generateCases draws them). Crops
/// of one source map (same name) make a positive case with its overlap; else a negative one.
MergeCase makeCase(const SourceMap& source_a, const CropSpec& a, const SourceMap& source_b,
                   const CropSpec& b);

struct CaseSettings {
  int positive_cases = 200;  ///< spread evenly over the overlap bands 20–40, 40–60, 60–80 %
  int negative_cases = 50;
  std::uint32_t seed = 1;
  int min_size = 160;  ///< window side range, cells
  int max_size = 320;
  int max_pad = 40;                 ///< random unknown margin on each side, cells
  std::size_t min_known = 2500;     ///< known cells each crop must hold
  double overlap_tolerance = 0.02;  ///< a drawn case is kept within this of its target overlap
};

/// Builds the cases from the source maps, seeded: the same settings give the same cases.
/// Throws std::invalid_argument when no case can be cut (no source map holds enough known cells,
/// or fewer than two buildings for negative cases).
std::vector<MergeCase> generateCases(const std::vector<SourceMap>& sources,
                                     const CaseSettings& settings);

/// How far a result is from the truth of a case: the angle difference and the distance between
/// where the two transforms put the centroid of crop A's known cells.
struct CaseError {
  double angle_rad = 0.0;
  double distance_cells = 0.0;
};
CaseError caseError(const MergeCase& merge_case, const GridTransform& T_b_a);

/// T2 ∘ T1: first T1, then T2.
GridTransform compose(const GridTransform& T2, const GridTransform& T1);

/// Success: within 2 cells and 1° of the truth.
constexpr double kSuccessDistanceCells = 2.0;
constexpr double kSuccessAngleRad = 1.0 * 3.14159265358979323846 / 180.0;
bool isCorrect(const CaseError& error);

/// A wrong transform that still puts crop A in the right place, a little off: within 5 cells
/// and 3° of the truth (a merge the maps' later growth can mend). Beyond that a false accept is
/// gross: a wing along, or a turn, of the building.
constexpr double kNearMissDistanceCells = 5.0;
constexpr double kNearMissAngleRad = 3.0 * 3.14159265358979323846 / 180.0;
bool isNearMiss(const CaseError& error);

}  // namespace mrslam::fusion
