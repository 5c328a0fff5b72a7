#pragma once
// SeedMerger: the seed paper's map merging pipeline (DESIGN.md "The merge", section II of the
// seed paper), with no prior on the relative pose. Blocks 1-9 are functions of their own headers;
// the steps marked (ours) are where the description is silent or not reliable enough alone.
//
// 1. Each map: Gaussian + Canny edges of the occupied cells and middle-point edge smoothing with
//    dt (blocks 1-2, edges.hpp); the Radon image of the edges and its angular profile (block 7,
//    radon.hpp).
// 2. Each map: up to `segment_trials` random (seeded) edge cells start a segment of n points
//    (block 3, segments.hpp); the segments that pass the histogram verification (hd, ωc; block 4,
//    histograms.hpp) are kept, at most `max_segments`, duplicates dropped.
// 3. Every pair of kept segments (one per map) gets the histogram score; the best
//    `correlated_pairs` also get the D/Δ correlation, and the best `pose_trials` pairs by the
//    combined score are tried (block 5, correlation.hpp).
// 4. Each tried pair gives two approximate poses (line angles modulo π, centroids of the matched
//    spans; block 6, approximate_pose.hpp); the Radon peak near each angle tunes the rotation and
//    the translation is recomputed from the centroids at the tuned angle (block 7).
// 5. Coarse score (ours): the share of `from`'s occupied cells (`coarse_samples` of them) landing
//    within `coarse_radius_cells` of an occupied cell of `to`, minus the share landing on free
//    cells farther away. It tolerates the few cells of error of an approximate pose and ranks
//    the hypotheses; the best `refined_hypotheses` distinct ones go on.
// 6. Translation tuning (block 8, similarity.hpp): agr - dis over ±δ, every other shift and then
//    ±1 around the best, on an even sample of `search_occupied_samples` occupied and
//    `search_free_samples` free cells of `from` (ours: so that walls, not open floor, decide).
//    Candidates whose walls meet walls (structure agreement ≥ min_structure_agreement on the
//    sample) rank first, then by agr - dis. With `wall_ranking` (ours) a hypothesis is instead
//    placed by the wall balance over ±δ (walls of each map within one cell of the other's walls
//    minus those on its other known cells; wall_anchor.cpp) and ranked by it, and a rival is
//    judged by the larger of its agr - dis share and its wall balance share: agr - dis is
//    dominated by free cells and grows by sliding the overlap into shared open floor.
// 7. With `wall_anchor` (ours) the translation is first fixed by the wall balance over ±δ, and
//    the steps below move at most a cell or two from there (the ICP result is also kept when the
//    wall balance does not drop; the translation ambiguity is the larger of the two measures').
//    Rotation polish (ours): rotations within ±`rotation_polish` of the best candidate in steps of
//    `rotation_polish_step` and then half that, each with ±1 cell, keep the best agr - dis; at the
//    polished angle block 8 runs again over every shift of ±δ with the merged entropy, and ±1 cell
//    on a sample four times denser. Then (ours) walls onto walls: point-to-point ICP of `from`'s
//    occupied cells onto the nearest of `to`'s within `wall_icp_distance_cells`, kept when agr -
//    dis is at least as high there; the entropy minimum and the translation ambiguity are then
//    taken around the refined transform. It settles the last cell and degree that the discrete
//    searches leave (median error on accepted real crops 0.04 cells and 0.01° against 0.38 cells
//    and 0.12° without it).
//    With `settle_alignment` (ours) the anchored transform is also aligned on both maps' walls
//    (step 11's alignment, from the anchor, climbing from the coarse grid's best point alone) and
//    replaces the result above where V is at least as high: the acceptance's figures (structure,
//    ambiguity, entropy) are then taken at a transform a fraction of a cell from where the walls
//    meet.
// 8. Verification (block 9): V = agr / (agr + dis) over all known cells and the merged map's
//    entropy. Accepted only when V ≥ `min_verification_v`, the overlap has ≥ `min_overlap_cells`
//    known cells, the entropy minimum over the ±δ shifts lies within `entropy_agreement_cells` of
//    the best agr - dis (DESIGN's "best V": V alone favours the smallest overlaps), and (ours)
//    the structure agreement in both directions is ≥ `min_structure_agreement` (V is dominated by
//    free cells, so a wrong pose in open space scores high), or ≥ `min_structure_off_frontier`
//    with the walls on the other map's frontier left out (free cells next to unknown ones: real
//    robots leave walls seen at a grazing angle or from far unmarked, and the other robot's walls
//    land there; on the ACES and CSAIL teams that left 0.46-0.87 of the walls meeting at the
//    truth), and the best shift ≥ 3 cells from the
//    best scores at most `max_translation_ambiguity` of it (a corridor seen along its length
//    fixes no translation), and no other candidate that meets the structure bar but puts `from`
//    elsewhere scores more than `max_rival_share` of the best (a symmetric junction), nor one
//    whose walls meet walls at least as well and whose known cells disagree at most
//    `cleaner_rival_rate` times as often (a hall that looks alike turned by 180°, where the wrong
//    turn overlaps more). A transform elsewhere whose walls meet walls `dirtier_rival_structure`
//    less well and whose cells disagree `dirtier_rival_rate` times as often is no rival (a loop
//    of corridors, where the placement one corridor over covers more cells and fits them worse).
// 9. Fallback (ours, `radon_fallback`): when step 8 refuses, the `fallback_rotations` strongest
//    peaks of the Radon profile correlation, each with its other half turn, are searched over all
//    translations at once by a coarse DFT correlation (seed_fallback.cpp); its
//    `fallback_translations` best peaks per rotation join the candidates of steps 6-8.
// 10. Global search (ours, `global_search`): when step 9 still refuses, every rotation of a full
//    turn is correlated over all translations on coarse grids (global_search.hpp); the best
//    coarse transforms, refined at full resolution (seed_global.cpp), join the candidates of
//    steps 6-8 as well. When still refused, a second sweep on a finer grid (`global_fine_cells`)
//    turns only within one rotation step of the first's hypotheses; its transforms must also
//    reach V ≥ `global_fine_min_verification` (a finer grid also finds near misses of distorted
//    maps). When still refused, the first sweep's peaks of a second score that also counts free
//    cells meeting free cells (`global_free_agreement_*`, global_search.hpp step 5: overlaps of
//    open floor with few walls) join last; theirs must reach V ≥ `global_free_min_verification`.
//    MergeResult::method names the step whose candidate is returned.
// 11. Alignment (ours, `wall_alignment`): an accepted transform is moved, within ±1.5° and ±2.5
//    cells, to the best two-way agreement of the two maps' walls read between cells
//    (wall_alignment.hpp), where V does not drop; the discrete searches above leave up to a cell
//    or two and a degree at small overlaps. The exhaustive and virtual-robot mergers, which this
//    merger judges, end with the same step.
// Acceptance (ours): with `rank_by_overlap`, candidates whose overlap is below
// `min_overlap_cells` rank after the others and are no rival. The translation also counts as
// fixed when the wall balance's runner-up share is at most `decisive_wall_ambiguity` and agr -
// dis's at most `max_open_floor_ambiguity` (open floor slides along a corridor, walls do not).
// At V ≥ `walls_over_floor_min_v`, walls that fix the shift and lead their runner-up by
// `decisive_wall_margin` sampled walls fix it however flat agr - dis is, and the entropy test is
// waived: over open floor bounded by the maps' edges its minimum drifts to more overlap.
// An overlap of `small_overlap_cells` suffices when the structure agreement is at least
// `small_overlap_structure` (or `clean_small_overlap_structure` at V at least
// `clean_small_overlap_min_v`: the wrong small overlaps of two buildings fit less cleanly) and
// no rival exists. When the best candidate is refused, the next
// `judged_candidates` are judged in turn, each facing the others as rivals; one refused for its
// rival alone is judged again without it when that rival, refined, fails its own overlap, V,
// structure or entropy test or settles onto the candidate (`refined_rivals`). A candidate ranked
// after the first `late_rank` needs V ≥ `late_rank_min_verification`: the ranking put transforms
// with more walls ahead of it, and the wrong ones found that deep fit less cleanly than the truths.
// Randomness comes from `seed` only: one merge of the same maps always gives the same answer.
// Choices where the description is silent: D is the distance to the segment's total-least-
// squares line and Δ the turning angle over chords of k points; the arc histogram is that of Δ;
// hd bounds the spread of D; segments are resampled to one cell of arc length per point; the
// entropy is that of the known cells, probabilities clamped to [1-c, c], fused by log-odds.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/correlation.hpp"
#include "mrslam/fusion/merge/edges.hpp"
#include "mrslam/fusion/merge/global_search.hpp"
#include "mrslam/fusion/merge/histograms.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/neighbour_basins.hpp"
#include "mrslam/fusion/merge/radon.hpp"
#include "mrslam/fusion/merge/segments.hpp"
#include "mrslam/fusion/merge/similarity.hpp"
#include "mrslam/fusion/merge/wall_alignment.hpp"

