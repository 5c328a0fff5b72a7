#include "mrslam/fusion/merge/seed_merger.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mrslam/fusion/merge/reason_text.hpp"
#include "mrslam/fusion/merge/wall_balance.hpp"
#include "seed_stages.hpp"

namespace mrslam::fusion {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kFineSampleFactor = 4;  // the ±1 cell steps sample 4 times as densely as ±δ

// Adds the time since `start` to `total` and restarts the clock.
void lap(Clock::time_point& start, SeedMergeTimings::Duration& total) {
  const Clock::time_point now = Clock::now();
  total += now - start;
  start = now;
}

// Why two maps cannot be merged at all, or empty.
std::string inputRefusal(const GridMap& from, const GridMap& to) {
  if (!from.isValid() || !to.isValid() || from.cells.empty() || to.cells.empty()) {
    return "a map is empty or invalid";
  }
  if (std::abs(from.geometry.resolution_m - to.geometry.resolution_m) >
      1e-9 * to.geometry.resolution_m) {
    return "the maps differ in resolution";
  }
  return "";
}

}  // namespace

SeedMerger::SeedMerger(const SeedMergerSettings& settings)
    : settings_(settings), tables_(settings.similarity) {}

std::shared_ptr<const seed::SearchInputs> SearchInputsCache::find(const GridMap& from,
                                                                  const GridMap& to) const {
  for (const Entry& entry : entries_) {
    if (entry.from == from && entry.to == to) {
      return entry.inputs;
    }
  }
  return nullptr;
}

void SearchInputsCache::keep(const GridMap& from, const GridMap& to,
                             std::shared_ptr<const seed::SearchInputs> inputs) {
  entries_.insert(entries_.begin(), Entry{from, to, std::move(inputs)});
  if (entries_.size() > pairs_) {
    entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(pairs_), entries_.end());
  }
}

std::shared_ptr<const seed::SearchInputs> SeedMerger::searchInputsOf(const GridMap& from,
                                                                     const GridMap& to) {
  std::shared_ptr<const seed::SearchInputs> inputs = inputs_cache_->find(from, to);
  if (!inputs) {
    const std::shared_ptr<const seed::SearchInputs> reversed = inputs_cache_->find(to, from);
    inputs = std::make_shared<const seed::SearchInputs>(searchInputs(from, to, reversed.get()));
    inputs_cache_->keep(from, to, inputs);
  }
  return inputs;
}

