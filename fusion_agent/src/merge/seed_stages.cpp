#include "seed_stages.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "mrslam/fusion/merge/approximate_pose.hpp"
#include "mrslam/fusion/merge/wall_balance.hpp"

namespace mrslam::fusion::seed {

namespace {

constexpr double kFollowSlack = 1.15;  // smoothing shortens a cell chain: follow a bit farther
constexpr double kDistinctCells = 3.0;
constexpr double kDistinctRad = 2.0 * M_PI / 180.0;

struct ScoredPair {
  double score;
  int from;
  int to;
};

// Turning about the centre of `from`'s known cells keeps the overlap in place.
Eigen::Vector2d translationAfterTurn(const GridTransform& T_to_from, double theta,
                                     const SearchInputs& inputs) {
  const Eigen::Vector2d pivot = inputs.pivot_from;
  return translationFromCentroids(theta, pivot, T_to_from.apply(pivot));
}

bool sameEnds(const Segment& a, const Segment& b) {
  constexpr double kSameCells = 1.5;
  const auto near = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return (p - q).norm() < kSameCells;
  };
  return (near(a.points.front(), b.points.front()) && near(a.points.back(), b.points.back())) ||
         (near(a.points.front(), b.points.back()) && near(a.points.back(), b.points.front()));
}

}  // namespace

void prepareEdges(const GridMap& map, const SeedMergerSettings& settings, PreparedMap& prepared) {
  prepared.occupied = occupiedImage(map, settings.edges.occupied_threshold);
  prepared.edges = smoothEdges(detectEdges(prepared.occupied, settings.edges),
                               settings.edges.edge_merge_distance_dt);
  prepared.edge_cells = nonZeroCells(prepared.edges);
}

void prepareRadon(const SeedMergerSettings& settings, PreparedMap& prepared) {
  prepared.radon =
      radonTransform(prepared.edge_cells, prepared.edges.size(), settings.radon.angle_step_rad);
  prepared.radon_profile = radonSpectrum(prepared.radon, settings.radon.profile_highpass_rad);
}

void sampleSegments(const SeedMergerSettings& settings, std::mt19937& random,
                    PreparedMap& prepared) {
  prepared.segments.clear();
  prepared.reversed.clear();
  prepared.histograms.clear();
  if (prepared.edge_cells.empty()) {
    return;
  }
  EdgeFollower follower(prepared.edges, settings.segments.gap_jump_cells);
  std::uniform_int_distribution<std::size_t> pick(0, prepared.edge_cells.size() - 1);
  const double length = kFollowSlack * settings.segments.segment_points_n + 4.0;
  for (int trial = 0; trial < settings.segment_trials &&
                      static_cast<int>(prepared.segments.size()) < settings.max_segments;
       ++trial) {
    const std::optional<Segment> segment =
        makeSegment(follower.follow(prepared.edge_cells[pick(random)], length), settings.segments);
    if (!segment) {
      continue;
    }
    if (std::any_of(prepared.segments.begin(), prepared.segments.end(),
                    [&](const Segment& kept) { return sameEnds(kept, *segment); })) {
      continue;  // a short edge gives the same segment from every start on it
    }
    SegmentHistograms histograms = segmentHistograms(*segment, settings.verification);
    if (verifySegment(*segment, histograms, settings.verification) == SegmentVerdict::kAccepted) {
      prepared.segments.push_back(*segment);
      prepared.reversed.push_back(reversedSegment(*segment));
      prepared.histograms.push_back(std::move(histograms));
    }
  }
}