namespace mrslam::fusion {

namespace seed {
enum class Stage;
class CoarseScorer;
struct Candidate;
struct Hypothesis;
struct Refined;
struct SearchInputs;
}  // namespace seed

/// Every setting of the seed merger; block settings are handed to the blocks as they are.
struct SeedMergerSettings {
  EdgeSettings edges;                        ///< blocks 1-2 (dt)
  SegmentSettings segments;                  ///< block 3 (n)
  SegmentVerificationSettings verification;  ///< block 4 (hd, ωc)
  CorrelationSettings correlation;           ///< block 5
  RadonSettings radon;                       ///< block 7
  SimilaritySettings similarity;             ///< blocks 8-9 (cell classes, entropy)
  int segment_trials = 200;                  ///< random segment starts tried per map
  int max_segments = 80;                     ///< verified segments kept per map
  int correlated_pairs = 500;        ///< pairs (best histogram scores) given D/Δ correlation
  int pose_trials = 60;              ///< best pairs whose approximate poses are tried
  int coarse_radius_cells = 2;       ///< coarse score: tolerance (cells) around walls
  int coarse_samples = 1500;         ///< coarse score: occupied cells of `from` sampled
  int refined_hypotheses = 3;        ///< hypotheses given the exhaustive search
  int translation_window_delta = 6;  ///< δ: translation search ±δ cells
  double rotation_polish_rad = 1.5 * M_PI / 180.0;       ///< polish: rotations tried ± this
  double rotation_polish_step_rad = 0.5 * M_PI / 180.0;  ///< polish: first step (then half)
  int search_occupied_samples = 2500;   ///< ±δ search: occupied cells of `from` sampled
  int search_free_samples = 2500;       ///< ±δ search: free cells of `from` sampled
  double min_verification_v = 0.9;      ///< V threshold: least agr / (agr + dis)
  long long min_overlap_cells = 1500;   ///< least known cells in the overlap (agr + dis)
  long long small_overlap_cells = 400;  ///< least overlap when walls all meet and no rival (0: off)
  double small_overlap_structure = 0.98;  ///< structure agreement that lets small_overlap_cells do
  /// The same for a small overlap that fits cleanly: structure ≥ clean_small_overlap_structure
  /// at V ≥ clean_small_overlap_min_v (> 1: off).
  double clean_small_overlap_structure = 0.93;
  double clean_small_overlap_min_v = 0.955;
  double min_structure_agreement = 0.89;  ///< least share of walls landing on walls
  /// ... or at least this share with the walls on the other map's frontier left out (free cells
  /// next to unknown ones: a wall that robot never marked; > 1: off).
  double min_structure_off_frontier = 0.88;
  double min_v_off_frontier = 0.98;         ///< ... where V is at least this
  double entropy_agreement_cells = 1.5;     ///< largest gap best-similarity ↔ least-entropy
  double max_translation_ambiguity = 0.95;  ///< largest runner-up / best agr - dis in ±δ
  double decisive_wall_ambiguity = 0.85;    ///< walls fix the shift: wall runner-up share ≤ this
  double max_open_floor_ambiguity = 0.975;  ///< agr - dis runner-up bar when walls fix the shift
  /// Walls outweigh open floor: at V ≥ this, walls that fix the shift (decisive_wall_ambiguity,
  /// decisive_wall_margin) fix it however flat agr - dis is, and the entropy test is waived (> 1:
  /// off).
  double walls_over_floor_min_v = 0.96;
  long long decisive_wall_margin = 45;  ///< ... and the best wall balance leads by this many walls
  /// The same for an overlap that fits more cleanly: at V ≥ clean_walls_over_floor_min_v, a lead of
  /// clean_decisive_wall_margin walls is enough (> 1: off).
  double clean_walls_over_floor_min_v = 0.99;
  long long clean_decisive_wall_margin = 15;
  double max_rival_share = 0.93;  ///< largest agr - dis of a rival transform / best
  /// A rival whose walls meet walls as well and whose known cells disagree at most this share as
  /// often as the best's refuses the best, as a rival of share 1 (0: off).
  double cleaner_rival_rate = 0.5;
  /// A transform elsewhere whose walls meet walls at least dirtier_rival_structure less well than
  /// the best's and whose known cells disagree at least dirtier_rival_rate times as often is no
  /// rival: it scores by covering more cells, not by fitting them (0: off).
  double dirtier_rival_structure = 0.03;
  double dirtier_rival_rate = 1.1;
  int judged_candidates = 3;  ///< candidates judged in turn when the best is refused
  /// A candidate ranked after the first `late_rank` (ranks 0, 1, ...) is accepted only at V ≥
  /// late_rank_min_verification: the ranking put transforms with more walls ahead of it.
  int late_rank = 3;
  double late_rank_min_verification = 0.97;
  bool wall_anchor = true;      ///< step 7: translation by walls near walls before agr - dis
  bool wall_ranking = true;     ///< candidates placed and ranked by walls, rivals judged by both
  bool rank_by_overlap = true;  ///< candidates whose overlap is below min_overlap_cells rank last
  int refined_rivals = 2;  ///< judged candidates refused for a rival alone: rivals refined in turn,
                           ///< dropped when they fail on their own or settle on the candidate
  int wall_icp_iterations = 30;          ///< final refinement: ICP of walls onto walls (0: off)
  double wall_icp_distance_cells = 3.0;  ///< final refinement: farthest wall matched
  int wall_icp_samples = 3000;           ///< final refinement: `from`'s walls matched (0: all)
  bool radon_fallback = true;            ///< try global Radon rotations when segments fail
  int fallback_rotations = 4;            ///< fallback: Radon peaks tried (× 2 half turns)
  int fallback_translations = 4;         ///< fallback: correlation peaks per rotation
  bool global_search = true;             ///< try the global search when all else is refused
  GlobalSearchSettings global;           ///< step 10 (global_search.hpp)
  double global_polish_step_rad = 0.5 * M_PI / 180.0;  ///< step 10: rotation step of the refinement
  int global_candidates = 6;        ///< step 10: refined hypotheses given the ±δ search
  int global_fine_cells = 2;        ///< finer sweep near step 10's rotations: coarse cells (0: off)
  int global_max_grid_cells = 160;  ///< step 10: longest side in blocks (the finer sweep's: twice
                                    ///< that); larger maps get larger blocks (0: no limit)
  double global_fine_min_verification = 0.96;  ///< least V of a transform of the finer sweep
  double global_free_min_verification = 0.98;  ///< least V of a transform found by free agreement
  std::uint32_t seed = 1;                      ///< seed of the random segment starts
  /// After acceptance: the walls aligned both ways (wall_alignment.hpp); also the last step of the
  /// mergers this one judges (exhaustive, virtual robot).
  WallAlignmentSettings wall_alignment;
  /// Step 7 with wall_anchor: the anchored transform also aligned on both maps' walls (the window
  /// of wall_alignment, one start), taken instead of the polished one where V is at least as high.
  bool settle_alignment = true;
};

/// Reads a `seed_merger` config section (every key optional, defaults above); angles in
/// degrees in the file (`max_turn_omega_c_deg`, `rotation_window_deg`, `radon_step_deg`).
SeedMergerSettings loadSeedMergerSettings(const Config& section);

/// Time spent in each block by the last merge.
struct SeedMergeTimings {
  using Duration = std::chrono::duration<double, std::milli>;
  Duration edges{};         ///< blocks 1-2, both maps
  Duration radon{};         ///< Radon images and profile correlation
  Duration segments{};      ///< blocks 3-4, both maps
  Duration correlation{};   ///< block 5
  Duration poses{};         ///< blocks 6-7 and the coarse score
  Duration translation{};   ///< block 8
  Duration verification{};  ///< block 9
  Duration fallback{};      ///< the Radon fallback, when it ran
  Duration global{};        ///< the global search, when it ran
  Duration alignment{};     ///< the walls aligned both ways, when accepted
};

/// How one transform fits once placed by block 8's ±δ search (SeedMerger::placedFits).
struct PlacedFit {
  GridTransform T_to_from;         ///< the placed transform
  long long similarity = 0;        ///< agr - dis on the search samples
  double disagreement_rate = 0.0;  ///< 1 - V over all known cells
  double structure = 0.0;          ///< the lesser structure agreement of both ways (samples)
};

/// Block 8's inputs (seed_stages.hpp: samples, code images, wall fields) of the last few pairs of
/// maps, newest first: a chain judges one pair many times, both ways, by its steps' judges and
/// by its own. Every SeedMerger that shares one must have the same settings.
class SearchInputsCache {
 public:
  explicit SearchInputsCache(std::size_t pairs = 2) : pairs_(pairs) {}
  /// The inputs kept for exactly these maps, or null.
  std::shared_ptr<const seed::SearchInputs> find(const GridMap& from, const GridMap& to) const;
  /// Keeps `inputs` of the pair (the oldest pair beyond `pairs` is let go).
  void keep(const GridMap& from, const GridMap& to,
            std::shared_ptr<const seed::SearchInputs> inputs);