seed::SearchInputs SeedMerger::searchInputs(const GridMap& from, const GridMap& to,
                                            const seed::SearchInputs* reversed) const {
  seed::SearchInputs inputs;
  // Each map's own parts built the other way already are taken from there.
  inputs.all_samples = reversed != nullptr ? reversed->all_to : knownCells(from, tables_);
  inputs.all_to = reversed != nullptr ? reversed->all_samples : knownCells(to, tables_);
  const KnownCellSampler sampler_from(inputs.all_samples, tables_);
  inputs.coarse_samples =
      sampler_from.sample(settings_.search_occupied_samples, settings_.search_free_samples);
  inputs.fine_samples = sampler_from.sample(kFineSampleFactor * settings_.search_occupied_samples,
                                            kFineSampleFactor * settings_.search_free_samples);
  for (const CellSample& sample : inputs.all_samples) {
    inputs.pivot_from += Eigen::Vector2d(sample.x, sample.y);
  }
  inputs.pivot_from /= std::max<double>(1.0, static_cast<double>(inputs.all_samples.size()));
  // Both code images have the pad the shifted searches read (from's is read by the structure
  // checks the other way round, where cells in a pad are unknown and count as off the image), so
  // the other way's serve this way swapped.
  const int pad = settings_.translation_window_delta + 2;
  const bool images_reversed =
      reversed != nullptr && reversed->to.pad == pad && reversed->from.pad == pad;
  inputs.to = images_reversed ? reversed->from : codeImage(to, pad, tables_);
  inputs.entropy_from = reversed != nullptr ? reversed->entropy_to : mapEntropy(from, tables_);
  inputs.entropy_to = reversed != nullptr ? reversed->entropy_from : mapEntropy(to, tables_);
  if (reversed != nullptr && reversed->walls_from && reversed->walls_to) {
    inputs.walls_from = reversed->walls_to;  // each map's wall field, built the other way
    inputs.walls_to = reversed->walls_from;
  } else if (settings_.wall_anchor && settings_.settle_alignment) {
    inputs.walls_from =
        std::make_shared<WallField>(from, settings_.similarity, settings_.wall_alignment);
    inputs.walls_to =
        std::make_shared<WallField>(to, settings_.similarity, settings_.wall_alignment);
  }
  inputs.from = images_reversed ? reversed->to : codeImage(from, pad, tables_);
  inputs.wall_balance_to =
      images_reversed ? reversed->wall_balance_from : wallBalanceImage(inputs.to);
  inputs.wall_balance_from =
      images_reversed ? reversed->wall_balance_to : wallBalanceImage(inputs.from);
  for (const CellSample& cell : inputs.all_to) {
    if (tables_.isOccupied(cell.code)) {
      inputs.occupied_to.push_back(cell);
    }
  }
  if (settings_.wall_icp_iterations > 0) {
    inputs.nearest_wall_to = std::make_shared<const seed::NearestWall>(inputs.occupied_to);
    inputs.occupied_from = seed::occupiedCells(
        settings_.wall_icp_samples > 0 ? sampler_from.sample(settings_.wall_icp_samples, 0)
                                       : inputs.all_samples,
        tables_);
  }
  inputs.occupied_to_samples =
      sampleKnownCells(inputs.occupied_to, tables_, settings_.search_occupied_samples, 0);
  for (const CellSample& cell : inputs.coarse_samples) {
    if (tables_.isOccupied(cell.code)) {
      inputs.occupied_from_samples.push_back(cell);
    }
  }
  return inputs;
}

BlockTimes SeedMerger::lastBlockTimes() const {
  const std::pair<const char*, SeedMergeTimings::Duration> blocks[] = {
      {"edges", timings_.edges},
      {"radon", timings_.radon},
      {"segments", timings_.segments},
      {"correlation", timings_.correlation},
      {"poses", timings_.poses},
      {"translation", timings_.translation},
      {"verification", timings_.verification},
      {"fallback", timings_.fallback},
      {"global", timings_.global},
      {"alignment", timings_.alignment}};
  BlockTimes times;
  for (const auto& [name, duration] : blocks) {
    if (duration.count() > 0.0) {
      addBlockTime(times, name, duration.count());
    }
  }
  return times;
}

