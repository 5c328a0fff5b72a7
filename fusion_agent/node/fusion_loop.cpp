#include "fusion_loop.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <thread>

namespace mrslam::fusion {

namespace {

constexpr double kFlushTimeoutS = 5.0;  // at the end: readers get this long to take the last map
constexpr std::size_t kMaxHeldRendezvous = 64;  // the oldest rendezvous beyond are dropped
// Once every final map is in, the sightings they count (another topic, with no order between
// the two) get this long to arrive before the agent finishes without them.
constexpr double kFinalSightingsWaitS = 5.0;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

FusionLoop::FusionLoop(const FusionConfig& config)
    : config_(config),
      viewer_model_(config.viewer.enabled ? std::make_unique<ViewerModel>() : nullptr),
      node_(config, store_, viewer_model_.get()),
      rendezvous_(config.rendezvous, config.merge.material_change, kMaxHeldRendezvous) {
  if (viewer_model_) {
    viewer_ = std::make_unique<LiveViewer>(config.viewer, *viewer_model_);
  }
  for (const auto& [robot_id, T_reference_robot] : config.fixed_transforms) {
    graph_.addConfigured(robot_id, config.reference_robot, T_reference_robot);
  }
  if (config.make_merger) {
    scheduler_ = std::make_unique<MergeScheduler>(config.merge, config.make_merger, graph_);
    scheduler_->start();
  }
}

bool FusionLoop::allExpectedFinal() const {
  for (const std::string& robot_id : config_.expected_robots) {
    if (!store_.isFinal(robot_id)) {
      return false;
    }
  }
  return true;
}

std::string FusionLoop::missingRobots() const {
  std::string missing;
  for (const std::string& robot_id : config_.expected_robots) {
    if (!store_.isFinal(robot_id)) {
      missing += (missing.empty() ? "" : ", ") + robot_id +
                 (store_.has(robot_id) ? " (no final map)" : " (no map)");
    }
  }
  return missing;
}

std::string FusionLoop::sightingsOutstanding() const {
  std::string outstanding;
  for (const std::string& robot_id : config_.expected_robots) {
    const std::uint64_t published = store_.sightingsPublished(robot_id);
    const std::uint64_t received = node_.sightingsReceived(robot_id);
    if (received < published) {
      outstanding += (outstanding.empty() ? "" : ", ") + robot_id + " (" +
                     std::to_string(received) + " of " + std::to_string(published) + ")";
    }
  }
  return outstanding;
}

bool FusionLoop::finalSightingsHeld() {
  const std::string outstanding = sightingsOutstanding();
  if (outstanding.empty()) {
    return true;
  }
  if (!final_maps_since_) {
    final_maps_since_ = Clock::now();
    spdlog::info(
        "fusion: every final map is in; waiting up to {} s for the sightings they count: "
        "{} (received of written)",
        kFinalSightingsWaitS, outstanding);
    return false;
  }
  if (secondsSince(*final_maps_since_) < kFinalSightingsWaitS) {
    return false;
  }
  spdlog::warn(
      "fusion: sightings the robots wrote are still missing after {} s: {} (received of "
      "written); finishing without them",
      kFinalSightingsWaitS, outstanding);
  return true;
}

void FusionLoop::publishAttempts() {
  if (!scheduler_) {
    return;
  }
  for (const MergeAttempt& attempt : scheduler_->takeAttempts()) {
    node_.publishAttempt(attempt);
    if (viewer_model_) {
      viewer_model_->addAttempt(attempt);
    }
    changed_ = changed_ || attempt.result.accepted;
  }
}

void FusionLoop::publish() {
  maps_ = store_.snapshot();
  const std::string reference = chooseReference(maps_, config_);
  std::vector<std::string> robot_ids;
  for (const RobotMap& map : maps_) {
    robot_ids.push_back(map.robot_id);
  }
  result_ = buildGlobalMap(maps_, reference, graph_.place(reference, robot_ids), config_.composer);
  reportDroppedEdges();
  node_.publish(result_, ++sequence_);
  if (viewer_model_) {
    viewer_model_->setGlobalMap(result_, maps_);
  }
  written_ = false;
}

void FusionLoop::reportDroppedEdges() {
  for (const DroppedEdge& drop : graph_.dropped()) {
    const std::string key = drop.estimate.from + ">" + drop.estimate.to;
    if (reported_drops_.insert(key).second) {
      spdlog::warn(
          "fusion: the {} merge {} -> {} (V {:.3f}) breaks a loop by {:.2f} m and {:.1f} deg; it "
          "is not used",
          drop.estimate.method, drop.estimate.from, drop.estimate.to, drop.estimate.verification,
          drop.translation_error_m, drop.rotation_error_rad * 180.0 / M_PI);
    }
  }
}

void FusionLoop::writeFiles() {
  writeFusionOutputs(result_, maps_, config_.output_folder, config_.write_robot_maps);
  written_ = true;
}

void FusionLoop::finalMerges() {
  if (!scheduler_) {
    return;
  }
  scheduler_->offer(store_.snapshot());
  if (!scheduler_->waitIdle(config_.final_merge_timeout_s)) {
    spdlog::warn("fusion: the last merges did not finish within {} s",
                 config_.final_merge_timeout_s);
  }
  publishAttempts();
}

namespace {

MergeAttempt rendezvousAttempt(const RendezvousOutcome& outcome) {
  MergeAttempt attempt;
  attempt.from = outcome.hypothesis.from;
  attempt.to = outcome.hypothesis.to;
  attempt.result.accepted = outcome.check.accepted;
  attempt.result.verification = outcome.check.verification;
  attempt.result.method = "rendezvous";
  attempt.result.reason = outcome.check.reason;
  attempt.result.trials = 1;
  attempt.T_to_from = outcome.check.T_to_from;
  attempt.time_ms = outcome.time_ms;
  return attempt;
}

}  // namespace

void FusionLoop::checkRendezvous() {
  const std::vector<RendezvousHypothesis> hypotheses = node_.rendezvous().takeHypotheses();
  for (const RendezvousHypothesis& hypothesis : hypotheses) {
    spdlog::info("fusion: rendezvous of {} and {}: a hypothesis to check against the maps",
                 hypothesis.from, hypothesis.to);
  }
  rendezvous_.add(hypotheses);
  const std::uint64_t version = store_.version();
  if (!rendezvous_.needsCheck(version)) {
    return;  // a snapshot copies every robot's map: taken only when a check may be due
  }
  for (const RendezvousOutcome& outcome : rendezvous_.checkDue(store_.snapshot(), version)) {
    useRendezvousOutcome(outcome);
  }
}

void FusionLoop::useRendezvousOutcome(const RendezvousOutcome& outcome) {
  const MergeAttempt attempt = rendezvousAttempt(outcome);
  node_.publishAttempt(attempt);
  if (viewer_model_) {
    viewer_model_->addAttempt(attempt);
  }
  const char* which_maps = outcome.on_final_maps ? "final" : "latest";
  if (outcome.check.accepted) {
    PairwiseEstimate estimate;
    estimate.from = attempt.from;
    estimate.to = attempt.to;
    estimate.T_to_from = outcome.check.T_to_from;
    estimate.verification = outcome.check.verification;
    estimate.method = "rendezvous";
    estimate.from_final_maps = outcome.on_final_maps;
    changed_ = graph_.addVerified(estimate) || changed_;
    spdlog::info("fusion: rendezvous {} -> {} verified by the maps ({}; V {:.3f})", attempt.from,
                 attempt.to, which_maps, outcome.check.verification);
  } else if (outcome.was_verified) {
    const bool withdrawn = graph_.withdraw(attempt.from, attempt.to, outcome.previous_T_to_from);
    changed_ = withdrawn || changed_;
    spdlog::warn(
        "fusion: rendezvous {} -> {}, verified before, is refused by the grown maps ({}): "
        "{}{}",
        attempt.from, attempt.to, which_maps, outcome.check.reason,
        withdrawn ? "; its placement is withdrawn" : "");
  } else if (!outcome.short_of_overlap) {
    spdlog::warn("fusion: {} -> {} ({} maps): {}{}", attempt.from, attempt.to, which_maps,
                 outcome.check.reason,
                 outcome.on_final_maps ? "" : "; checked again on grown and final maps");
  }
}

constexpr std::chrono::milliseconds kLoopPeriod{50};

int FusionLoop::run(const std::atomic<bool>& shutdown) {
  const Clock::time_point start = Clock::now();
  Clock::time_point last_publish = start;
  Clock::time_point last_write = start;
  spdlog::info("fusion: {} listening on domain {}", config_.fusion_id, config_.dds.domain_id);
  while (true) {
    // A new map wakes the loop at once, a change waiting for its publish period when that is
    // due; otherwise the loop looks around every 50 ms.
    std::chrono::duration<double> wait = kLoopPeriod;
    if (changed_) {
      wait = std::min(wait, std::chrono::duration<double>(std::max(
                                0.0, config_.publish_period_s - secondsSince(last_publish))));
    }
    store_.waitForChange(offered_version_, std::chrono::ceil<std::chrono::milliseconds>(wait));
    const bool complete = config_.exit_when_final && allExpectedFinal() && finalSightingsHeld();
    const bool timed_out =
        config_.max_runtime_s > 0.0 && secondsSince(start) > config_.max_runtime_s;
    const bool stopping = complete || timed_out || shutdown.load();
    if (store_.version() != offered_version_) {
      offered_version_ = store_.version();
      changed_ = true;
      if (scheduler_ && !stopping) {
        scheduler_->offer(store_.snapshot());
      }
    }
    publishAttempts();
    checkRendezvous();
    if (stopping) {
      finalMerges();
      publish();
      writeFiles();
      node_.flush(kFlushTimeoutS);
      if (timed_out && config_.exit_when_final && !complete) {
        spdlog::error("fusion: gave up after {} s; missing: {}", config_.max_runtime_s,
                      missingRobots());
        return 2;
      }
      break;
    }
    if (changed_ && secondsSince(last_publish) >= config_.publish_period_s) {
      changed_ = false;
      publish();
      last_publish = Clock::now();
    }
    if (config_.write_period_s > 0.0 && !written_ &&
        secondsSince(last_write) >= config_.write_period_s) {
      writeFiles();
      last_write = Clock::now();
    }
  }
  std::string refusals;
  for (const auto& [kind, count] : node_.rejected().counts()) {
    refusals += (refusals.empty() ? ": " : ", ") + kind + " " + std::to_string(count);
  }
  spdlog::info("fusion: wrote {} ({} maps refused{})", config_.output_folder,
               node_.rejected().total(), refusals);
  return 0;
}

}  // namespace mrslam::fusion