 private:
  struct Entry {
    GridMap from;
    GridMap to;
    std::shared_ptr<const seed::SearchInputs> inputs;
  };
  std::size_t pairs_;
  std::vector<Entry> entries_;  ///< newest first
};

class SeedMerger : public MapMerger {
 public:
  explicit SeedMerger(const SeedMergerSettings& settings = {});
  MergeResult merge(const GridMap& from, const GridMap& to) override;
  std::string name() const override { return "seed"; }
  void shareSearchInputs(const std::shared_ptr<SearchInputsCache>& cache) override {
    inputs_cache_ = cache;
  }
  const SeedMergeTimings& lastTimings() const { return timings_; }
  /// lastTimings() as named blocks ("edges", "radon", ... "alignment"), those that ran.
  BlockTimes lastBlockTimes() const override;
  const SeedMergerSettings& settings() const { return settings_; }
  /// Blocks 8-9 on hypotheses found by another method (a virtual robot, a rendezvous, a wider
  /// search): each is placed by the translation search within ±δ, they are ranked together and
  /// the best is judged by the same acceptance as the seed's own candidates, every other given
  /// hypothesis a rival. `method` of the result is "seed/given".
  MergeResult judgeHypotheses(const GridMap& from, const GridMap& to,
                              const std::vector<GridTransform>& hypotheses);
  /// Block 9's rival share of a transform facing `others` (transforms another step found): each
  /// placed by the ±δ search, the rival chosen and weighed as among the seed's own candidates.
  /// A rival that, refined, settles within kRivalCells of the transform is a copy slid along a
  /// corridor and does not count (up to `refined_rivals` in turn); one that fails its own tests
  /// still counts, as the caller passes transforms that passed them where they were found.
  /// Above max_rival_share, the transform would have been refused.
  double rivalShareAgainst(const GridMap& from, const GridMap& to, const GridTransform& T_to_from,
                           const std::vector<GridTransform>& others);
  /// Whether one of `others` (each placed by the ±δ search) is a cleaner rival of the transform
  /// (`cleaner_rival_rate`: its walls meet walls as well and its known cells disagree at most
  /// that share as often) that, refined, passes its own overlap, V, structure and entropy tests
  /// more than kRivalCells away (up to `refined_rivals` candidates in turn).
  bool cleanerRivalAmong(const GridMap& from, const GridMap& to, const GridTransform& T_to_from,
                         const std::vector<GridTransform>& others);
  /// `T_to_from` placed by the ±δ search and how it fits there, then the placements of the
  /// distinct `others`, best first (as block 9 ranks candidates); empty when the maps cannot be
  /// compared (resolutions that differ, an empty map).
  /// With `least_share` > 0, each of `others` whose agr - dis could not reach `least_share` times
  /// the placed transform's on any shift of the ±δ search is left out unplaced (mostSimilarity()):
  /// a caller that weighs only fits above that share decides alike, in less time.
  std::vector<PlacedFit> placedFits(const GridMap& from, const GridMap& to,
                                    const GridTransform& T_to_from,
                                    const std::vector<GridTransform>& others,
                                    double least_share = 0.0);
  /// The wall alignment of an accepted `result` of another method (alignAccepted) on the pair's
  /// block 8 inputs: their wall fields, samples and code image, built once for the pair (the
  /// same figures as alignAccepted(from, to, ...) with this merger's settings).
  void alignOnInputs(const GridMap& from, const GridMap& to, MergeResult& result);
  /// neighbourBasins() of T_to_from on the pair's block 8 inputs (every known cell of `from`,
  /// `to` as codes), built once for the pair; from the maps themselves where they cannot be
  /// compared.
  NeighbourBasins neighbourBasinsAt(const GridMap& from, const GridMap& to,
                                    const GridTransform& T_to_from,
                                    const NeighbourBasinSettings& settings);

