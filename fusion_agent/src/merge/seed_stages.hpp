#pragma once
// Private stages of SeedMerger (seed_merger.hpp summarises the pipeline): each stage is a
// function of the prepared maps, so merge() reads as the list of blocks.

#include <limits>
#include <memory>
#include <optional>
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

/// The step of the pipeline that proposed a transform (MergeResult::method names it).
enum class Stage {
  kSegments,
  kRadonFallback,
  kGlobalSearch,
  kFineGlobalSearch,
  kFreeGlobalSearch,
  kGiven
};

/// "seed", "seed/radon-fallback", "seed/global-search", "seed/global-search-fine",
/// "seed/global-search-free" (the global search's score with free agreement) or "seed/given"
/// (hypotheses from another method, SeedMerger::judgeHypotheses).
const char* stageName(Stage stage);

/// A candidate transform and its coarse score.
struct Hypothesis {
  GridTransform T_to_from;
  double coarse_score = 0.0;
  Stage stage = Stage::kSegments;
};

/// The coarse score (step 5 of seed_merger.hpp).
class CoarseScorer {
 public:
  CoarseScorer(const PreparedMap& from, const GridMap& to, const SeedMergerSettings& settings);
  double score(const GridTransform& T_to_from) const;
  /// score() at every shift (dx, dy) of T_to_from, dx and dy = -reach, -reach + step, ... up to
  /// reach, in row order (dy, then dx); the samples are placed once for all shifts.
  std::vector<double> scores(const GridTransform& T_to_from, int reach, int step) const;

 private:
  std::vector<cv::Point> samples_;  // occupied cells of `from`
  cv::Mat balance_;                 // CV_8S of `to`: +1 near occupied, -1 free, 0 unknown
};

/// The best coarse score among the shifts of T_to_from within ±reach cells, every `step` cells
/// (T_to_from itself when nothing scores above -2), labelled with `stage`.
Hypothesis bestShift(const GridTransform& T_to_from, int reach, int step,
                     const CoarseScorer& scorer, Stage stage);

/// Blocks 6-7 for the ranked pairs: tuned, scored hypotheses (unsorted).
std::vector<Hypothesis> poseHypotheses(const std::vector<PairCandidate>& pairs,
                                       const PreparedMap& from, const PreparedMap& to,
                                       const std::vector<double>& radon_correlation,
                                       const CoarseScorer& scorer,
                                       const SeedMergerSettings& settings);

/// The `count` best hypotheses, no two within 3 cells and 2° of each other.
std::vector<Hypothesis> bestDistinct(std::vector<Hypothesis> hypotheses, int count);

/// The occupied ones among `samples`, as cells (column, row).
std::vector<Eigen::Vector2d> occupiedCells(const std::vector<CellSample>& samples,
                                           const ComparisonTables& tables);

/// For every cell near a map's walls (within 8 cells of their bounding box), the nearest wall
/// cell, by a labelled distance transform: the wall ICP's lookup (cell_icp.cpp).
class NearestWall {
 public:
  explicit NearestWall(const std::vector<CellSample>& walls);
  /// The wall cell nearest to `point` within `max_distance`, if any.
  std::optional<Eigen::Vector2d> near(const Eigen::Vector2d& point, double max_distance) const;

 private:
  cv::Point origin_;
  cv::Mat labels_;
  std::vector<cv::Point> wall_of_label_;
};

/// The inputs of block 8 prepared once per merge.
struct SearchInputs {
  std::vector<CellSample> coarse_samples;                ///< an even sample of `from`'s known cells
  std::vector<CellSample> fine_samples;                  ///< a denser sample for the ±1 cell steps
  std::vector<CellSample> all_samples;                   ///< every known cell of `from`
  std::vector<CellSample> all_to;                        ///< every known cell of `to`
  Eigen::Vector2d pivot_from = Eigen::Vector2d::Zero();  ///< centre of `from`'s known cells
  CodeImage to;
  double entropy_from = 0.0;            ///< mapEntropy of `from` (block 9)
  double entropy_to = 0.0;              ///< mapEntropy of `to`
  std::vector<CellSample> occupied_to;  ///< occupied cells of `to` (structure check, reversed)
  std::vector<CellSample> occupied_to_samples;    ///< an even sample of them (wall balance)
  std::vector<CellSample> occupied_from_samples;  ///< occupied cells of coarse_samples (same)
  CodeImage from;                                 ///< `from` as codes (structure check, reversed)
  cv::Mat wall_balance_to;                        ///< wallBalanceImage(to) (wall anchoring)
  cv::Mat wall_balance_from;                      ///< wallBalanceImage(from) (same, reversed)
  std::shared_ptr<const NearestWall> nearest_wall_to;  ///< occupied_to's (wall ICP), built once
  std::vector<Eigen::Vector2d> occupied_from;          ///< every occupied cell of `from` (wall ICP)
  std::shared_ptr<const WallField> walls_from;  ///< with settle_alignment: `from`'s wall field
  std::shared_ptr<const WallField> walls_to;    ///< ... and `to`'s
};

