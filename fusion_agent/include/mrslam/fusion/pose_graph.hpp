#pragma once
// Least-squares placement of robots' map frames from redundant pairwise transforms.
//
// Each robot's map origin has a pose T_reference_robot (x, y, θ); each edge measures
// Z = T_to_from, the pose of `from`'s origin in `to`'s frame, with a standard deviation in
// translation and in rotation. The error of an edge is the measured transform against the one
// the poses imply, in the measurement's frame:
//   e = Z⁻¹ · (T_reference_to⁻¹ · T_reference_from)  as (x, y, θ), θ wrapped,
// and Gauss–Newton minimises Σ eᵀ Ω e with Ω = diag(1/σ_t², 1/σ_t², 1/σ_θ²), holding the fixed
// robots (the reference, robots placed by configuration) where they are.

#include <map>
#include <string>
#include <vector>

#include "mrslam/common/se2.hpp"

namespace mrslam::fusion {

struct PoseGraphEdge {
  std::string from;
  std::string to;
  SE2 T_to_from;
  double sigma_translation_m = 0.05;
  double sigma_rotation_rad = 0.01;
};

struct PoseGraphSettings {
  int max_iterations = 20;
  double step_tolerance = 1e-9;  ///< stop when the largest pose change is below this
};

struct PoseGraphResult {
  std::map<std::string, SE2> T_reference_robot;  ///< every robot of the initial guess
  double initial_cost = 0.0;                     ///< Σ eᵀ Ω e at the initial guess
  double final_cost = 0.0;                       ///< ... at the solution
  int iterations = 0;
};

/// Minimises the edges' weighted squared errors over the poses of the robots not in `fixed`,
/// from `initial` (which must hold every robot an edge names; edges naming others are ignored).
PoseGraphResult optimisePoseGraph(const std::map<std::string, SE2>& initial,
                                  const std::vector<PoseGraphEdge>& edges,
                                  const std::vector<std::string>& fixed,
                                  const PoseGraphSettings& settings = {});

/// The error vector (x, y, θ) of one edge at the given poses.
Eigen::Vector3d edgeError(const PoseGraphEdge& edge, const SE2& T_reference_from,
                          const SE2& T_reference_to);

}  // namespace mrslam::fusion
