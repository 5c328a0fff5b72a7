#pragma once
// The exhaustive merger: the exhaustive search's best distinct transforms (exhaustive_search.hpp)
// judged by the seed pipeline's own acceptance (SeedMerger::judgeHypotheses: the ±δ placement,
// ranking, rival check and every refusal rule of block 9), so that it accepts no transform the
// seed pipeline would refuse had it proposed it. Its settings are the search's; the acceptance
// is the seed merger's settings (the `seed:` section beside it in a merger config). With
// `check_both_ways`, an accepted transform must also be accepted the other way (the inverse
// hypotheses judged with `to` moved onto `from`) and agree with it within `agreement_cells` and
// `agreement_deg`: a transform a few degrees off that the acceptance lets through one way is
// seldom let through the other way at the same place. With `check_own_score`, the search's own
// score (both ways, full resolution) must also peak within that agreement of the accepted
// transform (looked for within ±own_score_turn_deg and ±own_score_shift_cells). With
// `return_own_peak`, that peak is the transform returned. With `max_turn_ambiguity` below 1, a
// peak that a turn of `ambiguity_turn_deg` scores that share of or more is refused: the overlap
// does not fix the rotation. Both are off by default: on 28 case sets, turning them off gained
// the chain 61 right merges and lost none, for 5 false accepts more (4 of them within 5 cells
// and 3° of the truth) and one fewer (docs/merge_tuning.md).
// An accepted transform is aligned last, as the seed merger's are (`wall_alignment` of the judge's
// settings, wall_alignment.hpp).

#include <string>
#include <vector>

#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/exhaustive_search.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {

struct ExhaustiveMergerSettings {
  ExhaustiveSearchSettings search;
  /// Hypotheses the judge takes in turn when the best is refused (its judged_candidates for this
  /// step; the seed pipeline's own candidates keep the judge's): the truth often ranks fourth or
  /// later behind transforms with more walls in their overlap (0: the judge's judged_candidates).
  int judged_hypotheses = 16;
  bool check_both_ways = true;   ///< the other way must accept the same transform
  double agreement_cells = 2.0;  ///< largest shift between the two ways' transforms, cells
  double agreement_deg = 1.0;    ///< largest turn between them, degrees
  /// The search's own score must peak at the accepted transform (off: of the chain's misses it
  /// refused, the judge's transform was right 40 times in 45).
  bool check_own_score = false;
  bool return_own_peak = false;     ///< return that peak instead of the judge's transform
  double own_score_turn_deg = 4.0;  ///< ... looked for within this turn
  int own_score_shift_cells = 4;    ///< ... and this shift
  /// The peak turned by ±ambiguity_turn_deg (with its best shift within ±ambiguity_shift_cells)
  /// scoring this share of the peak or more: the rotation is not fixed, refused (1 or more: off,
  /// the default: it refused right transforms 16 times for one wrong).
  double max_turn_ambiguity = 1.0;
  double ambiguity_turn_deg = 3.0;  ///< the turn of that check, degrees
  int ambiguity_shift_cells = 3;    ///< its shifts, cells
};

/// The strict search's defaults (the `exhaustive_strict` method): a wall of either map on the
/// other's open floor and a free cell on the other's wall cost 20 instead of 6, and free cells
/// within 2 grid cells of `from`'s walls are not scored. It ranks placements whose known cells
/// fit cleanly above ones that cover more cells with more conflicts: in ACES's lattice of
/// corridors the default search's 16 hypotheses can all be placements a corridor along that
/// overlap more (agr 7600, dis 370 against the truth's 5800 and 100), and the truth is not
/// among them (docs/merge_tuning.md).
ExhaustiveMergerSettings strictExhaustiveMergerSettings();

/// Reads the search's keys of an `exhaustive:` section (keys as the fields of
/// ExhaustiveSearchSettings; a key left out keeps its value in `defaults`); throws ConfigError
/// for a bad value.
ExhaustiveSearchSettings loadExhaustiveSearchSettings(
    const Config& config, const ExhaustiveSearchSettings& defaults = {});
/// Reads an `exhaustive:` (or `exhaustive_strict:`) section: the search's keys and the merger's
/// own, over `defaults`.
ExhaustiveMergerSettings loadExhaustiveMergerSettings(
    const Config& config, const ExhaustiveMergerSettings& defaults = {});

class ExhaustiveMerger : public MapMerger {
 public:
  /// `judge` judges the hypotheses, with judged_hypotheses as its judged_candidates (unless 0);
  /// `name` is the method its results give ("exhaustive", or "exhaustive_strict" with
  /// strictExhaustiveMergerSettings()).
  explicit ExhaustiveMerger(ExhaustiveMergerSettings settings = {},
                            const SeedMergerSettings& judge = {}, std::string name = "exhaustive");
  MergeResult merge(const GridMap& from, const GridMap& to) override;
  std::string name() const override { return name_; }
  void shareSearchInputs(const std::shared_ptr<SearchInputsCache>& cache) override {
    judge_.shareSearchInputs(cache);
  }

  /// The last merge's blocks: "prepare" (the score's grids of both maps), "search" (steps 1-7),
  /// "judge" (the seed acceptance of the hypotheses), then on an accepted transform "own_peak"
  /// (when a setting asks for it), "other_way" (with check_both_ways) and "alignment" (the walls
  /// aligned both ways).
  BlockTimes lastBlockTimes() const override { return times_; }

  /// The search's hypotheses, best first, before they are judged (for tests and tuning).
  std::vector<GridTransform> hypotheses(const GridMap& from, const GridMap& to) const;

 private:
  /// The hypotheses with the pair's score of step 7 built once.
  std::vector<GridTransform> hypotheses(const GridMap& from, const GridMap& to,
                                        const ExhaustiveScore& score) const;
  /// With check_both_ways: refuses `result` unless the other way accepts the same transform
  /// (compared where `pivot`, `from`'s known centre, lands).
  void checkTheOtherWay(const GridMap& from, const GridMap& to,
                        const std::vector<GridTransform>& found, const Eigen::Vector2d& pivot,
                        MergeResult& result);
  /// Whether a setting asks for the search's own peak near the accepted transform.
  bool ownPeakNeeded() const;
  /// The search's own checks near the accepted transform: with check_own_score, refuses `result`
  /// unless `score` (both ways) peaks within the agreement of it; with max_turn_ambiguity below 1,
  /// unless a turn scores clearly less there; with return_own_peak, returns that peak. Called
  /// only when ownPeakNeeded().
  void applyOwnPeakChecks(const GridMap& from, const GridMap& to, const ExhaustiveScore& score,
                          const Eigen::Vector2d& pivot, MergeResult& result) const;
  /// Refuses `result` when `score` turned by ±ambiguity_turn_deg about `centre` (`from`'s known
  /// centre) comes within max_turn_ambiguity of `peak`'s.
  void refuseUnlessTurnFixed(const ExhaustiveScore& score, const Eigen::Vector2d& centre,
                             const ExhaustiveHypothesis& peak, MergeResult& result) const;
  /// Refuses `result` when `other` puts `centre` farther from where `result` puts it, or turns
  /// farther, than the agreement bars.
  void refuseUnlessAgreeing(const Eigen::Vector2d& centre, const GridTransform& other,
                            const std::string& what, MergeResult& result) const;

  ExhaustiveMergerSettings settings_;
  SeedMerger judge_;
  SimilaritySettings classes_;
  std::string name_;
  BlockTimes times_;  // of the last merge
};

}  // namespace mrslam::fusion