/// Block 8 for one hypothesis: the best shift within ±δ on the coarse samples.
TranslationSearch searchAround(const GridTransform& T_to_from, const SearchInputs& inputs,
                               const ComparisonTables& tables, const SeedMergerSettings& settings);

/// A hypothesis after block 8's search.
struct Candidate {
  GridTransform T_to_from;
  Stage stage = Stage::kSegments;
  long long similarity = 0;        ///< agr - dis on the search samples
  double structure = 0.0;          ///< the lesser structure agreement of both directions (samples)
  long long walls = 0;             ///< wallBalance() (ranks the candidates with `wall_ranking`)
  double overlap_cells = 0.0;      ///< known cells in the overlap (agr + dis, all cells)
  double disagreement_rate = 0.0;  ///< 1 - V over all known cells (dis / (agr + dis))
};

/// The cells of `to` (its code image) within `reach` cells (Chebyshev) of one of its known cells.
class ReachableKnown {
 public:
  ReachableKnown(const CodeImage& to, int reach);
  /// Whether a known cell of `to` lies within `reach` of `cell` (a cell of `to`, unpadded);
  /// true off the padded image where the map's own cells lie within `reach`.
  bool at(const cv::Point& cell) const;

 private:
  cv::Mat near_known_;  // CV_8U over the padded image: non-zero within reach of a known cell
  int pad_ = 0;
  int reach_ = 0;
};

/// The most agr - dis that `samples` (known cells of `from`) can reach on `to` at T_to_from
/// shifted by whole cells within the reach of `reachable`: the samples that land within it of a
/// known cell of `to` (each agrees at most once).
long long mostSimilarity(const GridTransform& T_to_from, const std::vector<CellSample>& samples,
                         const ReachableKnown& reachable);

/// Block 8 on the `count` best distinct hypotheses; candidates ordered best first: those whose
/// walls meet walls (structure ≥ min_structure_agreement) and whose overlap reaches
/// min_overlap_cells (with `rank_by_overlap`) before the others, each group by similarity.
/// Placements whose structure agreement falls below `structure_floor` are left out unmeasured
/// (a caller that can use none of them); the others keep their order.
std::vector<Candidate> searchCandidates(
    const std::vector<Hypothesis>& hypotheses, int count, const SearchInputs& inputs,
    const ComparisonTables& tables, const SeedMergerSettings& settings,
    double structure_floor = -std::numeric_limits<double>::infinity());

/// agr - dis of the best candidate after the first that meets the structure bar and puts
/// `from`'s known cells elsewhere (more than 10 cells away at their centre), relative to the
/// first's (a dirtier one, whose walls meet walls `dirtier_rival_structure` less well and whose
/// cells disagree `dirtier_rival_rate` times as often, is passed over); 0 without one. Both are
/// compared alike: the best shift within ±1 cell on the fine samples, then agr - dis over all
/// known cells. Near 1: two different transforms explain the overlap equally well. With
/// `wall_ranking`, the larger of that and the rival's share of the first's wall balance. A
/// cleaner rival (cleanerRival()) counts as a share of 1.
double rivalShare(const std::vector<Candidate>& candidates, const SearchInputs& inputs,
                  const ComparisonTables& tables, const SeedMergerSettings& settings);

/// Rivals lie farther than this (cells) from the first candidate at the centre of `from`.
constexpr double kRivalCells = 10.0;

/// Whether a candidate farther than kRivalCells from the first meets the bars, its walls meet
/// walls at least as well as the first's and its known cells disagree at most
/// `cleaner_rival_rate` times as often (Candidate::disagreement_rate): the overlap is explained
/// more consistently elsewhere, however much smaller (a half-symmetric hall turned by 180°).
bool cleanerRival(const std::vector<Candidate>& candidates, const SearchInputs& inputs,
                  const SeedMergerSettings& settings);

/// The index of the first cleaner rival (as cleanerRival()), if any.
std::optional<std::size_t> cleanerRivalOf(const std::vector<Candidate>& candidates,
                                          const SearchInputs& inputs,
                                          const SeedMergerSettings& settings);

/// The index of the candidate that rivalShare() compares with the first, if any.
std::optional<std::size_t> rivalOf(const std::vector<Candidate>& candidates,
                                   const SearchInputs& inputs, const SeedMergerSettings& settings);

/// Merges two ordered candidate lists into one, in the same order.
std::vector<Candidate> mergeCandidates(std::vector<Candidate> a, const std::vector<Candidate>& b,
                                       const SeedMergerSettings& settings);