std::vector<PairCandidate> rankPairs(const PreparedMap& from, const PreparedMap& to,
                                     const SeedMergerSettings& settings) {
  std::vector<ScoredPair> scored;
  for (std::size_t i = 0; i < from.segments.size(); ++i) {
    for (std::size_t j = 0; j < to.segments.size(); ++j) {
      const double score = std::max(histogramScore(from.histograms[i], to.histograms[j], false),
                                    histogramScore(from.histograms[i], to.histograms[j], true));
      scored.push_back({score, static_cast<int>(i), static_cast<int>(j)});
    }
  }
  const auto by_score = [](const ScoredPair& a, const ScoredPair& b) { return a.score > b.score; };
  if (static_cast<int>(scored.size()) > settings.correlated_pairs) {
    std::nth_element(scored.begin(), scored.begin() + settings.correlated_pairs, scored.end(),
                     by_score);
    scored.resize(static_cast<std::size_t>(settings.correlated_pairs));
  }
  std::vector<PairCandidate> pairs;
  for (const ScoredPair& pair : scored) {
    const auto i = static_cast<std::size_t>(pair.from);
    const auto j = static_cast<std::size_t>(pair.to);
    pairs.push_back({pair.from, pair.to,
                     matchSegments(from.segments[i], from.histograms[i], to.segments[j],
                                   to.reversed[j], to.histograms[j], settings.correlation)});
  }
  std::sort(pairs.begin(), pairs.end(), [](const PairCandidate& a, const PairCandidate& b) {
    return a.match.score > b.match.score;
  });
  if (static_cast<int>(pairs.size()) > settings.pose_trials) {
    pairs.resize(static_cast<std::size_t>(settings.pose_trials));
  }
  return pairs;
}

CoarseScorer::CoarseScorer(const PreparedMap& from, const GridMap& to,
                           const SeedMergerSettings& settings) {
  const std::vector<cv::Point> occupied = nonZeroCells(from.occupied);
  const std::size_t step =
      std::max<std::size_t>(1, occupied.size() / std::max(1, settings.coarse_samples));
  for (std::size_t i = 0; i < occupied.size(); i += step) {
    samples_.push_back(occupied[i]);
  }
  const int radius = settings.coarse_radius_cells;
  cv::Mat near;
  cv::dilate(
      occupiedImage(to, settings.similarity.occupied_threshold), near,
      cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1)));
  balance_ = cv::Mat(near.size(), CV_8S, cv::Scalar(0));
  for (int y = 0; y < near.rows; ++y) {
    for (int x = 0; x < near.cols; ++x) {
      const std::int8_t value = to.at(x, y);
      if (near.at<std::uint8_t>(y, x) != 0) {
        balance_.at<std::int8_t>(y, x) = 1;
      } else if (value >= 0 && value <= settings.similarity.free_threshold) {
        balance_.at<std::int8_t>(y, x) = -1;
      }
    }
  }
}

double CoarseScorer::score(const GridTransform& T_to_from) const {
  return scores(T_to_from, 0, 1).front();
}

std::vector<double> CoarseScorer::scores(const GridTransform& T_to_from, int reach,
                                         int step) const {
  const double c = std::cos(T_to_from.theta_rad);
  const double s = std::sin(T_to_from.theta_rad);
  std::vector<cv::Point> placed;
  placed.reserve(samples_.size());
  for (const cv::Point& p : samples_) {
    placed.emplace_back(
        static_cast<int>(std::floor(c * p.x - s * p.y + T_to_from.t_cells.x() + 0.5)),
        static_cast<int>(std::floor(s * p.x + c * p.y + T_to_from.t_cells.y() + 0.5)));
  }
  const std::vector<long long> balances = windowSums(balance_, placed, reach, step);
  const double count = std::max<double>(1.0, static_cast<double>(samples_.size()));
  std::vector<double> shares;
  shares.reserve(balances.size());
  for (const long long balance : balances) {
    shares.push_back(static_cast<double>(balance) / count);  // 0 without samples
  }
  return shares;
}

Hypothesis bestShift(const GridTransform& T_to_from, int reach, int step,
                     const CoarseScorer& scorer, Stage stage) {
  step = std::max(1, step);
  const int count = 2 * reach / step + 1;
  const std::vector<double> scores = scorer.scores(T_to_from, reach, step);
  Hypothesis best{T_to_from, -2.0, stage};
  for (int row = 0; row < count; ++row) {
    for (int column = 0; column < count; ++column) {
      const double score = scores[static_cast<std::size_t>(row * count + column)];
      if (score > best.coarse_score) {
        GridTransform shifted = T_to_from;
        shifted.t_cells += Eigen::Vector2d(-reach + column * step, -reach + row * step);
        best = {shifted, score, stage};
      }
    }
  }
  return best;
}