MergeResult SeedMerger::merge(const GridMap& from, const GridMap& to) {
  timings_ = {};
  MergeResult result;
  result.method = name();
  result.reason = inputRefusal(from, to);
  if (!result.reason.empty()) {
    return result;
  }
  Clock::time_point clock = Clock::now();
  seed::PreparedMap prepared_from;
  seed::PreparedMap prepared_to;
  seed::prepareEdges(from, settings_, prepared_from);  // blocks 1-2
  seed::prepareEdges(to, settings_, prepared_to);
  lap(clock, timings_.edges);

  seed::prepareRadon(settings_, prepared_from);  // blocks 7.1-7.2
  seed::prepareRadon(settings_, prepared_to);
  const std::vector<double> radon_correlation =
      spectrumCorrelation(prepared_from.radon_profile, prepared_to.radon_profile);
  lap(clock, timings_.radon);

  std::mt19937 random(settings_.seed);
  seed::sampleSegments(settings_, random, prepared_from);  // blocks 3-4
  seed::sampleSegments(settings_, random, prepared_to);
  lap(clock, timings_.segments);

  const std::vector<seed::PairCandidate> pairs =
      seed::rankPairs(prepared_from, prepared_to, settings_);  // block 5
  result.trials = static_cast<int>(pairs.size());
  lap(clock, timings_.correlation);

  const seed::CoarseScorer scorer(prepared_from, to, settings_);
  const std::vector<seed::Hypothesis> hypotheses = seed::poseHypotheses(
      pairs, prepared_from, prepared_to, radon_correlation, scorer, settings_);  // blocks 6-7
  lap(clock, timings_.poses);

  const std::shared_ptr<const seed::SearchInputs> held = searchInputsOf(from, to);  // block 8
  const seed::SearchInputs& inputs = *held;
  std::vector<seed::Candidate> candidates =
      seed::searchCandidates(hypotheses, settings_.refined_hypotheses, inputs, tables_, settings_);
  seed::Refined refined = refineBest(candidates, inputs);
  lap(clock, timings_.translation);

  if ((candidates.empty() || !refusal(refined).empty()) && settings_.radon_fallback) {
    const std::vector<seed::Hypothesis> fallback = seed::fallbackHypotheses(
        prepared_from, prepared_to, to, radon_correlation, scorer, settings_);  // step 9
    result.trials += static_cast<int>(fallback.size());
    addCandidates(
        seed::searchCandidates(fallback, settings_.refined_hypotheses, inputs, tables_, settings_),
        inputs, candidates, refined);
    lap(clock, timings_.fallback);
  }
  if ((candidates.empty() || !refusal(refined).empty()) && settings_.global_search) {
    SeedMergerSettings sized = settings_;  // blocks large enough for the maps' size
    sized.global.coarse_cells =
        blockCellsForSize(from, to, settings_.global.coarse_cells, settings_.global_max_grid_cells);
    const seed::GlobalHypotheses global =
        seed::globalHypotheses(from, to, scorer, inputs, sized);  // step 10
    addGlobalCandidates(global.by_walls, settings_.global_candidates, seed::Stage::kGlobalSearch,
                        inputs, candidates, refined, result);
    if ((candidates.empty() || !refusal(refined).empty()) && settings_.global_fine_cells > 0 &&
        !global.by_walls.empty()) {
      SeedMergerSettings fine = settings_;  // step 10 again on a finer grid near its rotations
      fine.global.coarse_cells = blockCellsForSize(from, to, settings_.global_fine_cells,
                                                   2 * settings_.global_max_grid_cells);
      fine.global.free_agreement_hypotheses = 0;
      for (const seed::Hypothesis& hypothesis : global.by_walls) {
        fine.global.only_rotations_rad.push_back(hypothesis.T_to_from.theta_rad);
      }
      addGlobalCandidates(seed::globalHypotheses(from, to, scorer, inputs, fine).by_walls,
                          settings_.global_candidates, seed::Stage::kFineGlobalSearch, inputs,
                          candidates, refined, result);
    }
    if ((candidates.empty() || !refusal(refined).empty()) && !global.by_free_agreement.empty()) {
      // The first sweep's peaks of walls and free floor, last: judged apart, as the coarse score
      // of walls near walls ranks them low by design.
      addGlobalCandidates(global.by_free_agreement, settings_.global.free_agreement_hypotheses,
                          seed::Stage::kFreeGlobalSearch, inputs, candidates, refined, result);
    }
    lap(clock, timings_.global);
  }

  if (candidates.empty()) {
    result.reason = "no pose hypothesis: " + std::to_string(prepared_from.segments.size()) +
                    " and " + std::to_string(prepared_to.segments.size()) + " verified segments";
    return result;
  }
  if (!refusal(refined).empty()) {
    // The best candidate is refused: the next ones get their chance, each facing every other
    // candidate as a rival (so one that a better-ranked transform explains as well is refused).
    if (std::optional<seed::Refined> next = nextAcceptable(candidates, inputs, refined)) {
      refined = *next;
    }
  }
  judge(refined, inputs, result);  // block 9
  lap(clock, timings_.verification);
  alignOn(inputs, from, to, &refined.full, result);
  lap(clock, timings_.alignment);
  return result;
}

