#include "mrslam/fusion/merge_scheduler.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

namespace mrslam::fusion {

std::size_t knownCellCount(const GridMap& map) {
  std::size_t known = 0;
  for (const std::int8_t value : map.cells) {
    known += value != GridMap::kUnknown ? 1 : 0;
  }
  return known;
}

bool grewMaterially(std::size_t now_known, std::size_t then_known, double material_change) {
  return static_cast<double>(now_known) > static_cast<double>(then_known) * (1.0 + material_change);
}

MergeScheduler::MergeScheduler(const MergeSchedulerSettings& settings, MergerFactory factory,
                               TeamGraph& graph)
    : settings_(settings), factory_(std::move(factory)), graph_(graph) {}

MergeScheduler::~MergeScheduler() {
  stop();
}

void MergeScheduler::start() {
  thread_ = std::thread([this] { loop(); });
}

void MergeScheduler::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) {
    thread_.join();
  }
}

void MergeScheduler::offer(std::vector<RobotMap> maps) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    offered_ = std::move(maps);
    ++offered_version_;
  }
  wake_.notify_all();
}

bool MergeScheduler::waitIdle(double timeout_s) {
  std::unique_lock<std::mutex> lock(mutex_);
  return idle_.wait_for(lock, std::chrono::duration<double>(timeout_s),
                        [this] { return done_version_ == offered_version_; });
}

std::vector<MergeAttempt> MergeScheduler::takeAttempts() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<MergeAttempt> taken;
  taken.swap(attempts_);
  return taken;
}

void MergeScheduler::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stopping_) {
    wake_.wait(lock, [this] { return stopping_ || done_version_ != offered_version_; });
    if (stopping_) {
      break;
    }
    const std::uint64_t version = offered_version_;
    const std::vector<RobotMap> maps = offered_;
    lock.unlock();
    std::vector<MergeAttempt> attempts = runDue(maps, Clock::now());
    lock.lock();
    attempts_.insert(attempts_.end(), attempts.begin(), attempts.end());
    done_version_ = version;
    idle_.notify_all();
  }
}

bool MergeScheduler::isDue(const PairState& state, const PairMaps& maps, bool placed,
                           Clock::time_point now) const {
  if (!state.attempted) {
    return true;
  }
  if (placed && !settings_.refine_accepted) {
    return false;
  }
  if (maps.both_final && !state.final_merged) {
    return true;  // the last maps of both robots: merged once more, whatever the interval
  }
  if (now - state.last_attempt < std::chrono::duration<double>(settings_.min_interval_s)) {
    return false;
  }
  return grewMaterially(maps.known_from, state.known_from, settings_.material_change) ||
         grewMaterially(maps.known_to, state.known_to, settings_.material_change);
}

namespace {

/// Calls `work(k)` for k = 0 .. count - 1 on up to `threads` threads (the caller's one of them).
template <typename Work>
void runOnThreads(std::size_t count, int threads, const Work& work) {
  std::atomic<std::size_t> next{0};
  const auto drain = [&] {
    for (std::size_t k = next++; k < count; k = next++) {
      work(k);
    }
  };
  std::vector<std::thread> helpers;
  const std::size_t helper_count = std::min(count, static_cast<std::size_t>(std::max(1, threads)));
  for (std::size_t i = 1; i < helper_count; ++i) {
    helpers.emplace_back(drain);
  }
  drain();
  for (std::thread& helper : helpers) {
    helper.join();
  }
}

}  // namespace

std::vector<MergeAttempt> MergeScheduler::runDue(const std::vector<RobotMap>& maps,
                                                 Clock::time_point now) {
  std::vector<std::size_t> known(maps.size());
  for (std::size_t i = 0; i < maps.size(); ++i) {
    known[i] = knownCellCount(maps[i].map);
  }
  std::vector<std::pair<std::size_t, std::size_t>> due;         // (from, to)
  std::vector<std::pair<std::size_t, std::size_t>> due_placed;  // refinements, merged after
  for (std::size_t to = 0; to < maps.size(); ++to) {
    for (std::size_t from = to + 1; from < maps.size(); ++from) {
      if (known[from] == 0 || known[to] == 0) {
        continue;
      }
      PairState& state = pairs_[{maps[from].robot_id, maps[to].robot_id}];
      const bool placed = graph_.estimate(maps[from].robot_id, maps[to].robot_id).has_value();
      const PairMaps pair{known[from], known[to], maps[from].is_final && maps[to].is_final};
      if (!isDue(state, pair, placed, now)) {
        continue;
      }
      state.last_attempt = now;
      state.known_from = pair.known_from;
      state.known_to = pair.known_to;
      state.attempted = true;
      state.final_merged = pair.both_final;
      (placed ? due_placed : due).emplace_back(from, to);
    }
  }
  // Pairs without a verified transform first: with more due pairs than threads, a robot not yet
  // placed waits for no refinement of pairs already placed.
  due.insert(due.end(), due_placed.begin(), due_placed.end());
  // The mergers are made here, one at a time (their settings are read from the config), and
  // each merges on one thread.
  std::vector<std::unique_ptr<MapMerger>> mergers;
  for (std::size_t k = 0; k < due.size(); ++k) {
    mergers.push_back(factory_());
  }
  std::vector<MergeAttempt> attempts(due.size());
  runOnThreads(due.size(), settings_.threads, [&](std::size_t k) {
    const RobotMap& from = maps[due[k].first];
    const RobotMap& to = maps[due[k].second];
    attempts[k] = mergePair(*mergers[k], from, to, pairs_.at({from.robot_id, to.robot_id}));
  });
  return attempts;
}