std::vector<Hypothesis> poseHypotheses(const std::vector<PairCandidate>& pairs,
                                       const PreparedMap& from, const PreparedMap& to,
                                       const std::vector<double>& radon_correlation,
                                       const CoarseScorer& scorer,
                                       const SeedMergerSettings& settings) {
  std::vector<Hypothesis> hypotheses;
  for (const PairCandidate& pair : pairs) {
    const auto [line_from, line_to] =
        matchedLines(from.segments[static_cast<std::size_t>(pair.from)],
                     to.segments[static_cast<std::size_t>(pair.to)], pair.match);
    for (const GridTransform& approximate : posesFromLines(line_from, line_to)) {
      const std::optional<double> theta = tuneRotation(radon_correlation, approximate.theta_rad,
                                                       settings.radon.rotation_window_rad);
      if (!theta) {
        continue;
      }
      Hypothesis hypothesis;
      hypothesis.T_to_from.theta_rad = *theta;
      hypothesis.T_to_from.t_cells =
          translationFromCentroids(*theta, line_from.centroid, line_to.centroid);
      hypothesis.coarse_score = scorer.score(hypothesis.T_to_from);
      hypotheses.push_back(hypothesis);
    }
  }
  return hypotheses;
}

std::vector<Hypothesis> bestDistinct(std::vector<Hypothesis> hypotheses, int count) {
  std::sort(hypotheses.begin(), hypotheses.end(), [](const Hypothesis& a, const Hypothesis& b) {
    return a.coarse_score > b.coarse_score;
  });
  std::vector<Hypothesis> kept;
  for (const Hypothesis& candidate : hypotheses) {
    if (static_cast<int>(kept.size()) >= count) {
      break;
    }
    const bool repeated = std::any_of(kept.begin(), kept.end(), [&](const Hypothesis& other) {
      return std::abs(std::remainder(candidate.T_to_from.theta_rad - other.T_to_from.theta_rad,
                                     2.0 * M_PI)) < kDistinctRad &&
             (candidate.T_to_from.t_cells - other.T_to_from.t_cells).norm() < kDistinctCells;
    });
    if (!repeated) {
      kept.push_back(candidate);
    }
  }
  return kept;
}

TranslationSearch searchAround(const GridTransform& T_to_from, const SearchInputs& inputs,
                               const ComparisonTables& tables, const SeedMergerSettings& settings) {
  // Every other shift of ±δ first, then every shift ±1 around the best of those.
  const TranslationSearch coarse =
      searchTranslation(inputs.coarse_samples, inputs.to, T_to_from,
                        settings.translation_window_delta, tables, false, 2);
  return searchTranslation(inputs.coarse_samples, inputs.to, coarse.best_similarity, 1, tables,
                           false);
}

namespace {

// The lesser structure agreement of the two directions (`strict`): the walls among
// `from_samples` (the coarse sample for a candidate, every known cell in block 9) on `to`'s and
// all of `to`'s walls on `from`'s (a wrong transform often passes one direction only); and the
// lesser of the two with the walls on the other map's frontier left out (`off_frontier`).
struct TwoWayStructure {
  double strict = 0.0;
  double off_frontier = 0.0;
};
TwoWayStructure twoWayStructure(const std::vector<CellSample>& from_samples,
                                const GridTransform& T_to_from, const SearchInputs& inputs,
                                const ComparisonTables& tables) {
  const StructureAgreement forward = structureAgreement(from_samples, inputs.to, T_to_from, tables);
  const StructureAgreement backward =
      structureAgreement(inputs.occupied_to, inputs.from, T_to_from.inverse(), tables);
  return {std::min(forward.index(), backward.index()),
          std::min(forward.indexOffFrontier(), backward.indexOffFrontier())};
}

// Whether a candidate can pass block 9's structure bar and (with `rank_by_overlap`) its overlap
// bar: a transform that overlaps only a few walls would be refused for its overlap anyway.
bool meetsBars(const Candidate& candidate, const SeedMergerSettings& settings) {
  return candidate.structure >= settings.min_structure_agreement &&
         (!settings.rank_by_overlap ||
          candidate.overlap_cells >= static_cast<double>(settings.min_overlap_cells));
}

void orderCandidates(std::vector<Candidate>& candidates, const SeedMergerSettings& settings) {
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](const Candidate& a, const Candidate& b) {
                     const bool a_meets = meetsBars(a, settings);
                     const bool b_meets = meetsBars(b, settings);
                     if (a_meets != b_meets) {
                       return a_meets;
                     }
                     return settings.wall_ranking ? a.walls > b.walls : a.similarity > b.similarity;
                   });
}

