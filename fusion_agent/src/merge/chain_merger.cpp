#include "mrslam/fusion/merge/chain_merger.hpp"

#include <algorithm>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "mrslam/fusion/merge/approximate_pose.hpp"
#include "mrslam/fusion/merge/dissimilarity.hpp"
#include "mrslam/fusion/merge/floor_crossing.hpp"
#include "mrslam/fusion/merge/global_search.hpp"
#include "mrslam/fusion/merge/overlap_score.hpp"
#include "mrslam/fusion/merge/random_walk.hpp"
#include "mrslam/fusion/merge/reason_text.hpp"
#include "mrslam/fusion/merge/similarity.hpp"
#include "mrslam/fusion/merge/truth_slide.hpp"
#include "sampled_comparison.hpp"

namespace mrslam::fusion {

namespace {

// 1 - V over the overlap; 1 with no overlap.
double disagreementRate(const OverlapScore& overlap) {
  return overlap.overlap() == 0 ? 1.0 : 1.0 - overlap.verification();
}

// How many standard deviations fewer disagreements `there` holds than its overlap would at `rate`
// (one-sided, binomial): z = (r n - dis) / sqrt(n r (1 - r)); 0 when that spread is 0.
double deviationsCleaner(const OverlapScore& there, double rate) {
  const double cells = static_cast<double>(there.overlap());
  const double spread = std::sqrt(cells * rate * (1.0 - rate));
  return spread > 0.0 ? (rate * cells - static_cast<double>(there.disagreement)) / spread : 0.0;
}

// How far apart two transforms put `pivot` (a cell of `from`), cells.
double cellsApartAt(const GridTransform& T_a, const GridTransform& T_b,
                    const Eigen::Vector2d& pivot) {
  return (T_a.apply(pivot) - T_b.apply(pivot)).norm();
}

// The turn between two transforms, radians in [0, π].
double turnBetween(const GridTransform& T_a, const GridTransform& T_b) {
  return std::abs(wrapAngle(T_a.theta_rad - T_b.theta_rad));
}

// Whether two transforms put `pivot` within `cells` of each other.
bool landsWithin(const GridTransform& T_a, const GridTransform& T_b, const Eigen::Vector2d& pivot,
                 double cells) {
  return cellsApartAt(T_a, T_b, pivot) <= cells;
}

// How an alternative judged alone fared, in words.
std::string howItFaredAlone(const MergeResult& alternative) {
  if (alternative.accepted) {
    return "passes every test on its own";
  }
  const bool unwalled = alternative.refusal == MergeRefusal::kStructure;
  return std::string("fails on its own only for ") +
         (unwalled ? "the walls it leaves unmet" : "its exact shift") + " (" + alternative.reason +
         ")";
}

void refuseForAlternative(const Eigen::Vector2d& pivot, const MergeResult& alternative,
                          double ratio, double deviations, MergeResult& result) {
  const GridTransform& T_alternative = alternative.T_to_from;
  std::ostringstream reason;
  reason.precision(3);
  reason << "another placement, " << cellsApartAt(T_alternative, result.T_to_from, pivot)
         << " cells and " << turnBetween(T_alternative, result.T_to_from) * 180.0 / M_PI
         << " degrees away, " << howItFaredAlone(alternative) << ", and its known cells disagree "
         << ratio << " times as often, " << deviations
         << " standard deviations below the accepted rate (a building that looks alike turned)";
  result.accepted = false;
  result.refusal = MergeRefusal::kRival;
  result.reason = reason.str();
}

// What every sweep of the chain shares: its coarse cells and no free agreement; `rotations` its
// only rotations.
GlobalSearchSettings chainSweepSettings(const ChainSettings& settings,
                                        std::vector<double> rotations) {
  GlobalSearchSettings sweep;
  sweep.rotation_step_rad = settings.sweep_step_deg * M_PI / 180.0;
  sweep.only_rotations_rad = std::move(rotations);
  sweep.free_agreement_hypotheses = 0;
  sweep.coarse_cells = settings.sweep_coarse_cells;
  return sweep;
}

}  // namespace

class ChainMerger::PreparedPair {
 public:
  PreparedPair(const GridMap& from, const GridMap& to, const ChainSettings& settings,
               const SimilaritySettings& classes)
      : from_(from),
        to_(to),
        sweep_settings_(chainSweepSettings(settings, {0.0})),
        classes_(classes) {}