namespace {

bool agree(const SE2& a, const SE2& b, const MergeSchedulerSettings& settings) {
  return (a.translation() - b.translation()).norm() <= settings.confirm_distance_m &&
         std::abs(wrapAngle(a.theta() - b.theta())) <= settings.confirm_angle_rad;
}

}  // namespace

MergeScheduler::Confirmation MergeScheduler::confirm(const PairwiseEstimate& estimate,
                                                     PairState& state) const {
  if (estimate.from_final_maps || settings_.confirmations <= 1) {
    state.pending.reset();
    return {true, std::nullopt, ""};  // the final maps hold every scan: their merge counts alone
  }
  const std::optional<PairwiseEstimate> in_use = graph_.estimate(estimate.from, estimate.to);
  if (in_use && agree(in_use->T_to_from, estimate.T_to_from, settings_)) {
    state.pending.reset();
    return {true, std::nullopt, ""};  // it refines the estimate in use
  }
  const bool agrees_with_pending =
      state.pending && agree(state.pending->T_to_from, estimate.T_to_from, settings_);
  state.agreeing = agrees_with_pending ? state.agreeing + 1 : 1;
  if (state.agreeing >= settings_.confirmations) {
    state.pending.reset();
    // Merges of grown maps that agree with each other and not with the estimate in use outweigh
    // it, whatever its V: V is not comparable across overlaps of different sizes.
    const bool replaces = in_use && !in_use->configured;
    return {true, replaces ? in_use : std::nullopt,
            replaces ? "; confirmed by the merges of earlier maps, it replaces the estimate in use"
                     : "; confirmed by the merges of earlier maps"};
  }
  state.pending = estimate;
  return {false, std::nullopt,
          "; not used until " + std::to_string(settings_.confirmations - state.agreeing) +
              " more merge(s) of grown maps agree" +
              (in_use ? " (it disagrees with the estimate in use)" : "")};
}

MergeAttempt MergeScheduler::mergePair(MapMerger& merger, const RobotMap& from, const RobotMap& to,
                                       PairState& state) {
  MergeAttempt attempt;
  attempt.from = from.robot_id;
  attempt.to = to.robot_id;
  const auto start = Clock::now();
  if (from.map.geometry.resolution_m != to.map.geometry.resolution_m) {
    attempt.result.reason = "the maps' resolutions differ";
  } else {
    try {
      attempt.result = merger.merge(from.map, to.map);
    } catch (const std::exception& error) {  // on a merge thread: reported, not fatal
      attempt.result = MergeResult{};
      attempt.result.reason = std::string("the merge failed: ") + error.what();
    }
  }
  attempt.time_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  if (attempt.result.accepted) {
    attempt.T_to_from =
        gridTransformToMetric(attempt.result.T_to_from, from.map.geometry, to.map.geometry);
    PairwiseEstimate estimate;
    estimate.from = from.robot_id;
    estimate.to = to.robot_id;
    estimate.T_to_from = attempt.T_to_from;
    estimate.verification = attempt.result.verification;
    estimate.entropy = attempt.result.entropy;
    estimate.method = attempt.result.method;
    estimate.from_final_maps = from.is_final && to.is_final;
    const Confirmation confirmation = confirm(estimate, state);
    std::string note = confirmation.note;
    const bool use = confirmation.use;
    if (!use) {
      attempt.result.reason = "held back" + note;  // accepted, but not placing a robot yet
    }
    const bool stored =
        use &&
        (confirmation.replaced ? graph_.replaceVerified(estimate, confirmation.replaced->T_to_from)
                               : graph_.addVerified(estimate));
    if (use && !stored) {
      note += "; a better estimate is kept";
    }
    spdlog::info(
        "fusion: {} → {} merged by {} (V {:.3f}, {:.0f} ms): {}'s origin at ({:.3f} m, "
        "{:.3f} m, {:.2f} deg) in {}'s frame{}",
        from.robot_id, to.robot_id, estimate.method, estimate.verification, attempt.time_ms,
        from.robot_id, estimate.T_to_from.x(), estimate.T_to_from.y(),
        estimate.T_to_from.theta() * 180.0 / M_PI, to.robot_id, note);
  } else {
    spdlog::info("fusion: {} → {} not merged: {}", from.robot_id, to.robot_id,
                 attempt.result.reason);
  }
  return attempt;
}

}  // namespace mrslam::fusion