/// The chosen transform with the figures of block 9.
struct Refined {
  GridTransform T_to_from;         ///< best similarity
  Stage stage = Stage::kSegments;  ///< where the candidate came from
  GridTransform least_entropy;     ///< least merged entropy over the same shifts
  Agreement full;                  ///< all known cells at T_to_from
  double structure = 0.0;          ///< the lesser structure agreement of the two directions
  /// The same with the walls on the other map's frontier left out (indexOffFrontier()).
  double frontier_structure = 0.0;
  double entropy_gap_cells = 0.0;
  double translation_ambiguity = 1.0;  ///< runner-up / best agr - dis within ±δ
  double wall_ambiguity = 1.0;         ///< the wall balance's runner-up share (wall_anchor)
  double similarity_ambiguity = 1.0;   ///< agr - dis's runner-up share (wall_anchor)
  long long wall_margin = 0;           ///< the wall balance's lead over its runner-up (wall_anchor)
  double rival_share = 0.0;            ///< rivalShare() of the candidates
  std::size_t rank = 0;  ///< the candidate's place in the ranking (0: first), when judged in turn
};

/// Rotation polish (step 7 of seed_merger.hpp), block 8 again at the polished angle, then ±1 cell
/// on all known cells for both the best similarity and the least entropy.
Refined finalize(const GridTransform& T_to_from, const SearchInputs& inputs,
                 const ComparisonTables& tables, const SeedMergerSettings& settings);

/// Step 9 of seed_merger.hpp: `T_to_from` refined by point-to-point ICP of `from`'s occupied
/// cells onto `to`'s (nearest wall within wall_icp_distance_cells); unchanged when too few walls
/// meet or when `inputs` were prepared without the wall ICP (wall_icp_iterations 0).
GridTransform refineOnWalls(const GridTransform& T_to_from, const SearchInputs& inputs,
                            const SeedMergerSettings& settings);

/// Walls of `from` near walls of `to` minus those on `to`'s other known cells, plus the same of
/// `to`'s walls on `from` (wall_anchor.cpp); free cells do not count.
long long wallBalance(const GridTransform& T_to_from, const SearchInputs& inputs,
                      const ComparisonTables& tables);

/// The shift within ±reach of the largest wallBalance (the first of equals in row order, the
/// unshifted transform before all), and the runner-up at least kRunnerUpCells away (equal to
/// the best when the window has none).
struct WallSearch {
  GridTransform best;
  long long best_balance = 0;
  long long runner_up_balance = 0;
};
WallSearch anchorOnWalls(const GridTransform& T_to_from, int reach, const SearchInputs& inputs,
                         const ComparisonTables& tables);

/// Step 7's rotation polish: rotations within ±rotation_polish in rotation_polish_step steps and
/// then half steps, each with its best shift within ±1 cell by agr - dis on the coarse samples.
GridTransform polishRotation(const GridTransform& T_to_from, const SearchInputs& inputs,
                             const ComparisonTables& tables, const SeedMergerSettings& settings);

/// Step 7 with `wall_anchor` (wall_anchor.cpp): the translation by anchorOnWalls first, then the
/// rotation polish, ±1 cell by agr - dis and walls onto walls by ICP (kept when agr - dis or the
/// wall balance is at least as high), none of which can slide far; with `settle_alignment`, the
/// anchored transform aligned on both maps' walls (alignWalls) instead where V is at least as
/// high. `coarse` is block 8's ±δ
/// search around the result (for the entropy figures); the translation ambiguity is the larger
/// of the wall balance's and agr - dis's runner-up share.
Refined settleOnWalls(const GridTransform& T_to_from, const SearchInputs& inputs,
                      const ComparisonTables& tables, const SeedMergerSettings& settings,
                      TranslationSearch& coarse);

/// Step 8 of seed_merger.hpp: hypotheses from global Radon rotations and a coarse correlation
/// over all translations.
std::vector<Hypothesis> fallbackHypotheses(const PreparedMap& from, const PreparedMap& to,
                                           const GridMap& to_map,
                                           const std::vector<double>& radon_correlation,
                                           const CoarseScorer& scorer,
                                           const SeedMergerSettings& settings);

/// Step 10 of seed_merger.hpp: hypotheses of the global search (global_search.hpp), each
/// refined at full resolution by the coarse score over rotations within half a sweep step (and
/// `global_polish_step`) and translations within a coarse cell; those of the walls' score and
/// those of the score with free agreement apart, each best first.
struct GlobalHypotheses {
  std::vector<Hypothesis> by_walls;
  std::vector<Hypothesis> by_free_agreement;
};
GlobalHypotheses globalHypotheses(const GridMap& from, const GridMap& to,
                                  const CoarseScorer& scorer, const SearchInputs& inputs,
                                  const SeedMergerSettings& settings);

}  // namespace mrslam::fusion::seed