MergeResult SeedMerger::judgeHypotheses(const GridMap& from, const GridMap& to,
                                        const std::vector<GridTransform>& hypotheses) {
  MergeResult result;
  result.method = seed::stageName(seed::Stage::kGiven);
  result.trials = static_cast<int>(hypotheses.size());
  result.reason = inputRefusal(from, to);
  if (!result.reason.empty()) {
    return result;
  }
  if (hypotheses.empty()) {
    result.reason = "no pose hypothesis given";
    return result;
  }
  std::vector<seed::Hypothesis> given;  // the given order is kept where hypotheses repeat
  for (const GridTransform& T_to_from : hypotheses) {
    given.push_back({T_to_from, -static_cast<double>(given.size()), seed::Stage::kGiven});
  }
  const std::shared_ptr<const seed::SearchInputs> held = searchInputsOf(from, to);
  const seed::SearchInputs& inputs = *held;
  const std::vector<seed::Candidate> candidates =
      seed::searchCandidates(given, static_cast<int>(given.size()), inputs, tables_, settings_);
  seed::Refined refined = refineBest(candidates, inputs);
  if (!refusal(refined).empty()) {
    if (std::optional<seed::Refined> next = nextAcceptable(candidates, inputs, refined)) {
      refined = *next;
    }
  }
  judge(refined, inputs, result);
  return result;
}

double SeedMerger::rivalShareAgainst(const GridMap& from, const GridMap& to,
                                     const GridTransform& T_to_from,
                                     const std::vector<GridTransform>& others) {
  if (!inputRefusal(from, to).empty() || others.empty()) {
    return 0.0;
  }
  const std::shared_ptr<const seed::SearchInputs> held = searchInputsOf(from, to);
  const seed::SearchInputs& inputs = *held;
  std::vector<seed::Candidate> facing = placedFacing(T_to_from, others, inputs);
  if (facing.empty()) {
    return 0.0;
  }
  for (int check = 0;; ++check) {
    const double share = seed::rivalShare(facing, inputs, tables_, settings_);
    const std::optional<std::size_t> rival = seed::rivalOf(facing, inputs, settings_);
    if (share <= settings_.max_rival_share || check >= settings_.refined_rivals || !rival) {
      return share;
    }
    const seed::Refined rival_refined =
        seed::finalize(facing[*rival].T_to_from, inputs, tables_, settings_);
    if (settlesApart(rival_refined, facing.front(), inputs)) {
      return share;
    }
    dropRival(facing, *rival, rival_refined.T_to_from, inputs);
  }
}

bool SeedMerger::cleanerRivalAmong(const GridMap& from, const GridMap& to,
                                   const GridTransform& T_to_from,
                                   const std::vector<GridTransform>& others) {
  if (!inputRefusal(from, to).empty() || others.empty()) {
    return false;
  }
  const std::shared_ptr<const seed::SearchInputs> held = searchInputsOf(from, to);
  const seed::SearchInputs& inputs = *held;
  // Only rivals whose walls meet walls as well as the transform's can be cleaner
  // (cleanerRivalOf): the others are not measured.
  std::vector<seed::Candidate> facing = placedFacing(T_to_from, others, inputs, true);
  for (int check = 0; !facing.empty() && check <= settings_.refined_rivals; ++check) {
    const std::optional<std::size_t> rival = seed::cleanerRivalOf(facing, inputs, settings_);
    if (!rival) {
      return false;
    }
    const seed::Refined rival_refined =
        seed::finalize(facing[*rival].T_to_from, inputs, tables_, settings_);
    if (!failsOnItsOwn(rival_refined) && settlesApart(rival_refined, facing.front(), inputs)) {
      return true;
    }
    dropRival(facing, *rival, rival_refined.T_to_from, inputs);
  }
  return false;
}

std::vector<PlacedFit> SeedMerger::placedFits(const GridMap& from, const GridMap& to,
                                              const GridTransform& T_to_from,
                                              const std::vector<GridTransform>& others,
                                              double least_share) {
  std::vector<PlacedFit> fits;
  if (!inputRefusal(from, to).empty()) {
    return fits;
  }
  const std::shared_ptr<const seed::SearchInputs> held = searchInputsOf(from, to);
  const seed::SearchInputs& inputs = *held;
  for (const seed::Candidate& placed :
       placedFacing(T_to_from, others, inputs, false, least_share)) {
    fits.push_back(
        {placed.T_to_from, placed.similarity, placed.disagreement_rate, placed.structure});
  }
  return fits;
}

