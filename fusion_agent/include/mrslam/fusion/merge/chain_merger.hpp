#pragma once
// A configured chain of mergers (issue: "seed pipeline; virtual robot when it refuses"): each
// step is tried in turn until one accepts. The result is that step's, its `method` naming the
// step ("virtual", "seed/global-search", ...); a refusal of the whole chain gives every step's
// reason. Settings: `steps` (comma-separated merger names) and one section per step name.
// With `slid_rivals`, a transform that an earlier step refused only because a slide along a
// corridor scored almost as well faces a later step's accepted transform as a rival (block 9's
// rival test, SeedMerger::rivalShareAgainst): the earlier step found the place, if not the exact
// shift, and a transform elsewhere that explains the overlap no better is refused too. With
// `sweep_rivals`, every translation at the accepted rotation is searched for a placement that
// explains the overlap more cleanly (a building whose rooms repeat along a corridor). With
// `cleaner_alternative_rate`, the hypotheses of the steps' own searches at every rotation
// (MergeResult::hypotheses) are judged alone, and one that passes elsewhere and fits more cleanly
// (with `cleaner_alternative_min_z`: beyond chance) refuses the merge (a hall that looks alike
// turned by a quarter or a half); with `alternative_sweep_degrees`, so do the peaks of a sweep over
// every translation at the accepted rotation turned by those angles (the right turn of such a hall
// where it overlaps too little to be among the search's hypotheses). With `walls_alternative_rate`,
// so does one refused alone only by the structure test that fits more cleanly over more known cells
// (`walls_alternative_overlap`), turned from the accepted transform
// (`walls_alternative_min_turn_deg`). A transform so refused and its alternative stay undecided: a
// later step's transform near either is refused too (`undecided_deg`). With
// `turned_rival_degrees`, the overlap turned by a quarter or a half about its centre and placed
// again refuses the merge when it explains clearly more of it about as cleanly (a room that fits
// turned as well). With
// `second_opinion_step`, a transform whose turn check came near its bar is refused when that step
// (the seed pipeline), run as well, ends within the wall alignment's window of it and finds there
// that the walls do not fix the rotation. With `floor_crossing_min_cells` (on by default), a step's
// transform is refused where the walls of one map run across the other's certain open floor
// (floor_crossing.hpp): a room that looks alike, placed along a corridor or turned. With
// `neighbour_basin_min_v_gain` (on by default), the transform the checks accepted is refused
// where V peaks higher, by more than that, in another basin a few cells and degrees away that
// keeps most of the overlap (neighbour_basins.hpp): the searches left it in the basin of a
// placement a little off.

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/floor_crossing.hpp"
#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/merge/neighbour_basins.hpp"
#include "mrslam/fusion/merge/overlap_score.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {

