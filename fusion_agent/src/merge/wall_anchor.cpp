// Wall anchoring (ours, step 7 of seed_merger.hpp): the translation that lays the most walls of
// each map near walls of the other. agr - dis is dominated by free cells, so near the truth it
// often grows by sliding the overlap a few cells into more shared open floor while the walls move
// into unknown space (on real crops up to 10 cells off a true start); walls alone pin it. The
// discrete searches of agr - dis and the wall ICP then settle the last cell and degree.

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <utility>
#include <vector>

#include "mrslam/fusion/merge/wall_balance.hpp"
#include "seed_stages.hpp"

namespace mrslam::fusion::seed {

namespace {

// The wall balance at every shift of T_to_from within ±reach, in row order (dy, then dx): the
// walls of `from` on `to` plus those of `to` on `from`.
std::vector<long long> shiftedBalances(const GridTransform& T_to_from, int reach,
                                       const SearchInputs& inputs, const ComparisonTables& tables) {
  std::vector<long long> balances = wallBalancesAfterShifts(
      inputs.occupied_from_samples, inputs.to, inputs.wall_balance_to, T_to_from, reach, tables);
  const std::vector<long long> onto_from = wallBalancesOfInverseShifts(
      inputs.occupied_to_samples, inputs.from, inputs.wall_balance_from, T_to_from, reach, tables);
  for (std::size_t k = 0; k < balances.size(); ++k) {
    balances[k] += onto_from[k];
  }
  return balances;
}

using ShiftBalance = std::pair<Eigen::Vector2i, long long>;

// The largest balance among the shifts at least kRunnerUpCells (Chebyshev) from `best_shift`.
std::optional<long long> runnerUp(const std::vector<ShiftBalance>& balances,
                                  const Eigen::Vector2i& best_shift) {
  std::optional<long long> runner_up;
  for (const auto& [shift, balance] : balances) {
    const Eigen::Vector2i gap = shift - best_shift;
    if (std::max(std::abs(gap.x()), std::abs(gap.y())) >= kRunnerUpCells &&
        (!runner_up || balance > *runner_up)) {
      runner_up = balance;
    }
  }
  return runner_up;
}

}  // namespace

long long wallBalance(const GridTransform& T_to_from, const SearchInputs& inputs,
                      const ComparisonTables& tables) {
  const StructureAgreement onto_to =
      structureAgreement(inputs.occupied_from_samples, inputs.to, T_to_from, tables);
  const StructureAgreement onto_from =
      structureAgreement(inputs.occupied_to_samples, inputs.from, T_to_from.inverse(), tables);
  return onto_to.near - onto_to.far + onto_from.near - onto_from.far;
}
WallSearch anchorOnWalls(const GridTransform& T_to_from, int reach, const SearchInputs& inputs,
                         const ComparisonTables& tables) {
  WallSearch search;
  search.best = T_to_from;
  const std::vector<long long> all = shiftedBalances(T_to_from, reach, inputs, tables);
  const int side = 2 * reach + 1;
  const long long unshifted = all[static_cast<std::size_t>(reach * side + reach)];
  search.best_balance = unshifted;
  Eigen::Vector2i best_shift = Eigen::Vector2i::Zero();
  std::vector<ShiftBalance> balances;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const Eigen::Vector2i shift(dx, dy);
      GridTransform shifted = T_to_from;
      shifted.t_cells += shift.cast<double>();
      const long long balance = all[static_cast<std::size_t>((dy + reach) * side + dx + reach)];
      balances.emplace_back(shift, balance);
      if (balance > search.best_balance) {
        search.best_balance = balance;
        search.best = shifted;
        best_shift = shift;
      }
    }
  }
  search.runner_up_balance = runnerUp(balances, best_shift).value_or(search.best_balance);
  return search;
}

namespace {

// Step 7's walls onto walls by ICP: `refined` moves there when agr - dis or the wall balance is
// at least as high.
void keepIcpOnWalls(const SearchInputs& inputs, const ComparisonTables& tables,
                    const SeedMergerSettings& settings, Refined& refined) {
  const GridTransform on_walls = refineOnWalls(refined.T_to_from, inputs, settings);
  const Agreement at_walls = compareAt(inputs.all_samples, inputs.to, on_walls, tables);
  if (at_walls.similarity() >= refined.full.similarity() ||
      wallBalance(on_walls, inputs, tables) >= wallBalance(refined.T_to_from, inputs, tables)) {
    refined.T_to_from = on_walls;
    refined.full = at_walls;
  }
}

// With `settle_alignment`: the wall-anchored transform aligned on both maps' walls replaces
// `refined` where V is at least as high there. The alignment climbs from the coarse grid's best
// point alone: from three starts here too, the transforms the acceptance judges moved, and the 40
// case sets had 2 more false accepts (23 against 21) and 2 fewer right merges (measured with the
// turn check at the first peak only).
void keepAlignedWhereVHolds(const GridTransform& anchored, const SearchInputs& inputs,
                            const ComparisonTables& tables, const SeedMergerSettings& settings,
                            Refined& refined) {
  if (!settings.settle_alignment || !inputs.walls_from || !inputs.walls_to) {
    return;
  }
  WallAlignmentSettings one_start = settings.wall_alignment;
  one_start.starts = 1;
  const GridTransform aligned =
      alignWalls(*inputs.walls_from, *inputs.walls_to, anchored, one_start);
  const Agreement at_aligned = compareAt(inputs.all_samples, inputs.to, aligned, tables);
  if (verificationIndex(at_aligned) >= verificationIndex(refined.full)) {
    refined.T_to_from = aligned;
    refined.full = at_aligned;
  }
}

}  // namespace

Refined settleOnWalls(const GridTransform& T_to_from, const SearchInputs& inputs,
                      const ComparisonTables& tables, const SeedMergerSettings& settings,
                      TranslationSearch& coarse) {
  const int reach = settings.translation_window_delta;
  const GridTransform anchored = anchorOnWalls(T_to_from, reach, inputs, tables).best;
  const GridTransform polished = polishRotation(anchored, inputs, tables, settings);
  Refined refined;
  refined.T_to_from =
      searchTranslation(inputs.fine_samples, inputs.to, polished, 1, tables, false).best_similarity;
  refined.full = compareAt(inputs.all_samples, inputs.to, refined.T_to_from, tables);
  if (settings.wall_icp_iterations > 0) {
    keepIcpOnWalls(inputs, tables, settings, refined);
  }
  keepAlignedWhereVHolds(anchored, inputs, tables, settings, refined);
  const WallSearch walls = anchorOnWalls(refined.T_to_from, reach, inputs, tables);
  coarse =
      searchTranslation(inputs.coarse_samples, inputs.to, refined.T_to_from, reach, tables, true);
  // Either measure may be flat along a corridor: the translation is judged by the flatter (the
  // merger lets decisive walls outweigh open floor, SeedMerger::translationFixed).
  const long long best = coarse.at_best_similarity.similarity();
  refined.wall_ambiguity = walls.best_balance > 0 ? static_cast<double>(walls.runner_up_balance) /
                                                        static_cast<double>(walls.best_balance)
                                                  : 1.0;
  refined.similarity_ambiguity =
      best > 0 ? static_cast<double>(coarse.runner_up_similarity) / static_cast<double>(best) : 1.0;
  refined.translation_ambiguity = std::max(refined.wall_ambiguity, refined.similarity_ambiguity);
  refined.wall_margin = walls.best_balance - walls.runner_up_balance;
  return refined;
}

}  // namespace mrslam::fusion::seed