void SeedMerger::alignOnInputs(const GridMap& from, const GridMap& to, MergeResult& result) {
  if (!settings_.wall_alignment.enabled || !result.accepted) {
    return;
  }
  if (!inputRefusal(from, to).empty()) {
    alignAccepted(from, to, settings_.wall_alignment, settings_.similarity, result);
    return;
  }
  alignOn(*searchInputsOf(from, to), from, to, nullptr, result);
}

NeighbourBasins SeedMerger::neighbourBasinsAt(const GridMap& from, const GridMap& to,
                                              const GridTransform& T_to_from,
                                              const NeighbourBasinSettings& settings) {
  if (!inputRefusal(from, to).empty()) {
    return neighbourBasins(from, to, settings_.similarity, T_to_from, settings);
  }
  const std::shared_ptr<const seed::SearchInputs> held = searchInputsOf(from, to);
  return neighbourBasins(held->all_samples, held->to, tables_, T_to_from, settings);
}

void SeedMerger::alignOn(const seed::SearchInputs& inputs, const GridMap& from, const GridMap& to,
                         const Agreement* at_found, MergeResult& result) const {
  if (inputs.walls_from && inputs.walls_to) {  // block 8's fields, when it settled on them
    alignAccepted({*inputs.walls_from, *inputs.walls_to, tables_, inputs.all_samples, inputs.to,
                   inputs.entropy_from, inputs.entropy_to, at_found},
                  settings_.wall_alignment, result);
  } else {
    alignAccepted(from, to, settings_.wall_alignment, settings_.similarity, result);
  }
}

bool SeedMerger::settlesApart(const seed::Refined& rival, const seed::Candidate& chosen,
                              const seed::SearchInputs& inputs) {
  return (rival.T_to_from.apply(inputs.pivot_from) - chosen.T_to_from.apply(inputs.pivot_from))
             .norm() > seed::kRivalCells;
}

void SeedMerger::dropRival(std::vector<seed::Candidate>& facing, std::size_t rival,
                           const GridTransform& refined, const seed::SearchInputs& inputs) {
  const GridTransform gone = facing[rival].T_to_from;
  facing.erase(std::remove_if(facing.begin() + 1, facing.end(),
                              [&](const seed::Candidate& candidate) {
                                return samePlace(candidate.T_to_from, gone, inputs) ||
                                       samePlace(candidate.T_to_from, refined, inputs);
                              }),
               facing.end());
}

std::vector<GridTransform> SeedMerger::ableToReach(const seed::Candidate& placed,
                                                   const std::vector<GridTransform>& others,
                                                   double least_share,
                                                   const seed::SearchInputs& inputs) const {
  if (least_share <= 0.0 || placed.similarity <= 0 || others.empty()) {
    return others;
  }
  // Every shift of the search lies within δ + 1 cells (the ±1 step after ±δ); a cell more for
  // the rounding of the landing.
  const seed::ReachableKnown reachable(inputs.to, settings_.translation_window_delta + 2);
  std::vector<GridTransform> able;
  for (const GridTransform& other : others) {
    const double most =
        static_cast<double>(seed::mostSimilarity(other, inputs.coarse_samples, reachable));
    if (most / static_cast<double>(placed.similarity) >= least_share) {
      able.push_back(other);
    }
  }
  return able;
}

std::vector<seed::Candidate> SeedMerger::placedFacing(const GridTransform& T_to_from,
                                                      const std::vector<GridTransform>& all_others,
                                                      const seed::SearchInputs& inputs,
                                                      bool only_as_walled,
                                                      double least_share) const {
  std::vector<seed::Candidate> facing = seed::searchCandidates(
      {{T_to_from, 0.0, seed::Stage::kGiven}}, 1, inputs, tables_, settings_);
  if (facing.empty()) {
    return facing;
  }
  const std::vector<GridTransform> others =
      ableToReach(facing.front(), all_others, least_share, inputs);
  std::vector<seed::Hypothesis> given;
  for (const GridTransform& other : others) {
    given.push_back({other, -static_cast<double>(given.size()), seed::Stage::kGiven});
  }
  const double structure_floor =
      only_as_walled ? std::max(facing.front().structure, settings_.min_structure_agreement)
                     : -std::numeric_limits<double>::infinity();
  const std::vector<seed::Candidate> placed = seed::searchCandidates(
      given, static_cast<int>(given.size()), inputs, tables_, settings_, structure_floor);
  facing.insert(facing.end(), placed.begin(), placed.end());
  return facing;
}