struct ChainSettings {
  /// Refine an accepted transform by the random walk of Carpin's ψ (seed 002, Algorithm 3); the
  /// refinement is kept when it stays within these bounds and V does not drop.
  bool refine_psi = false;
  double max_refinement_cells = 2.0;         ///< largest shift of the refinement kept
  double max_refinement_rad = M_PI / 180.0;  ///< largest turn of the refinement kept
  /// A transform an earlier step refused only because the overlap did not fix its translation
  /// (MergeRefusal::kTranslation) faces a later step's accepted transform as a rival.
  bool slid_rivals = true;
  /// An accepted transform is refused when a transform elsewhere at its rotation explains the
  /// overlap more cleanly (SeedMerger::cleanerRivalAmong): found by the global search's sweep
  /// (global_search.hpp) over all translations, within one step of the accepted rotation.
  bool sweep_rivals = true;
  double sweep_step_deg = 1.0;  ///< rotation step of that sweep, degrees
  int sweep_peaks = 24;         ///< its best peaks, each placed by the ±δ search and weighed
  int sweep_coarse_cells = 4;   ///< cells per coarse cell of the sweep
  /// Peaks of that sweep whose cells disagree more than this many times as often as the
  /// accepted transform's (every other row and column of `from`'s known cells) are not placed:
  /// a rival must end at cleaner_rival_rate (0.5) times it (0: every peak placed).
  double sweep_prefilter_rate = 2.0;
  /// An accepted transform is refused when a hypothesis of a step's own search
  /// (MergeResult::hypotheses: the exhaustive search's, at any rotation) passes block 9's every
  /// test on its own, lands more than `alternative_cells` away, and its known cells disagree at
  /// most this many times as often (a hall that looks alike turned by a quarter or a half: the
  /// wrong turn overlaps more and wins the ranking, the right one fits more cleanly); 0: off.
  double cleaner_alternative_rate = 1.0;
  /// ... and only when its disagreements are this many standard deviations fewer than its overlap
  /// would hold at the accepted transform's rate (z = (r n - dis) / sqrt(n r (1 - r)), n its
  /// overlap, r the accepted rate): a fit cleaner by chance no longer refuses, and the placement
  /// that overlaps more is taken; 0: off, the rate alone decides. Off by default: at 4 it gains
  /// right merges but took one wrong quarter turn on case sets never used to tune it.
  double cleaner_alternative_min_z = 0.0;
  /// The same for an alternative refused on its own only because its exact shift is not fixed
  /// (MergeRefusal::kEntropy or kTranslation: the maps fit there, slid along a corridor); 0: off
  /// (at 0.5 it refuses a wrong quarter turn and a right merge of the same figures alike).
  double slid_alternative_rate = 0.0;
  /// The same for an alternative refused on its own only because too few of its overlapping walls
  /// meet walls (MergeRefusal::kStructure), when it also overlaps walls_alternative_overlap times
  /// as many known cells; 0: off.
  double walls_alternative_rate = 0.7;
  double walls_alternative_overlap = 1.2;  ///< ... the least overlap of it, times the accepted's
  /// ... and when it is turned at least this much from the accepted transform (degrees): one at
  /// about the same rotation is the accepted fit slid along its walls, which the translation
  /// tests weigh, not a building that looks alike turned.
  double walls_alternative_min_turn_deg = 20.0;
  double alternative_cells = 10.0;  ///< alternatives land farther than this from it (cells)
  /// Only hypotheses whose known cells, as found, disagree at most this many times as often as
  /// the accepted transform's are judged on their own (each judgement refines a hypothesis).
  double alternative_prefilter_rate = 2.0;
  /// The alternatives also hold the best peaks (alternative_sweep_peaks) of a sweep over every
  /// translation at the accepted rotation turned by exactly each of these angles (degrees): the
  /// turn of a hall that looks alike whose right placement overlaps too little to be among the
  /// search's own hypotheses. They are judged as those are, at the same bars: where a turned
  /// placement passes alone and fits more cleanly, the maps do not tell the turn, whichever of
  /// the two is right (docs/merge_tuning.md: most merges so refused were right). Empty: off.
  std::vector<double> alternative_sweep_degrees = {90.0, 180.0, 270.0};
  int alternative_sweep_peaks = 100;  ///< ... the best peaks of that sweep kept
  /// A step's transform refused for a cleaner alternative and that alternative are undecided: a
  /// later step's transform within alternative_cells and this many degrees of either is refused
  /// too (the maps did not tell them apart).
  double undecided_deg = 5.0;
  /// An accepted transform is refused when the overlap turned by one of these angles (degrees)
  /// about its centre and placed by the ±δ search explains turned_rival_similarity times its
  /// agr - dis or more while its known cells disagree at most turned_rival_rate times as often:
  /// a room or hall that looks alike turned, placed the wrong way round (its walls need not
  /// meet walls, as the walls of the right turn often do not where the maps were cut). Empty: off.
  std::vector<double> turned_rival_degrees = {90.0, 180.0, 270.0};
  double turned_rival_similarity = 1.5;  ///< least agr - dis of a turn, times the accepted's
  double turned_rival_rate = 1.5;        ///< most disagreement rate of a turn, times the accepted's
  /// Where the accepted transform's walls meet walls less well than this (structure agreement,
  /// both ways), a turn may disagree up to turned_rival_weak_rate times as often.
  double turned_rival_weak_structure = 0.95;
  double turned_rival_weak_rate = 2.2;  ///< most disagreement rate of a turn there, times
  /// After another step accepts, this step of the chain (empty or not in the chain: off) is run as
  /// well. Where it refuses because the walls do not fix the rotation (MergeRefusal::kRotation) at
  /// a placement within second_opinion_cells and second_opinion_deg of the accepted one, the
  /// accepted transform is refused too: two searches end at the same overlap (the wall
  /// alignment's windows about them, ±2.5 cells and ±1.5° each, meet), and its walls fix the
  /// rotation at one of them only (the turn check's share lies near its bar there). A placement
  /// farther away is another answer, refused on its own, and says nothing of the accepted one.
  std::string second_opinion_step = "seed";
  double second_opinion_cells = 5.0;  ///< ... at most this far apart at the overlap's centre
  double second_opinion_deg = 3.0;    ///< ... and turned at most this much (degrees)
  /// The step is asked only where the accepted transform's turn check came near its bar: a turn
  /// keeps at least this share of the walls' agreement (MergeResult::wall_turn_share).
  double second_opinion_turn_share = 0.9;
  /// The chain's last check, on the transform it would return: refused when the placement slid 3
  /// to 8 cells (keeping 0.9 of its overlap) disagrees on fewer than this many more known cells
  /// (truth_slide.hpp): the maps hardly fix its shift. 0: off (the default; docs/merge_tuning.md,
  /// it refuses more right merges than wrong ones).
  long long min_slide_margin_cells = 0;
  /// A step's accepted transform is refused when the walls of either map cross the other's open
  /// floor (floor_crossing.hpp) in a run of at least floor_crossing_min_cells cells that is at
  /// least floor_crossing_min_share of its walls on the other's known cells: a room that looks
  /// alike placed along or turned (docs/merge_tuning.md).
  /// 0 cells: off.
  int floor_crossing_min_cells = 4;
  double floor_crossing_min_share = 0.015;
  /// What counts as crossing: the clearance from the other map's walls, the occupancy of open
  /// floor, and whether floor at the other map's frontier counts (config keys
  /// floor_crossing_clearance_cells, floor_crossing_floor_max_occupancy,
  /// floor_crossing_known_around).
  FloorCrossingSettings floor_crossing;
  /// The transform a step's checks accepted is refused when V peaks higher in another basin a few
  /// cells and degrees away (neighbour_basins.hpp) by more than this: the searches left it in the
  /// basin of a placement a little off (docs/merge_tuning.md). 1 or more:
  /// off.
  double neighbour_basin_min_v_gain = 0.002;
  NeighbourBasinSettings neighbour_basins;  ///< the grid around the transform and the climbs
};

