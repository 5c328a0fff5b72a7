#pragma once
// Private stages of SeedMerger (seed_merger.hpp summarises the pipeline): each stage is a
// function of the prepared maps, so merge() reads as the list of blocks.

#include <random>
#include <vector>

#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion::seed {

/// What the pipeline derives from one map before the two are compared.
struct PreparedMap {
  cv::Mat occupied;                           ///< block 1 input
  cv::Mat edges;                              ///< after blocks 1-2
  std::vector<cv::Point> edge_cells;          ///< non-zero cells of `edges`
  cv::Mat radon;                              ///< block 7.1, of `edge_cells`
  std::vector<double> radon_profile;          ///< block 7.2
  std::vector<Segment> segments;              ///< verified segments (block 4)
  std::vector<Segment> reversed;              ///< the same walked backwards (block 5)
  std::vector<SegmentHistograms> histograms;  ///< of `segments`
};

/// Blocks 1-2.
void prepareEdges(const GridMap& map, const SeedMergerSettings& settings, PreparedMap& prepared);

/// Blocks 7.1-7.2: the Radon image and profile of the edges.
void prepareRadon(const SeedMergerSettings& settings, PreparedMap& prepared);

/// Blocks 3-4: random starts until `max_segments` verified segments or `segment_trials` tries.
void sampleSegments(const SeedMergerSettings& settings, std::mt19937& random,
                    PreparedMap& prepared);

/// A pair of segments, one per map, and how they match.
struct PairCandidate {
  int from = 0;
  int to = 0;
  SegmentMatch match;
};

/// Block 5: the `pose_trials` best pairs, best first.
std::vector<PairCandidate> rankPairs(const PreparedMap& from, const PreparedMap& to,
                                     const SeedMergerSettings& settings);

/// A candidate transform and its coarse score.
struct Hypothesis {
  GridTransform T_to_from;
  double coarse_score = 0.0;
};

/// The coarse score (step 5 of seed_merger.hpp).
class CoarseScorer {
 public:
  CoarseScorer(const PreparedMap& from, const GridMap& to, const SeedMergerSettings& settings);
  double score(const GridTransform& T_to_from) const;

 private:
  std::vector<cv::Point> samples_;  // occupied cells of `from`
  cv::Mat classes_;                 // of `to`: 2 near occupied, 1 free, 0 unknown
};

/// Blocks 6-7 for the ranked pairs: tuned, scored hypotheses (unsorted).
std::vector<Hypothesis> poseHypotheses(const std::vector<PairCandidate>& pairs,
                                       const PreparedMap& from, const PreparedMap& to,
                                       const std::vector<double>& radon_correlation,
                                       const CoarseScorer& scorer,
                                       const SeedMergerSettings& settings);

/// The `count` best hypotheses, no two within 3 cells and 2° of each other.
std::vector<Hypothesis> bestDistinct(std::vector<Hypothesis> hypotheses, int count);

/// The inputs of block 8 prepared once per merge.
struct SearchInputs {
  std::vector<CellSample> coarse_samples;                ///< an even sample of `from`'s known cells
  std::vector<CellSample> fine_samples;                  ///< a denser sample for the ±1 cell steps
  std::vector<CellSample> all_samples;                   ///< every known cell of `from`
  Eigen::Vector2d pivot_from = Eigen::Vector2d::Zero();  ///< centre of `from`'s known cells
  CodeImage to;
  std::vector<CellSample> occupied_to;  ///< occupied cells of `to` (structure check, reversed)
  CodeImage from;                       ///< `from` as codes (structure check, reversed)
};

/// Block 8 for one hypothesis: the best shift within ±δ on the coarse samples.
TranslationSearch searchAround(const GridTransform& T_to_from, const SearchInputs& inputs,
                               const ComparisonTables& tables, const SeedMergerSettings& settings);

/// A hypothesis after block 8's search.
struct Candidate {
  GridTransform T_to_from;
  long long similarity = 0;  ///< agr - dis on the search samples
  double structure = 0.0;    ///< structure agreement on the search samples
};

/// Block 8 on the `refined_hypotheses` best distinct hypotheses; candidates ordered best first:
/// those whose walls meet walls (structure ≥ min_structure_agreement) before the others, each
/// group by similarity.
std::vector<Candidate> searchCandidates(const std::vector<Hypothesis>& hypotheses,
                                        const SearchInputs& inputs, const ComparisonTables& tables,
                                        const SeedMergerSettings& settings);

/// agr - dis of the best candidate after the first that meets the structure bar and puts
/// `from`'s known cells elsewhere (more than 10 cells away at their centre), relative to the
/// first's; 0 without one. Near 1: two different transforms explain the overlap equally well.
double rivalShare(const std::vector<Candidate>& candidates, const SearchInputs& inputs,
                  const SeedMergerSettings& settings);

/// Merges two ordered candidate lists into one, in the same order.
std::vector<Candidate> mergeCandidates(std::vector<Candidate> a, const std::vector<Candidate>& b,
                                       const SeedMergerSettings& settings);

/// The chosen transform with the figures of block 9.
struct Refined {
  GridTransform T_to_from;      ///< best similarity
  GridTransform least_entropy;  ///< least merged entropy over the same shifts
  Agreement full;               ///< all known cells at T_to_from
  double structure = 0.0;       ///< the lesser structure agreement of the two directions
  double entropy_gap_cells = 0.0;
  double translation_ambiguity = 1.0;  ///< runner-up / best agr - dis within ±δ
  double rival_share = 0.0;            ///< rivalShare() of the candidates
};

/// Rotation polish (step 7 of seed_merger.hpp), block 8 again at the polished angle, then ±1 cell
/// on all known cells for both the best similarity and the least entropy.
Refined finalize(const GridTransform& T_to_from, const SearchInputs& inputs,
                 const ComparisonTables& tables, const SeedMergerSettings& settings);

/// Step 9 of seed_merger.hpp: `T_to_from` refined by point-to-point ICP of `from`'s occupied
/// cells onto `to`'s (nearest wall within wall_icp_distance_cells); unchanged when too few walls
/// meet.
GridTransform refineOnWalls(const GridTransform& T_to_from, const SearchInputs& inputs,
                            const ComparisonTables& tables, const SeedMergerSettings& settings);

/// Step 8 of seed_merger.hpp: hypotheses from global Radon rotations and a coarse correlation
/// over all translations.
std::vector<Hypothesis> fallbackHypotheses(const PreparedMap& from, const PreparedMap& to,
                                           const GridMap& to_map,
                                           const std::vector<double>& radon_correlation,
                                           const CoarseScorer& scorer,
                                           const SeedMergerSettings& settings);

}  // namespace mrslam::fusion::seed