void SeedMerger::addGlobalCandidates(std::vector<seed::Hypothesis> hypotheses, int count,
                                     seed::Stage stage, const seed::SearchInputs& inputs,
                                     std::vector<seed::Candidate>& candidates,
                                     seed::Refined& refined, MergeResult& result) const {
  for (seed::Hypothesis& hypothesis : hypotheses) {
    hypothesis.stage = stage;
  }
  result.trials += static_cast<int>(hypotheses.size());
  addCandidates(seed::searchCandidates(hypotheses, count, inputs, tables_, settings_), inputs,
                candidates, refined);
}

void SeedMerger::addCandidates(const std::vector<seed::Candidate>& more,
                               const seed::SearchInputs& inputs,
                               std::vector<seed::Candidate>& candidates,
                               seed::Refined& refined) const {
  const std::vector<seed::Candidate> tried = candidates;
  candidates = seed::mergeCandidates(candidates, more, settings_);
  if (tried.empty() || (!candidates.empty() &&
                        !sameTransform(candidates.front().T_to_from, tried.front().T_to_from))) {
    refined = refineBest(candidates, inputs);
  }
  refined.rival_share = seed::rivalShare(candidates, inputs, tables_, settings_);
}

std::optional<seed::Refined> SeedMerger::nextAcceptable(
    const std::vector<seed::Candidate>& candidates, const seed::SearchInputs& inputs,
    const seed::Refined& first) const {
  const std::size_t judged =
      std::min(candidates.size(), static_cast<std::size_t>(settings_.judged_candidates));
  const std::size_t from = settings_.refined_rivals > 0 ? 0 : 1;  // the first was judged already
  for (std::size_t k = from; k < judged; ++k) {
    seed::Refined refined = first;
    if (k > 0) {
      refined = seed::finalize(candidates[k].T_to_from, inputs, tables_, settings_);
      refined.stage = candidates[k].stage;
      refined.rank = k;
    }
    std::vector<bool> excluded(candidates.size(), false);
    for (int check = 0;; ++check) {
      std::vector<seed::Candidate> facing = {candidates[k]};
      std::vector<std::size_t> index = {k};
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (i != k && !excluded[i]) {
          facing.push_back(candidates[i]);
          index.push_back(i);
        }
      }
      refined.rival_share = seed::rivalShare(facing, inputs, tables_, settings_);
      if (refusal(refined).empty()) {
        return refined;
      }
      // Refused for a rival alone: the rival counts only when, refined itself, it passes its own
      // tests somewhere else (a copy of the candidate slid along a corridor often settles back
      // onto it).
      const std::optional<std::size_t> rival = seed::rivalOf(facing, inputs, settings_);
      seed::Refined alone = refined;
      alone.rival_share = 0.0;
      if (check >= settings_.refined_rivals || !rival || !refusal(alone).empty()) {
        break;
      }
      const std::size_t r = index[*rival];
      const seed::Refined rival_refined =
          seed::finalize(candidates[r].T_to_from, inputs, tables_, settings_);
      const double apart = (rival_refined.T_to_from.apply(inputs.pivot_from) -
                            refined.T_to_from.apply(inputs.pivot_from))
                               .norm();
      if (!failsOnItsOwn(rival_refined) && apart > seed::kRivalCells) {
        break;
      }
      // The rival goes, and with it every candidate that places `from` as it does (before or
      // after its refinement): the other steps of the same slide.
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        excluded[i] =
            excluded[i] || i == r ||
            (i != k && (samePlace(candidates[i].T_to_from, candidates[r].T_to_from, inputs) ||
                        samePlace(candidates[i].T_to_from, rival_refined.T_to_from, inputs)));
      }
    }
  }
  return std::nullopt;
}

bool SeedMerger::samePlace(const GridTransform& a, const GridTransform& b,
                           const seed::SearchInputs& inputs) {
  constexpr double kSameTurnRad = 5.0 * M_PI / 180.0;
  return (a.apply(inputs.pivot_from) - b.apply(inputs.pivot_from)).norm() <= seed::kRivalCells &&
         std::abs(std::remainder(a.theta_rad - b.theta_rad, 2.0 * M_PI)) <= kSameTurnRad;
}