class ChainMerger : public MapMerger {
 public:
  /// `judge`: the acceptance that weighs a step's transform against earlier refused ones.
  explicit ChainMerger(std::vector<std::unique_ptr<MapMerger>> steps, ChainSettings settings = {},
                       const SeedMergerSettings& judge = {});
  MergeResult merge(const GridMap& from, const GridMap& to) override;
  std::string name() const override { return "chain"; }
  /// The chain's own judge and every step keep their inputs in `cache`: for a chain whose
  /// steps are judged with its judge's settings (merger_registry.cpp builds them so).
  void shareSearchInputs(const std::shared_ptr<SearchInputsCache>& cache) override {
    judge_.shareSearchInputs(cache);
    for (const auto& step : steps_) {
      step->shareSearchInputs(cache);
    }
  }
  /// The last merge's blocks: each step that ran, by its own blocks ("exhaustive/search", ...,
  /// "exhaustive/rest" for the time between them) or as one block (its name) when it times none,
  /// and each check the chain ran on an accepted transform ("chain/sweep", "chain/turns",
  /// "chain/alternatives", "chain/second_opinion", ...; a second opinion's own step counts there).
  BlockTimes lastBlockTimes() const override { return times_; }

 private:
  /// step.merge(), its time added to times_ (by the step's own blocks where it times them).
  MergeResult timedStepMerge(MapMerger& step, const GridMap& from, const GridMap& to);

  /// Refuses the accepted `result` when one of the `earlier` refused transforms is its rival.
  void judgeAgainstEarlier(const GridMap& from, const GridMap& to,
                           const std::vector<GridTransform>& earlier, MergeResult& result);

  /// What the chain's checks of one pair of maps share, each built when first needed: one
  /// preparation of the maps for the sweeps (at the accepted rotation, and turned), and one sample
  /// of `from`'s known cells for their prefilters.
  class PreparedPair;

  /// With sweep_rivals: refuses the accepted `result` when a peak of the sweep at its rotation
  /// is a cleaner rival.
  void judgeAgainstSweep(const GridMap& from, const GridMap& to, PreparedPair& pair,
                         MergeResult& result);

  /// With turned_rival_degrees: refuses the accepted `result` when a turned copy of it explains
  /// more of the overlap about as cleanly.
  void judgeAgainstTurns(const GridMap& from, const GridMap& to, MergeResult& result);

  /// The second-opinion step and its result, once it ran in a merge (it runs once).
  struct SecondOpinion {
    MapMerger* step = nullptr;
    MergeResult result;
  };
  /// With second_opinion_step: that step's result (run into `second` unless it ran already) after
  /// `accepting` accepted `result`; refuses `result` when that step refused a placement near it
  /// for the turn check.
  void askSecondOpinion(const GridMap& from, const GridMap& to, const MapMerger& accepting,
                        SecondOpinion& second, MergeResult& result);

  /// What an alternative must meet to refuse the accepted transform: disagree at most `rate`
  /// times as often (0: no bar), over at least `overlap` times as many known cells.
  struct AlternativeBar {
    double rate = 0.0;
    double overlap = 0.0;
    double min_z = 0.0;  ///< how many standard deviations cleaner (cleaner_alternative_min_z)
    double min_turn_deg = 0.0;  ///< the least turn from the accepted transform
  };
  /// The bar of an alternative judged alone: cleaner_alternative_rate (with
  /// cleaner_alternative_min_z) when it passes,
  /// slid_alternative_rate when only its shift is not fixed, walls_alternative_rate (with
  /// walls_alternative_overlap and walls_alternative_min_turn_deg) when only its walls are unmet,
  /// else no bar.
  AlternativeBar alternativeBar(const MergeResult& alone) const;

