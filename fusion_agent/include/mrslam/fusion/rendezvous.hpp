#pragma once
// Rendezvous between robots (seed 003 §3.2). Robot a sees robot b at range d and bearing α_ab
// (in a's frame) while b sees a at bearing α_ba. Then b sits at d·(cos α_ab, sin α_ab) in a's
// frame, turned by θ_ab = α_ab + π − α_ba (the line from b to a has direction α_ab + π in a's
// frame and α_ba in b's), and with both robots' poses in their own map frames at that moment
//   T_mapA_mapB = T_mapA_a · T_a_b · T_mapB_b⁻¹.
// Such a transform is only a hypothesis: the fusion agent fits the two maps near it and checks
// the fit (overlap, V, walls on walls) before it places a robot with it.

#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/common/stamp.hpp"
#include "mrslam/fusion/merge/local_fit.hpp"

namespace mrslam::fusion {

/// One robot's sighting of another, with the observer's pose estimate then.
struct Sighting {
  std::string observer;
  std::string observed;
  Stamp stamp;
  double range_m = 0.0;
  double bearing_rad = 0.0;  ///< in the observer's frame
  SE2 T_map_observer;
};

/// T_a_b: robot b's pose in robot a's frame from the two mutual sightings.
SE2 relativePoseFromSightings(const Sighting& a_sees_b, const Sighting& b_sees_a);

/// T_mapA_mapB (the pose of b's map origin in a's map frame) from the two mutual sightings.
SE2 rendezvousTransform(const Sighting& a_sees_b, const Sighting& b_sees_a);

/// A transform between two robots' map frames from one rendezvous: T_to_from.
struct RendezvousHypothesis {
  std::string from;
  std::string to;
  SE2 T_to_from;
  Stamp stamp;
};

struct RendezvousSettings {
  double max_time_gap_s = 0.25;         ///< two sightings further apart are not one rendezvous
  std::size_t max_kept = 512;           ///< sightings kept (oldest dropped first)
  double min_verification_v = 0.9;      ///< V the maps must give the (refined) hypothesis
  std::size_t min_overlap_cells = 300;  ///< known cells the two maps must share at it
  /// Least share of walls landing on walls, both ways: a rendezvous is measured, so the maps only
  /// have to rule a wrong one out (wrong ones gave 0.02-0.44, right ones 0.53-0.70 on the demo).
  double min_structure_agreement = 0.5;
  double max_refinement_m = 0.5;                   ///< the fit searches shifts up to this far
  double max_refinement_rad = 3.0 * M_PI / 180.0;  ///< ... and turns up to this far
  double rotation_step_rad = 0.25 * M_PI / 180.0;  ///< turn step of the fit
};

/// The sightings received, paired into rendezvous (thread-safe: DDS listeners add, the fusion
/// loop takes).
class RendezvousBook {
 public:
  explicit RendezvousBook(RendezvousSettings settings = {}) : settings_(settings) {}
  /// Keeps a sighting; one of a robot by itself is refused (false).
  bool add(const Sighting& sighting);
  /// Every rendezvous not taken before: a sighting of b by a and one of a by b within
  /// max_time_gap_s (each sighting used once, the closest in time first).
  std::vector<RendezvousHypothesis> takeHypotheses();
  std::size_t size() const;

 private:
  RendezvousSettings settings_;
  mutable std::mutex mutex_;
  std::vector<Sighting> open_;      ///< not yet paired
  bool added_since_taken_ = false;  ///< pairing is needed only after a new sighting
};

/// The result of checking a hypothesis against the maps.
struct RendezvousCheck {
  bool accepted = false;
  SE2 T_to_from;              ///< refined (valid when accepted)
  double verification = 0.0;  ///< V at T_to_from
  double structure = 0.0;     ///< structure agreement at T_to_from
  std::size_t overlap_cells = 0;
  std::string reason;  ///< why it was refused
};

/// Fits the hypothesis to the maps (fitNear, local_fit.hpp) and accepts it when the overlap, V and
/// the structure agreement are large enough there. A rendezvous that was wrong finds no such fit
/// near it: it is refused, with the figure that failed.
RendezvousCheck checkRendezvous(const RendezvousHypothesis& hypothesis, const GridMap& from,
                                const GridMap& to, const RendezvousSettings& settings);

}  // namespace mrslam::fusion