bool SeedMerger::failsOnItsOwn(const seed::Refined& refined) const {
  const long long overlap = refined.full.overlap();
  return (overlap < settings_.min_overlap_cells && !smallOverlapDecisive(refined)) ||
         verificationIndex(refined.full) < settings_.min_verification_v || !wallsMeet(refined) ||
         entropyDisagrees(refined);
}

seed::Refined SeedMerger::refineBest(const std::vector<seed::Candidate>& candidates,
                                     const seed::SearchInputs& inputs) const {
  seed::Refined refined;
  if (!candidates.empty()) {
    refined = seed::finalize(candidates.front().T_to_from, inputs, tables_, settings_);
    refined.stage = candidates.front().stage;
    refined.rival_share = seed::rivalShare(candidates, inputs, tables_, settings_);
  }
  return refined;
}

void SeedMerger::judge(const seed::Refined& refined, const seed::SearchInputs& inputs,
                       MergeResult& result) const {
  result.T_to_from = refined.T_to_from;
  result.method = seed::stageName(refined.stage);
  result.verification = verificationIndex(refined.full);
  result.entropy = mergedEntropy(inputs.entropy_from, inputs.entropy_to, refined.full);
  const Refusal refused = refusal(refined);
  result.reason = refused.reason;
  result.refusal = refused.kind;
  result.accepted = refused.empty();
}

bool SeedMerger::smallOverlapDecisive(const seed::Refined& refined) const {
  // Every overlapping wall meets a wall both ways (or nearly every one where the cells fit
  // cleanly) and no other transform explains the overlap.
  const long long overlap = refined.full.overlap();
  if (settings_.small_overlap_cells <= 0 || overlap < settings_.small_overlap_cells ||
      refined.rival_share > 0.0) {
    return false;
  }
  return refined.structure >= settings_.small_overlap_structure ||
         (refined.structure >= settings_.clean_small_overlap_structure &&
          verificationIndex(refined.full) >= settings_.clean_small_overlap_min_v);
}

bool SeedMerger::translationFixed(const seed::Refined& refined) const {
  if (refined.translation_ambiguity <= settings_.max_translation_ambiguity) {
    return true;
  }
  // Walls that clearly pin the shift outweigh open floor that slides along a corridor.
  return refined.wall_ambiguity <= settings_.decisive_wall_ambiguity &&
         (refined.similarity_ambiguity <= settings_.max_open_floor_ambiguity ||
          wallsOutweighFloor(refined));
}

bool SeedMerger::wallsOutweighFloor(const seed::Refined& refined) const {
  if (refined.wall_ambiguity > settings_.decisive_wall_ambiguity) {
    return false;
  }
  // A wide lead of walls at a good V, or a narrower lead where the cells fit more cleanly.
  const double verification = verificationIndex(refined.full);
  return (refined.wall_margin >= settings_.decisive_wall_margin &&
          verification >= settings_.walls_over_floor_min_v) ||
         (refined.wall_margin >= settings_.clean_decisive_wall_margin &&
          verification >= settings_.clean_walls_over_floor_min_v);
}

bool SeedMerger::wallsMeet(const seed::Refined& refined) const {
  return refined.structure >= settings_.min_structure_agreement || frontierExcuses(refined);
}

bool SeedMerger::frontierExcuses(const seed::Refined& refined) const {
  return refined.frontier_structure >= settings_.min_structure_off_frontier &&
         verificationIndex(refined.full) >= settings_.min_v_off_frontier;
}

bool SeedMerger::entropyDisagrees(const seed::Refined& refined) const {
  return refined.entropy_gap_cells > settings_.entropy_agreement_cells &&
         !wallsOutweighFloor(refined);
}

