#pragma once
// Where a robot's map lies in the team's reference frame.

#include <optional>
#include <string>

#include "mrslam/common/se2.hpp"

namespace mrslam::fusion {

/// Where one robot's map origin lies in the reference frame, if known.
struct Placement {
  std::string robot_id;
  bool placed = false;
  SE2 T_reference_robot;
  std::optional<double> verification;  ///< V of the merge that placed it (none when configured)
  std::string source;                  ///< "reference", "config", or why it is not placed
  /// The methods of the estimates on its path from the reference ("seed", "rendezvous", ...;
  /// several joined by "+"), empty when it was not placed through estimates.
  std::string methods;
  /// Its pose is the least-squares one over redundant verified pairs (loops), not one path's.
  bool least_squares = false;
};

}  // namespace mrslam::fusion