// The candidate's overlap (agr + dis over all of `from`'s known cells) and its disagreement rate.
void measureOverlap(const SearchInputs& inputs, const ComparisonTables& tables,
                    Candidate& candidate) {
  const Agreement all =
      compareAt(inputs.all_samples, inputs.to, candidate.T_to_from, tables, false);
  candidate.overlap_cells = static_cast<double>(all.overlap());
  candidate.disagreement_rate = 1.0 - verificationIndex(all);
}

// The best shift within ±1 cell and its agr - dis.
std::pair<GridTransform, long long> bestNearby(const GridTransform& T_to_from,
                                               const SearchInputs& inputs,
                                               const ComparisonTables& tables) {
  const TranslationSearch search =
      searchTranslation(inputs.coarse_samples, inputs.to, T_to_from, 1, tables, false);
  return {search.best_similarity, search.at_best_similarity.similarity()};
}

}  // namespace

GridTransform polishRotation(const GridTransform& T_to_from, const SearchInputs& inputs,
                             const ComparisonTables& tables, const SeedMergerSettings& settings) {
  auto [best, best_score] = bestNearby(T_to_from, inputs, tables);
  double step = settings.rotation_polish_step_rad;
  for (int level = 0; level < 2; ++level, step *= 0.5) {  // coarse steps, then half steps
    const GridTransform centre = best;
    const int reach = level == 0 ? static_cast<int>(settings.rotation_polish_rad / step) : 1;
    for (int i = -reach; i <= reach; ++i) {
      if (i == 0) {
        continue;
      }
      GridTransform turned = centre;
      turned.theta_rad = centre.theta_rad + i * step;
      turned.t_cells = translationAfterTurn(centre, turned.theta_rad, inputs);
      const auto [shifted, score] = bestNearby(turned, inputs, tables);
      if (score > best_score) {
        best_score = score;
        best = shifted;
      }
    }
  }
  return best;
}

const char* stageName(Stage stage) {
  switch (stage) {
    case Stage::kRadonFallback:
      return "seed/radon-fallback";
    case Stage::kGlobalSearch:
      return "seed/global-search";
    case Stage::kFineGlobalSearch:
      return "seed/global-search-fine";
    case Stage::kFreeGlobalSearch:
      return "seed/global-search-free";
    case Stage::kGiven:
      return "seed/given";
    case Stage::kSegments:
      break;
  }
  return "seed";
}

ReachableKnown::ReachableKnown(const CodeImage& to, int reach)
    : pad_(to.pad), reach_(std::max(0, reach)) {
  cv::Mat known;
  cv::compare(to.classes, 0, known, cv::CMP_NE);
  cv::dilate(known, near_known_,
             cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * reach_ + 1, 2 * reach_ + 1)));
}

bool ReachableKnown::at(const cv::Point& cell) const {
  const int x = cell.x + pad_;
  const int y = cell.y + pad_;
  if (x >= 0 && y >= 0 && x < near_known_.cols && y < near_known_.rows) {
    return near_known_.ptr<std::uint8_t>(y)[x] != 0;
  }
  const int width = near_known_.cols - 2 * pad_;
  const int height = near_known_.rows - 2 * pad_;
  return cell.x >= -reach_ && cell.y >= -reach_ && cell.x < width + reach_ &&
         cell.y < height + reach_;
}

long long mostSimilarity(const GridTransform& T_to_from, const std::vector<CellSample>& samples,
                         const ReachableKnown& reachable) {
  CellRounding rounding(T_to_from);
  long long most = 0;
  for (const CellSample& sample : samples) {
    most += reachable.at(rounding.landing(sample.x, sample.y)) ? 1 : 0;
  }
  return most;
}