SeedMerger::Refusal SeedMerger::refusal(const seed::Refined& refined) const {
  Refusal refused = cellsRefusal(refined);
  if (!refused.empty()) {
    return refused;
  }
  refused = placementRefusal(refined);
  if (refined.structure >= settings_.min_structure_agreement) {
    return refused;
  }
  // The walls on the other map's frontier left out, the walls may meet: then accepted only when
  // nothing else refuses; otherwise the strict bar is the reason, as it always was.
  if (refused.empty() && frontierExcuses(refined)) {
    return {};
  }
  return {MergeRefusal::kStructure, "only " + reasonFigure(refined.structure) +
                                        " of the overlapping walls meet walls (below " +
                                        reasonFigure(settings_.min_structure_agreement) + "; " +
                                        reasonFigure(refined.frontier_structure) +
                                        " off the other map's frontier)"};
}

SeedMerger::Refusal SeedMerger::cellsRefusal(const seed::Refined& refined) const {
  const long long overlap = refined.full.overlap();
  const double verification = verificationIndex(refined.full);
  if (overlap < settings_.min_overlap_cells && !smallOverlapDecisive(refined)) {
    return {MergeRefusal::kOverlap, "overlap of " + std::to_string(overlap) +
                                        " known cells is below " +
                                        std::to_string(settings_.min_overlap_cells)};
  }
  if (verification < settings_.min_verification_v) {
    return {MergeRefusal::kVerification, "verification index " + reasonFigure(verification) +
                                             " is below " +
                                             reasonFigure(settings_.min_verification_v)};
  }
  if (refined.stage == seed::Stage::kFineGlobalSearch &&
      verification < settings_.global_fine_min_verification) {
    return {MergeRefusal::kVerification, "verification index " + reasonFigure(verification) +
                                             " of a finer sweep's transform is below " +
                                             reasonFigure(settings_.global_fine_min_verification)};
  }
  if (refined.stage == seed::Stage::kFreeGlobalSearch &&
      verification < settings_.global_free_min_verification) {
    return {MergeRefusal::kVerification, "verification index " + reasonFigure(verification) +
                                             " of a transform found with free agreement is below " +
                                             reasonFigure(settings_.global_free_min_verification)};
  }
  if (refined.rank >= static_cast<std::size_t>(settings_.late_rank) &&
      verification < settings_.late_rank_min_verification) {
    return {MergeRefusal::kVerification, "verification index " + reasonFigure(verification) +
                                             " of the candidate ranked " +
                                             std::to_string(refined.rank + 1) + " is below " +
                                             reasonFigure(settings_.late_rank_min_verification)};
  }
  return {};
}

SeedMerger::Refusal SeedMerger::placementRefusal(const seed::Refined& refined) const {
  if (entropyDisagrees(refined)) {
    return {MergeRefusal::kEntropy, "the entropy minimum lies " +
                                        reasonFigure(refined.entropy_gap_cells) +
                                        " cells from the best similarity"};
  }
  if (!translationFixed(refined)) {
    return {MergeRefusal::kTranslation,
            "the overlap does not fix the translation: a shift of " +
                std::to_string(kRunnerUpCells) + " cells or more scores " +
                reasonFigure(refined.translation_ambiguity) + " of the best (walls " +
                reasonFigure(refined.wall_ambiguity) + ", ahead by " +
                std::to_string(refined.wall_margin) + " sampled walls; agr - dis " +
                reasonFigure(refined.similarity_ambiguity) + ")"};
  }
  if (refined.rival_share > settings_.max_rival_share) {
    return {MergeRefusal::kRival, "another transform explains the overlap almost as well (" +
                                      reasonFigure(refined.rival_share) + " of the best)"};
  }
  return {};
}

MergeResult judgeFoundHypotheses(SeedMerger& judge, const GridMap& from, const GridMap& to,
                                 const std::vector<GridTransform>& found, const std::string& method,
                                 const std::string& what) {
  MergeResult result;
  if (from.geometry.resolution_m != to.geometry.resolution_m) {
    result.reason = "the maps' resolutions differ";
  } else if (found.empty()) {
    result.reason = what + ": no hypothesis";
  } else {
    result = judge.judgeHypotheses(from, to, found);
    if (!result.accepted) {
      result.reason = what + ": " + result.reason;
    }
  }
  result.method = method;
  return result;
}

}  // namespace mrslam::fusion