 private:
  /// Adds `more` to the ordered `candidates`; `refined` follows a new best and the rival share.
  void addCandidates(const std::vector<seed::Candidate>& more, const seed::SearchInputs& inputs,
                     std::vector<seed::Candidate>& candidates, seed::Refined& refined) const;
  /// Step 10: the `count` best of the global search's refined `hypotheses`, labelled `stage`,
  /// join the candidates.
  void addGlobalCandidates(std::vector<seed::Hypothesis> hypotheses, int count, seed::Stage stage,
                           const seed::SearchInputs& inputs,
                           std::vector<seed::Candidate>& candidates, seed::Refined& refined,
                           MergeResult& result) const;
  /// The first of the `judged_candidates` candidates that passes block 9, refined; `first` is
  /// the refined first candidate (refused). A candidate refused for its rival alone is judged
  /// again without it when the rival, refined, failsOnItsOwn() or settles within kRivalCells of
  /// the candidate (up to `refined_rivals` rivals in turn); the candidates in the samePlace() as
  /// that rival go with it.
  std::optional<seed::Refined> nextAcceptable(const std::vector<seed::Candidate>& candidates,
                                              const seed::SearchInputs& inputs,
                                              const seed::Refined& first) const;
  /// Of the `others`, those whose agr - dis on the search samples could reach `least_share`
  /// times `placed`'s (seed::mostSimilarity over the ±δ search's shifts); all when `least_share`
  /// is 0 or `placed`'s is not positive.
  std::vector<GridTransform> ableToReach(const seed::Candidate& placed,
                                         const std::vector<GridTransform>& others,
                                         double least_share,
                                         const seed::SearchInputs& inputs) const;
  /// `T_to_from` and then `others`, each placed by the ±δ search (empty when T_to_from is not).
  /// `only_as_walled`: the others whose structure agreement falls below T_to_from's or below
  /// min_structure_agreement are left out (never a cleaner rival); `least_share`: so are those
  /// that cannot reach that share of T_to_from's agr - dis (ableToReach()).
  std::vector<seed::Candidate> placedFacing(const GridTransform& T_to_from,
                                            const std::vector<GridTransform>& others,
                                            const seed::SearchInputs& inputs,
                                            bool only_as_walled = false,
                                            double least_share = 0.0) const;
  /// Whether a refined rival places the centre of `from`'s known cells more than kRivalCells
  /// from where the chosen candidate does (a copy slid along a corridor settles back onto it).
  static bool settlesApart(const seed::Refined& rival, const seed::Candidate& chosen,
                           const seed::SearchInputs& inputs);
  /// Removes the `rival` of `facing` and every later candidate in the samePlace() as it, before
  /// or after its refinement (`refined`): the other steps of the same slide.
  static void dropRival(std::vector<seed::Candidate>& facing, std::size_t rival,
                        const GridTransform& refined, const seed::SearchInputs& inputs);
  /// Whether two transforms place the centre of `from`'s known cells within kRivalCells of each
  /// other at rotations within 5°.
  static bool samePlace(const GridTransform& a, const GridTransform& b,
                        const seed::SearchInputs& inputs);
  /// Whether a refined transform is refused for its own overlap, V, structure agreement or
  /// entropy gap.
  bool failsOnItsOwn(const seed::Refined& refined) const;
  /// Block 8's last steps and block 9's figures for the first candidate.
  seed::Refined refineBest(const std::vector<seed::Candidate>& candidates,
                           const seed::SearchInputs& inputs) const;
  /// Block 9: the result of a refined transform.
  void judge(const seed::Refined& refined, const seed::SearchInputs& inputs,
             MergeResult& result) const;
  /// Which test refuses a transform, and why in words.
  struct Refusal {
    MergeRefusal kind = MergeRefusal::kUnspecified;
    std::string reason;  ///< empty when accepted
    bool empty() const { return reason.empty(); }
  };
  /// Why a refined transform is refused; empty when it is accepted.
  Refusal refusal(const seed::Refined& refined) const;
  /// refusal()'s tests of the cells: the overlap and V bars.
  Refusal cellsRefusal(const seed::Refined& refined) const;
  /// refusal()'s tests after the walls: the entropy, the translation and the rivals.
  Refusal placementRefusal(const seed::Refined& refined) const;
  /// Whether an overlap below min_overlap_cells is still decisive (small_overlap_* bars).
  bool smallOverlapDecisive(const seed::Refined& refined) const;
  /// Whether the overlap fixes the translation (the ambiguity bars of block 9).
  bool translationFixed(const seed::Refined& refined) const;
  /// Whether decisive walls at a high V outweigh flat open floor (walls_over_floor_min_v).
  bool wallsOutweighFloor(const seed::Refined& refined) const;
  /// Whether the least merged entropy lies too far from the best similarity to accept.
  bool entropyDisagrees(const seed::Refined& refined) const;
  /// Whether the overlapping walls meet walls: min_structure_agreement, or frontierExcuses().
  bool wallsMeet(const seed::Refined& refined) const;
  /// Whether they meet with the walls on the other map's frontier left out
  /// (min_structure_off_frontier) where the known cells agree cleanly (min_v_off_frontier).
  bool frontierExcuses(const seed::Refined& refined) const;
  /// Block 8's inputs; `reversed` (may be null): those of (to, from), whose wall fields serve.
  seed::SearchInputs searchInputs(const GridMap& from, const GridMap& to,
                                  const seed::SearchInputs* reversed = nullptr) const;
  /// The wall alignment of an accepted `result` on a pair's block 8 inputs: their wall fields
  /// when they hold both, else fields built for it; `at_found` (may be null): the comparison of
  /// all known cells at result.T_to_from, when the caller has it.
  void alignOn(const seed::SearchInputs& inputs, const GridMap& from, const GridMap& to,
               const Agreement* at_found, MergeResult& result) const;
  /// searchInputs() of a pair held in inputs_cache_, built only for a pair it does not hold: a
  /// chain judges many transforms of one pair in turn (judgeHypotheses, placedFits, ...). The
  /// caller holds what it is given while it uses it.
  std::shared_ptr<const seed::SearchInputs> searchInputsOf(const GridMap& from, const GridMap& to);

  const SeedMergerSettings settings_;
  const ComparisonTables tables_;
  SeedMergeTimings timings_;
  /// What searchInputsOf() returns for the same maps again (its own, or a chain's).
  std::shared_ptr<SearchInputsCache> inputs_cache_ = std::make_shared<SearchInputsCache>();
};

/// The result of a merger whose hypotheses (`found`) are judged by `judge`'s acceptance
/// (SeedMerger::judgeHypotheses): refused when the maps' resolutions differ or nothing was found;
/// `method` is `method`, a refusal's reason starts with `what` (the hypotheses' source).
MergeResult judgeFoundHypotheses(SeedMerger& judge, const GridMap& from, const GridMap& to,
                                 const std::vector<GridTransform>& found, const std::string& method,
                                 const std::string& what);

}  // namespace mrslam::fusion