std::vector<Candidate> searchCandidates(const std::vector<Hypothesis>& hypotheses, int count,
                                        const SearchInputs& inputs, const ComparisonTables& tables,
                                        const SeedMergerSettings& settings,
                                        double structure_floor) {
  std::vector<Candidate> candidates;
  for (const Hypothesis& hypothesis : bestDistinct(hypotheses, count)) {
    Candidate candidate{hypothesis.T_to_from, hypothesis.stage, 0, 0.0, 0, 0.0, 0.0};
    if (settings.wall_ranking) {
      const WallSearch walls =
          anchorOnWalls(hypothesis.T_to_from, settings.translation_window_delta, inputs, tables);
      candidate.T_to_from = walls.best;
      candidate.walls = walls.best_balance;
    } else {
      const TranslationSearch search = searchAround(hypothesis.T_to_from, inputs, tables, settings);
      candidate.T_to_from = search.best_similarity;
      candidate.similarity = search.at_best_similarity.similarity();
    }
    candidate.structure =
        twoWayStructure(inputs.coarse_samples, candidate.T_to_from, inputs, tables).strict;
    if (candidate.structure < structure_floor) {
      continue;
    }
    if (settings.wall_ranking) {
      candidate.similarity =
          compareAt(inputs.coarse_samples, inputs.to, candidate.T_to_from, tables, false)
              .similarity();
    }
    measureOverlap(inputs, tables, candidate);
    candidates.push_back(candidate);
  }
  orderCandidates(candidates, settings);
  return candidates;
}

namespace {

// Whether `other` covers the overlap only by covering more: its walls meet walls less well and
// its known cells disagree more often than the chosen transform's (dirtier_rival_structure,
// dirtier_rival_rate; two rates of 0 are not "more often").
bool dirtierThan(const Candidate& other, const Candidate& chosen,
                 const SeedMergerSettings& settings) {
  return settings.dirtier_rival_structure > 0.0 &&
         other.structure <= chosen.structure - settings.dirtier_rival_structure &&
         other.disagreement_rate > chosen.disagreement_rate &&
         other.disagreement_rate >= settings.dirtier_rival_rate * chosen.disagreement_rate;
}

// agr - dis over all known cells at the best shift within ±1 cell (fine samples).
long long fullSimilarity(const GridTransform& T_to_from, const SearchInputs& inputs,
                         const ComparisonTables& tables) {
  const TranslationSearch near =
      searchTranslation(inputs.fine_samples, inputs.to, T_to_from, 1, tables, false);
  return compareAt(inputs.all_samples, inputs.to, near.best_similarity, tables, false).similarity();
}

}  // namespace

std::optional<std::size_t> rivalOf(const std::vector<Candidate>& candidates,
                                   const SearchInputs& inputs, const SeedMergerSettings& settings) {
  if (candidates.empty() || candidates.front().similarity <= 0) {
    return std::nullopt;
  }
  const Eigen::Vector2d centre = candidates.front().T_to_from.apply(inputs.pivot_from);
  for (std::size_t i = 1; i < candidates.size(); ++i) {
    const Candidate& other = candidates[i];
    if (meetsBars(other, settings) && !dirtierThan(other, candidates.front(), settings) &&
        (other.T_to_from.apply(inputs.pivot_from) - centre).norm() > kRivalCells) {
      return i;
    }
  }
  return std::nullopt;
}

std::optional<std::size_t> cleanerRivalOf(const std::vector<Candidate>& candidates,
                                          const SearchInputs& inputs,
                                          const SeedMergerSettings& settings) {
  if (candidates.empty() || settings.cleaner_rival_rate <= 0.0) {
    return std::nullopt;
  }
  const Candidate& chosen = candidates.front();
  const Eigen::Vector2d centre = chosen.T_to_from.apply(inputs.pivot_from);
  for (std::size_t i = 1; i < candidates.size(); ++i) {
    const Candidate& other = candidates[i];
    if (meetsBars(other, settings) && other.structure >= chosen.structure &&
        (other.T_to_from.apply(inputs.pivot_from) - centre).norm() > kRivalCells &&
        other.disagreement_rate <= settings.cleaner_rival_rate * chosen.disagreement_rate) {
      return i;
    }
  }
  return std::nullopt;
}