  /// globalSearch() with `sweep` (chainSweepSettings()), the maps prepared once.
  std::vector<GlobalHypothesis> search(const GlobalSearchSettings& sweep) {
    if (!sweep_) {
      sweep_.emplace(from_, to_, sweep_settings_, classes_);
    }
    return sweep_->search(sweep);
  }

  /// The sample of `from`'s known cells against `to`, built once.
  const SampledComparison& sampled() {
    if (!sampled_) {
      sampled_.emplace(from_, to_, classes_);
    }
    return *sampled_;
  }

 private:
  const GridMap& from_;
  const GridMap& to_;
  GlobalSearchSettings sweep_settings_;
  SimilaritySettings classes_;
  std::optional<GlobalSweep> sweep_;
  std::optional<SampledComparison> sampled_;
};

ChainMerger::ChainMerger(std::vector<std::unique_ptr<MapMerger>> steps, ChainSettings settings,
                         const SeedMergerSettings& judge)
    : steps_(std::move(steps)), settings_(settings), judge_(judge) {
  if (steps_.empty()) {
    throw std::invalid_argument("a merge chain needs at least one step");
  }
}

MergeResult ChainMerger::merge(const GridMap& from, const GridMap& to) {
  std::string reasons;
  int trials = 0;
  MergeResult last;
  std::vector<GridTransform> earlier;    // transforms earlier steps refused for a slide alone
  std::vector<GridTransform> searched;   // every step's search hypotheses so far
  std::vector<GridTransform> undecided;  // placements an earlier step refused for a cleaner one
  SecondOpinion second;                  // the second-opinion step's result, when it ran already
  PreparedPair pair(from, to, settings_, judge_.settings().similarity);
  times_.clear();
  for (const auto& step : steps_) {
    MergeResult result =
        step.get() == second.step ? second.result : timedStepMerge(*step, from, to);
    if (step->name() == settings_.second_opinion_step) {
      second = {step.get(), result};
    }
    trials += result.trials;
    searched.insert(searched.end(), result.hypotheses.begin(), result.hypotheses.end());
    if (result.accepted && settings_.floor_crossing_min_cells > 0) {
      timeBlock(times_, "chain/floor_crossing", [&] {
        refuseWhereWallsCrossFloor(from, to, settings_, judge_.settings().similarity, result);
      });
    }
    if (result.accepted && !undecided.empty()) {
      timeBlock(times_, "chain/undecided", [&] { judgeAgainstUndecided(from, undecided, result); });
    }
    if (result.accepted && !earlier.empty()) {
      timeBlock(times_, "chain/earlier", [&] { judgeAgainstEarlier(from, to, earlier, result); });
    }
    if (result.accepted && settings_.sweep_rivals) {
      timeBlock(times_, "chain/sweep", [&] { judgeAgainstSweep(from, to, pair, result); });
    }
    if (result.accepted && !settings_.turned_rival_degrees.empty()) {
      timeBlock(times_, "chain/turns", [&] { judgeAgainstTurns(from, to, result); });
    }
    if (result.accepted &&
        (settings_.cleaner_alternative_rate > 0.0 || settings_.slid_alternative_rate > 0.0 ||
         settings_.walls_alternative_rate > 0.0)) {
      timeBlock(times_, "chain/alternatives",
                [&] { judgeAgainstAlternatives(from, to, searched, pair, undecided, result); });
    }
    if (result.accepted) {
      timeBlock(times_, "chain/second_opinion",
                [&] { askSecondOpinion(from, to, *step, second, result); });
    }
    if (result.accepted && settings_.neighbour_basin_min_v_gain < 1.0) {
      timeBlock(times_, "chain/neighbour_basins",
                [&] { refuseWhereANeighbourPeaksHigher(from, to, settings_, judge_, result); });
    }
    if (result.accepted) {
      result.trials = trials;
      if (settings_.refine_psi) {
        timeBlock(times_, "chain/psi",
                  [&] { refineByPsi(from, to, settings_, judge_.settings().similarity, result); });
      }
      if (settings_.min_slide_margin_cells > 0) {
        timeBlock(times_, "chain/slides", [&] {
          refuseWhereSlidesCostLittle(from, to, settings_, judge_.settings().similarity,
                                      step->name(), name(), result);
        });
      }
      return result;
    }
    reasons += (reasons.empty() ? "" : "; ") + step->name() + ": " + result.reason;
    if (settings_.slid_rivals && result.refusal == MergeRefusal::kTranslation) {
      earlier.push_back(result.T_to_from);
    }
    last = std::move(result);
  }
  last.method = name();
  last.trials = trials;
  last.reason = reasons;
  return last;
}

MergeResult ChainMerger::timedStepMerge(MapMerger& step, const GridMap& from, const GridMap& to) {
  BlockTimes step_total;
  MergeResult result = timeBlock(step_total, step.name(), [&] { return step.merge(from, to); });
  const BlockTimes inner = step.lastBlockTimes();
  if (inner.empty()) {
    addBlockTime(times_, step.name(), totalMs(step_total));
    return result;
  }
  addBlockTimes(times_, step.name(), inner);
  addBlockTime(times_, step.name() + "/rest", std::max(0.0, totalMs(step_total) - totalMs(inner)));
  return result;
}

void ChainMerger::judgeAgainstEarlier(const GridMap& from, const GridMap& to,
                                      const std::vector<GridTransform>& earlier,
                                      MergeResult& result) {
  const double share = judge_.rivalShareAgainst(from, to, result.T_to_from, earlier);
  if (share > judge_.settings().max_rival_share) {
    result.accepted = false;
    result.reason = "a transform an earlier step refused explains the overlap almost as well (" +
                    reasonFigure(share) + " of this one)";
  }
}

void ChainMerger::judgeAgainstUndecided(const GridMap& from,
                                        const std::vector<GridTransform>& undecided,
                                        MergeResult& result) const {
  const Eigen::Vector2d pivot = knownCentroid(from);
  const double alike_rad = settings_.undecided_deg * M_PI / 180.0;
  for (const GridTransform& T_undecided : undecided) {
    if (turnBetween(T_undecided, result.T_to_from) <= alike_rad &&
        landsWithin(T_undecided, result.T_to_from, pivot, settings_.alternative_cells)) {
      result.accepted = false;
      result.refusal = MergeRefusal::kRival;
      result.reason =
          "an earlier step found this placement and another, turned or moved elsewhere, that fits "
          "more cleanly: the maps do not tell the two apart";
      return;
    }
  }
}

void ChainMerger::judgeAgainstSweep(const GridMap& from, const GridMap& to, PreparedPair& pair,
                                    MergeResult& result) {
  GlobalSearchSettings at_accepted = chainSweepSettings(settings_, {result.T_to_from.theta_rad});
  at_accepted.peaks_per_rotation = settings_.sweep_peaks;
  at_accepted.kept_hypotheses = settings_.sweep_peaks;
  std::vector<GridTransform> peaks;
  for (const GlobalHypothesis& peak : pair.search(at_accepted)) {
    peaks.push_back(peak.T_to_from);
  }
  if (!peaks.empty() && settings_.sweep_prefilter_rate > 0.0) {  // far dirtier peaks: not placed
    const SampledComparison& sampled = pair.sampled();
    const double bar = settings_.sweep_prefilter_rate * sampled.disagreementRate(result.T_to_from);
    peaks.erase(std::remove_if(peaks.begin(), peaks.end(),
                               [&](const GridTransform& peak) {
                                 return sampled.disagreesMoreThan(peak, bar);
                               }),
                peaks.end());
  }
  if (judge_.cleanerRivalAmong(from, to, result.T_to_from, peaks)) {
    result.accepted = false;
    result.reason =
        "a transform elsewhere at the same rotation explains the overlap more cleanly (a building "
        "that repeats)";
  }
}

std::vector<GridTransform> ChainMerger::turnedSweepPeaks(const GridMap& from, PreparedPair& pair,
                                                         const GridTransform& T_to_from) const {
  std::vector<GridTransform> peaks;
  if (settings_.alternative_sweep_degrees.empty()) {
    return peaks;
  }
  std::vector<double> turned;
  for (const double degrees : settings_.alternative_sweep_degrees) {
    turned.push_back(T_to_from.theta_rad + degrees * M_PI / 180.0);
  }
  GlobalSearchSettings at_turns = chainSweepSettings(settings_, std::move(turned));
  at_turns.exact_rotations = true;
  at_turns.peaks_per_rotation = settings_.alternative_sweep_peaks;
  at_turns.kept_hypotheses = settings_.alternative_sweep_peaks;
  // Peaks of one turn that land within alternative_cells of each other would be judged alike:
  // the better one stands.
  const Eigen::Vector2d pivot = knownCentroid(from);
  const double alike_rad = 2.5 * at_turns.rotation_step_rad;
  for (const GlobalHypothesis& peak : pair.search(at_turns)) {
    const bool alike = std::any_of(peaks.begin(), peaks.end(), [&](const GridTransform& kept) {
      return turnBetween(kept, peak.T_to_from) <= alike_rad &&
             landsWithin(kept, peak.T_to_from, pivot, settings_.alternative_cells);
    });
    if (!alike) {
      peaks.push_back(peak.T_to_from);
    }
  }
  return peaks;
}

namespace {

/// The mean cell of `from` over its known cells that land on known cells of `to` (the centre of
/// the overlap); the centre of `from`'s known cells when none does.
Eigen::Vector2d overlapCentre(const GridMap& from, const GridMap& to,
                              const GridTransform& T_to_from) {
  const CellMapping to_cell(T_to_from);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double count = 0.0;
  for (int y = 0; y < from.geometry.height; ++y) {
    for (int x = 0; x < from.geometry.width; ++x) {
      if (from.at(x, y) == GridMap::kUnknown) {
        continue;
      }
      const Eigen::Vector2d there = to_cell(Eigen::Vector2d(x, y));
      const int to_x = roundToInt(there.x());
      const int to_y = roundToInt(there.y());
      if (to.geometry.contains(to_x, to_y) && to.at(to_x, to_y) != GridMap::kUnknown) {
        sum += Eigen::Vector2d(x, y);
        count += 1.0;
      }
    }
  }
  return count > 0.0 ? Eigen::Vector2d(sum / count) : knownCentroid(from);
}

/// T_to_from turned by `turn_rad` about `from`'s cell `pivot`: `pivot` stays where it lands.
GridTransform turnedAbout(const GridTransform& T_to_from, const Eigen::Vector2d& pivot,
                          double turn_rad) {
  GridTransform turned;
  turned.theta_rad = T_to_from.theta_rad + turn_rad;
  turned.t_cells = translationFromCentroids(turned.theta_rad, pivot, T_to_from.apply(pivot));
  return turned;
}

}  // namespace

void ChainMerger::judgeAgainstTurns(const GridMap& from, const GridMap& to, MergeResult& result) {
  const Eigen::Vector2d pivot = overlapCentre(from, to, result.T_to_from);
  std::vector<GridTransform> turned;
  for (const double degrees : settings_.turned_rival_degrees) {
    turned.push_back(turnedAbout(result.T_to_from, pivot, degrees * M_PI / 180.0));
  }
  // A turn that cannot reach turned_rival_similarity times the accepted agr - dis on any shift
  // of the search is not placed: it could not refuse.
  const std::vector<PlacedFit> fits =
      judge_.placedFits(from, to, result.T_to_from, turned, settings_.turned_rival_similarity);
  if (fits.empty() || fits.front().similarity <= 0) {
    return;
  }
  const PlacedFit& accepted = fits.front();
  const double rate_bar =
      accepted.structure < settings_.turned_rival_weak_structure
          ? std::max(settings_.turned_rival_rate, settings_.turned_rival_weak_rate)
          : settings_.turned_rival_rate;
  for (std::size_t i = 1; i < fits.size(); ++i) {
    const double similarity =
        static_cast<double>(fits[i].similarity) / static_cast<double>(accepted.similarity);
    const bool as_clean = fits[i].disagreement_rate <= rate_bar * accepted.disagreement_rate;
    if (similarity >= settings_.turned_rival_similarity && as_clean) {
      const std::string rate =
          accepted.disagreement_rate > 0.0
              ? reasonFigure(fits[i].disagreement_rate / accepted.disagreement_rate) +
                    " times as often"
              : "no more often";
      result.accepted = false;
      result.reason = "the overlap turned about its centre explains more of it about as cleanly (" +
                      reasonFigure(similarity) + " times agr - dis, its cells disagreeing " + rate +
                      "): the rotation is not fixed";
      return;
    }
  }
}

void ChainMerger::askSecondOpinion(const GridMap& from, const GridMap& to,
                                   const MapMerger& accepting, SecondOpinion& second,
                                   MergeResult& result) {
  const auto asked = std::find_if(steps_.begin(), steps_.end(), [&](const auto& step) {
    return step->name() == settings_.second_opinion_step;
  });
  if (asked == steps_.end() || asked->get() == &accepting ||
      result.wall_turn_share < settings_.second_opinion_turn_share) {
    return;
  }
  if (second.step == nullptr) {
    second = {asked->get(), (*asked)->merge(from, to)};
  }
  const MergeResult& opinion = second.result;
  if (opinion.accepted || opinion.refusal != MergeRefusal::kRotation) {
    return;
  }
  const Eigen::Vector2d pivot = overlapCentre(from, to, result.T_to_from);
  const double cells = cellsApartAt(opinion.T_to_from, result.T_to_from, pivot);
  const double turn_deg = turnBetween(opinion.T_to_from, result.T_to_from) * 180.0 / M_PI;
  if (cells > settings_.second_opinion_cells || turn_deg > settings_.second_opinion_deg) {
    return;
  }
  result.accepted = false;
  result.refusal = MergeRefusal::kRotation;
  result.reason = "the " + settings_.second_opinion_step + " step places the overlap " +
                  reasonFigure(cells) + " cells and " + reasonFigure(turn_deg) +
                  " degrees away, where " + opinion.reason + ": the rotation is not fixed";
}

ChainMerger::AlternativeBar ChainMerger::alternativeBar(const MergeResult& alone) const {
  if (alone.accepted) {
    return {settings_.cleaner_alternative_rate, 0.0, settings_.cleaner_alternative_min_z, 0.0};
  }
  switch (alone.refusal) {
    case MergeRefusal::kEntropy:
    case MergeRefusal::kTranslation:
      return {settings_.slid_alternative_rate, 0.0, 0.0, 0.0};
    case MergeRefusal::kStructure:
      return {settings_.walls_alternative_rate, settings_.walls_alternative_overlap, 0.0,
              settings_.walls_alternative_min_turn_deg};
    default:
      return {};
  }
}

bool ChainMerger::refusedForAlternative(const GridMap& from, const GridMap& to,
                                        const GridTransform& hypothesis, const Accepted& accepted,
                                        std::vector<GridTransform>& judged,
                                        std::vector<GridTransform>& undecided,
                                        MergeResult& result) {
  const MergeResult alone = judge_.judgeHypotheses(from, to, {hypothesis});
  judged.push_back(hypothesis);
  judged.push_back(alone.T_to_from);
  const AlternativeBar bar = alternativeBar(alone);
  if (bar.rate <= 0.0 ||
      landsWithin(result.T_to_from, alone.T_to_from, accepted.pivot, settings_.alternative_cells) ||
      turnBetween(result.T_to_from, alone.T_to_from) * 180.0 / M_PI < bar.min_turn_deg) {
    return false;
  }
  const OverlapScore there = scoreOverlap(from, to, alone.T_to_from);
  const double ratio = disagreementRate(there) / accepted.rate;
  const bool overlaps_enough = static_cast<double>(there.overlap()) >=
                               bar.overlap * static_cast<double>(accepted.overlap.overlap());
  const double deviations = deviationsCleaner(there, accepted.rate);
  const bool beyond_chance = bar.min_z <= 0.0 || deviations >= bar.min_z;
  if (ratio <= bar.rate && overlaps_enough && beyond_chance) {
    undecided.push_back(result.T_to_from);
    undecided.push_back(alone.T_to_from);
    refuseForAlternative(accepted.pivot, alone, ratio, deviations, result);
    return true;
  }
  return false;
}

void ChainMerger::judgeAgainstAlternatives(const GridMap& from, const GridMap& to,
                                           const std::vector<GridTransform>& searched,
                                           PreparedPair& pair,
                                           std::vector<GridTransform>& undecided,
                                           MergeResult& result) {
  Accepted accepted;
  accepted.pivot = knownCentroid(from);
  accepted.overlap = scoreOverlap(from, to, result.T_to_from);
  accepted.rate = disagreementRate(accepted.overlap);
  if (accepted.rate <= 0.0) {
    return;  // no placement fits more cleanly than one without a single disagreement
  }
  std::vector<GridTransform> judged;  // hypotheses judged on their own, and where they settled
  const auto judgedAlready = [&](const GridTransform& hypothesis) {
    return landsWithin(result.T_to_from, hypothesis, accepted.pivot, settings_.alternative_cells) ||
           std::any_of(judged.begin(), judged.end(), [&](const GridTransform& T) {
             return landsWithin(T, hypothesis, accepted.pivot, settings_.alternative_cells);
           });
  };
  const double bar = settings_.alternative_prefilter_rate;
  for (const GridTransform& hypothesis : searched) {
    if (judgedAlready(hypothesis) ||
        disagreementRate(scoreOverlap(from, to, hypothesis)) > bar * accepted.rate) {
      continue;
    }
    if (refusedForAlternative(from, to, hypothesis, accepted, judged, undecided, result)) {
      return;
    }
  }
  const std::vector<GridTransform> swept = turnedSweepPeaks(from, pair, result.T_to_from);
  if (swept.empty()) {
    return;
  }
  // The sweep's many peaks are prefiltered on a sample of `from`'s cells, the accepted one too.
  const SampledComparison& sampled = pair.sampled();
  const double sampled_rate = sampled.disagreementRate(result.T_to_from);
  for (const GridTransform& peak : swept) {
    if (judgedAlready(peak) || sampled.disagreesMoreThan(peak, bar * sampled_rate)) {
      continue;
    }
    if (refusedForAlternative(from, to, peak, accepted, judged, undecided, result)) {
      return;
    }
  }
}

namespace {

double verificationAt(const GridMap& from, const CodeImage& to, const GridTransform& T_to_from,
                      const ComparisonTables& tables) {
  return verificationIndex(compareAt(knownCells(from, tables), to, T_to_from, tables, false));
}

}  // namespace

void refuseWhereSlidesCostLittle(const GridMap& from, const GridMap& to,
                                 const ChainSettings& settings, const SimilaritySettings& classes,
                                 const std::string& step, const std::string& chain,
                                 MergeResult& result) {
  if (!result.accepted || settings.min_slide_margin_cells <= 0) {
    return;
  }
  TruthSlideSettings slide_settings;
  slide_settings.similarity = classes;
  const TruthSlide slide = truthSlide(from, to, result.T_to_from, slide_settings);
  if (!slide.slid_found || slide.margin() >= settings.min_slide_margin_cells) {
    return;
  }
  result.accepted = false;
  result.refusal = MergeRefusal::kTranslation;
  result.method = chain;
  result.reason = step + ": the maps hardly fix the shift: slid by (" +
                  std::to_string(slide.slide.x()) + ", " + std::to_string(slide.slide.y()) +
                  ") cells the placement disagrees on " + std::to_string(slide.margin()) +
                  " more known cells (below " + std::to_string(settings.min_slide_margin_cells) +
                  ")";
}

void refuseWhereWallsCrossFloor(const GridMap& from, const GridMap& to,
                                const ChainSettings& settings, const SimilaritySettings& classes,
                                MergeResult& result) {
  if (!result.accepted || settings.floor_crossing_min_cells <= 0) {
    return;
  }
  const FloorCrossing ways[] = {
      floorCrossing(from, to, result.T_to_from, classes, settings.floor_crossing),
      floorCrossing(to, from, result.T_to_from.inverse(), classes, settings.floor_crossing)};
  for (int way = 0; way < 2; ++way) {
    const FloorCrossing& crossing = ways[way];
    if (crossing.run_cells < settings.floor_crossing_min_cells ||
        crossing.share() < settings.floor_crossing_min_share) {
      continue;
    }
    std::ostringstream reason;
    reason << "a run of " << crossing.run_cells << " wall cells of the "
           << (way == 0 ? "first" : "second") << " map crosses the other's open floor ("
           << 100.0 * crossing.share() << " % of its " << crossing.walls_on_known
           << " walls on known cells; bars " << settings.floor_crossing_min_cells << " cells and "
           << 100.0 * settings.floor_crossing_min_share << " %)";
    result.accepted = false;
    result.refusal = MergeRefusal::kStructure;
    result.reason = reason.str();
    return;
  }
}

void refuseWhereANeighbourPeaksHigher(const GridMap& from, const GridMap& to,
                                      const ChainSettings& settings, SeedMerger& judge,
                                      MergeResult& result) {
  if (!result.accepted || settings.neighbour_basin_min_v_gain >= 1.0) {
    return;
  }
  const NeighbourBasins basins =
      judge.neighbourBasinsAt(from, to, result.T_to_from, settings.neighbour_basins);
  if (basins.other_v <= basins.own_v + settings.neighbour_basin_min_v_gain) {
    return;
  }
  std::ostringstream reason;
  reason << "V peaks higher " << basins.other_cells << " cells and " << basins.other_deg
         << " degrees away (" << basins.other_v << " against " << basins.own_v
         << " at the accepted transform's peak; bar +" << settings.neighbour_basin_min_v_gain
         << ")";
  result.accepted = false;
  result.refusal = MergeRefusal::kRival;
  result.reason = reason.str();
}

void refineByPsi(const GridMap& from, const GridMap& to, const ChainSettings& settings,
                 const SimilaritySettings& classes, MergeResult& result) {
  RandomWalkSettings walk;
  walk.step_cells = 0.5;
  walk.step_rad = 0.25 * M_PI / 180.0;
  const RandomWalkResult refined =
      randomWalk(prepareDissimilarity(from, classes), prepareDissimilarity(to, classes),
                 result.T_to_from, walk);
  const Eigen::Vector2d centre(0.5 * from.geometry.width, 0.5 * from.geometry.height);
  if (cellsApartAt(refined.T_to_from, result.T_to_from, centre) > settings.max_refinement_cells ||
      turnBetween(refined.T_to_from, result.T_to_from) > settings.max_refinement_rad) {
    return;
  }
  const ComparisonTables tables(classes);
  const CodeImage to_codes = codeImage(to, 2, tables);
  const double refined_v = verificationAt(from, to_codes, refined.T_to_from, tables);
  if (refined_v >= verificationAt(from, to_codes, result.T_to_from, tables)) {
    result.T_to_from = refined.T_to_from;
    result.verification = refined_v;
    result.method += "+psi";
  }
}

}  // namespace mrslam::fusion