  /// The accepted transform as its alternatives are weighed against it.
  struct Accepted {
    Eigen::Vector2d pivot;  ///< the cell of `from` where placements are compared
    OverlapScore overlap;   ///< its overlap's counts
    double rate = 0.0;      ///< its known cells' disagreement rate
  };
  /// Judges `hypothesis` alone (recording it and where it settled in `judged`); refuses `result`
  /// and returns true when it lands elsewhere and meets its alternativeBar(), adding both
  /// placements to `undecided`.
  bool refusedForAlternative(const GridMap& from, const GridMap& to,
                             const GridTransform& hypothesis, const Accepted& accepted,
                             std::vector<GridTransform>& judged,
                             std::vector<GridTransform>& undecided, MergeResult& result);

  /// With cleaner_alternative_rate (or the slid or walls rates): refuses the accepted `result`
  /// when one of the `searched` hypotheses, then one of the turnedSweepPeaks(), judged alone,
  /// lands elsewhere and meets its alternativeBar(). The searched ones are prefiltered by their
  /// disagreement rate over every known cell, the swept ones over a sample of them
  /// (alternative_prefilter_rate times the accepted transform's, measured alike). The refused
  /// transform and the alternative that refused it are added to `undecided`.
  void judgeAgainstAlternatives(const GridMap& from, const GridMap& to,
                                const std::vector<GridTransform>& searched, PreparedPair& pair,
                                std::vector<GridTransform>& undecided, MergeResult& result);

  /// Refuses the accepted `result` when it lands within alternative_cells and undecided_deg of
  /// one of the `undecided` placements: an earlier step's transform refused for a cleaner
  /// alternative, or that alternative. Neither is chosen by a later step.
  void judgeAgainstUndecided(const GridMap& from, const std::vector<GridTransform>& undecided,
                             MergeResult& result) const;

  /// With alternative_sweep_degrees: the best peaks of the sweep at the accepted rotation turned
  /// by those angles.
  std::vector<GridTransform> turnedSweepPeaks(const GridMap& from, PreparedPair& pair,
                                              const GridTransform& T_to_from) const;

  std::vector<std::unique_ptr<MapMerger>> steps_;
  ChainSettings settings_;
  SeedMerger judge_;
  BlockTimes times_;  // of the last merge
};

/// With min_slide_margin_cells: refuses the accepted `result` of step `step` when its slides cost
/// fewer disagreeing cells (see ChainSettings), cells classed by `classes`; `chain` names the
/// refusing merger.
void refuseWhereSlidesCostLittle(const GridMap& from, const GridMap& to,
                                 const ChainSettings& settings, const SimilaritySettings& classes,
                                 const std::string& step, const std::string& chain,
                                 MergeResult& result);

/// With floor_crossing_min_cells: refuses a step's accepted `result` when the walls of either map
/// cross the other's open floor (see ChainSettings), cells classed by `classes`.
void refuseWhereWallsCrossFloor(const GridMap& from, const GridMap& to,
                                const ChainSettings& settings, const SimilaritySettings& classes,
                                MergeResult& result);

/// Refuses an accepted `result` whose V peaks higher in another basin nearby by more than
/// settings.neighbour_basin_min_v_gain (neighbour_basins.hpp), on `judge`'s block 8 inputs of
/// the pair; the reason gives both peaks.
void refuseWhereANeighbourPeaksHigher(const GridMap& from, const GridMap& to,
                                      const ChainSettings& settings, SeedMerger& judge,
                                      MergeResult& result);

/// Refines an accepted result by ψ (see ChainSettings), cells classed by `classes` as the judge
/// classes them; `method` gains "+psi" when it is kept.
void refineByPsi(const GridMap& from, const GridMap& to, const ChainSettings& settings,
                 const SimilaritySettings& classes, MergeResult& result);

/// Reads a `chain:` section's own keys (every key optional, defaults above); throws ConfigError
/// for a bad value. The steps (`steps`) are read by the merger registry.
ChainSettings loadChainSettings(const Config& chain);

/// The default steps of a chain: the exhaustive search, the strict one where it refuses
/// (strictExhaustiveMergerSettings(): clean fits ranked above placements that overlap more and
/// conflict; docs/merge_tuning.md), the seed pipeline, the virtual robot.
constexpr const char* kDefaultChainSteps = "exhaustive,exhaustive_strict,seed,virtual";

/// The step names of a `steps` value ("exhaustive,seed"); throws std::invalid_argument for an empty
/// list, "chain" itself or a repeated step.
std::vector<std::string> parseChainSteps(const std::string& steps);

}  // namespace mrslam::fusion