bool cleanerRival(const std::vector<Candidate>& candidates, const SearchInputs& inputs,
                  const SeedMergerSettings& settings) {
  return cleanerRivalOf(candidates, inputs, settings).has_value();
}

double rivalShare(const std::vector<Candidate>& candidates, const SearchInputs& inputs,
                  const ComparisonTables& tables, const SeedMergerSettings& settings) {
  if (cleanerRival(candidates, inputs, settings)) {
    return 1.0;
  }
  const std::optional<std::size_t> rival = rivalOf(candidates, inputs, settings);
  if (!rival) {
    return 0.0;
  }
  const Candidate& chosen = candidates.front();
  const Candidate& other = candidates[*rival];
  const long long best = fullSimilarity(chosen.T_to_from, inputs, tables);
  const double by_similarity =
      best > 0 ? static_cast<double>(fullSimilarity(other.T_to_from, inputs, tables)) /
                     static_cast<double>(best)
               : 1.0;
  if (!settings.wall_ranking) {
    return by_similarity;
  }
  // Either measure may favour the wrong one: the rival is judged by the closer of the two.
  const double by_walls =
      chosen.walls > 0 ? static_cast<double>(other.walls) / static_cast<double>(chosen.walls) : 1.0;
  return std::max(by_similarity, by_walls);
}

std::vector<Candidate> mergeCandidates(std::vector<Candidate> a, const std::vector<Candidate>& b,
                                       const SeedMergerSettings& settings) {
  a.insert(a.end(), b.begin(), b.end());
  orderCandidates(a, settings);
  return a;
}

namespace {

// Step 7's translation by agr - dis (the seed paper's block 8 alone).
Refined settleBySimilarity(const GridTransform& polished, const SearchInputs& inputs,
                           const ComparisonTables& tables, const SeedMergerSettings& settings,
                           TranslationSearch& coarse) {
  coarse = searchTranslation(inputs.coarse_samples, inputs.to, polished,
                             settings.translation_window_delta, tables, true);
  const TranslationSearch fine_similarity =
      searchTranslation(inputs.fine_samples, inputs.to, coarse.best_similarity, 1, tables, false);
  Refined refined;
  refined.T_to_from = fine_similarity.best_similarity;
  refined.full = compareAt(inputs.all_samples, inputs.to, refined.T_to_from, tables);
  if (settings.wall_icp_iterations > 0) {
    // Walls onto walls, kept when the maps agree at least as well there; the entropy and
    // ambiguity figures are then taken around the refined transform.
    const GridTransform on_walls = refineOnWalls(refined.T_to_from, inputs, settings);
    const Agreement at_walls = compareAt(inputs.all_samples, inputs.to, on_walls, tables);
    if (at_walls.similarity() >= refined.full.similarity()) {
      refined.T_to_from = on_walls;
      refined.full = at_walls;
      coarse = searchTranslation(inputs.coarse_samples, inputs.to, on_walls,
                                 settings.translation_window_delta, tables, true);
    }
  }
  const long long best = coarse.at_best_similarity.similarity();
  refined.translation_ambiguity =
      best > 0 ? static_cast<double>(coarse.runner_up_similarity) / static_cast<double>(best) : 1.0;
  return refined;
}

}  // namespace

Refined finalize(const GridTransform& T_to_from, const SearchInputs& inputs,
                 const ComparisonTables& tables, const SeedMergerSettings& settings) {
  TranslationSearch coarse;
  Refined refined = settings.wall_anchor
                        ? settleOnWalls(T_to_from, inputs, tables, settings, coarse)
                        : settleBySimilarity(polishRotation(T_to_from, inputs, tables, settings),
                                             inputs, tables, settings, coarse);
  const TranslationSearch fine_entropy =
      searchTranslation(inputs.fine_samples, inputs.to, coarse.least_entropy, 1, tables);
  const TwoWayStructure structure =
      twoWayStructure(inputs.all_samples, refined.T_to_from, inputs, tables);
  refined.structure = structure.strict;
  refined.frontier_structure = structure.off_frontier;
  refined.least_entropy = fine_entropy.least_entropy;
  refined.entropy_gap_cells = (refined.T_to_from.t_cells - refined.least_entropy.t_cells).norm();
  return refined;
}

}  // namespace mrslam::fusion::seed
