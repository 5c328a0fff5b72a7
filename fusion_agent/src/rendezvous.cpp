#include "mrslam/fusion/rendezvous.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mrslam::fusion {

SE2 relativePoseFromSightings(const Sighting& a_sees_b, const Sighting& b_sees_a) {
  // Both measured the same distance: take their mean.
  const double range = 0.5 * (a_sees_b.range_m + b_sees_a.range_m);
  const double bearing = a_sees_b.bearing_rad;
  return SE2(range * std::cos(bearing), range * std::sin(bearing),
             bearing + M_PI - b_sees_a.bearing_rad);
}

SE2 rendezvousTransform(const Sighting& a_sees_b, const Sighting& b_sees_a) {
  return a_sees_b.T_map_observer * relativePoseFromSightings(a_sees_b, b_sees_a) *
         b_sees_a.T_map_observer.inverse();
}

bool RendezvousBook::add(const Sighting& sighting) {
  if (sighting.observer == sighting.observed || sighting.observer.empty() ||
      sighting.observed.empty()) {
    return false;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  open_.push_back(sighting);
  added_since_taken_ = true;
  if (open_.size() > settings_.max_kept) {
    open_.erase(open_.begin());
  }
  return true;
}

std::size_t RendezvousBook::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return open_.size();
}

std::vector<RendezvousHypothesis> RendezvousBook::takeHypotheses() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!added_since_taken_) {
    return {};  // the open sightings were paired as far as they go at the last call
  }
  added_since_taken_ = false;
  // Every mutual pair within the time gap, closest in time first.
  struct Candidate {
    double gap_s;
    std::size_t a;
    std::size_t b;
  };
  std::vector<Candidate> candidates;
  for (std::size_t a = 0; a < open_.size(); ++a) {
    for (std::size_t b = a + 1; b < open_.size(); ++b) {
      const bool mutual =
          open_[a].observer == open_[b].observed && open_[a].observed == open_[b].observer;
      const double gap = std::abs(secondsBetween(open_[a].stamp, open_[b].stamp));
      if (mutual && gap <= settings_.max_time_gap_s) {
        candidates.push_back({gap, a, b});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& x, const Candidate& y) { return x.gap_s < y.gap_s; });
  std::vector<bool> used(open_.size(), false);
  std::vector<RendezvousHypothesis> hypotheses;
  for (const Candidate& candidate : candidates) {
    if (used[candidate.a] || used[candidate.b]) {
      continue;
    }
    used[candidate.a] = used[candidate.b] = true;
    // T_to_from with to = a, the robot whose id sorts first, and from = b: a pair's check fits
    // the same map into the same other whichever robot's sighting arrived first (the fit is not
    // symmetric, so the order of arrival would otherwise change the answer).
    const bool a_first = open_[candidate.a].observer < open_[candidate.b].observer;
    const Sighting& a_sees_b = a_first ? open_[candidate.a] : open_[candidate.b];
    const Sighting& b_sees_a = a_first ? open_[candidate.b] : open_[candidate.a];
    hypotheses.push_back({a_sees_b.observed, a_sees_b.observer,
                          rendezvousTransform(a_sees_b, b_sees_a),
                          std::max(a_sees_b.stamp, b_sees_a.stamp)});
  }
  std::vector<Sighting> still_open;
  for (std::size_t i = 0; i < open_.size(); ++i) {
    if (!used[i]) {
      still_open.push_back(open_[i]);
    }
  }
  open_ = std::move(still_open);
  return hypotheses;
}

namespace {

std::string describeRefusal(const char* what, double value, double bound) {
  std::ostringstream text;
  text << "rendezvous refused by the maps: " << what << " " << value << " (bound " << bound << ")";
  return text.str();
}

}  // namespace

RendezvousCheck checkRendezvous(const RendezvousHypothesis& hypothesis, const GridMap& from,
                                const GridMap& to, const RendezvousSettings& settings) {
  RendezvousCheck check;
  if (from.geometry.resolution_m != to.geometry.resolution_m) {
    check.reason = "rendezvous: the maps' resolutions differ";
    return check;
  }
  const GridTransform measured =
      metricToGridTransform(hypothesis.T_to_from, from.geometry, to.geometry);
  const LocalFit fit =
      fitNear(from, to, measured,
              {settings.max_refinement_m, settings.max_refinement_rad, settings.rotation_step_rad});
  check.T_to_from = gridTransformToMetric(fit.T_to_from, from.geometry, to.geometry);
  check.verification = fit.verification;
  check.structure = fit.structure;
  check.overlap_cells = fit.overlap_cells;
  if (check.overlap_cells < settings.min_overlap_cells) {
    check.reason = describeRefusal("overlap cells", static_cast<double>(check.overlap_cells),
                                   static_cast<double>(settings.min_overlap_cells));
  } else if (check.verification < settings.min_verification_v) {
    check.reason = describeRefusal("V", check.verification, settings.min_verification_v);
  } else if (check.structure < settings.min_structure_agreement) {
    check.reason =
        describeRefusal("structure agreement", check.structure, settings.min_structure_agreement);
  } else {
    check.accepted = true;
  }
  return check;
}

}  // namespace mrslam::fusion
