#include "mrslam/fusion/pose_graph.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <set>

namespace mrslam::fusion {

namespace {

constexpr double kJacobianStep = 1e-6;  ///< central differences of the edge errors

Eigen::Matrix3d informationOf(const PoseGraphEdge& edge) {
  const double wt = 1.0 / (edge.sigma_translation_m * edge.sigma_translation_m);
  const double wr = 1.0 / (edge.sigma_rotation_rad * edge.sigma_rotation_rad);
  return Eigen::Vector3d(wt, wt, wr).asDiagonal();
}

SE2 perturbed(const SE2& pose, int axis, double step) {
  Eigen::Vector3d v(pose.x(), pose.y(), pose.theta());
  v[axis] += step;
  return SE2(v.x(), v.y(), v.z());
}

SE2 updated(const SE2& pose, const Eigen::Vector3d& delta) {
  return SE2(pose.x() + delta.x(), pose.y() + delta.y(), pose.theta() + delta.z());
}

/// d e / d (x, y, θ) of `pose_of_edge_end`, by central differences.
Eigen::Matrix3d numericJacobian(const PoseGraphEdge& edge, const SE2& T_from, const SE2& T_to,
                                bool of_from) {
  Eigen::Matrix3d jacobian;
  for (int axis = 0; axis < 3; ++axis) {
    const SE2 from_plus = of_from ? perturbed(T_from, axis, kJacobianStep) : T_from;
    const SE2 from_minus = of_from ? perturbed(T_from, axis, -kJacobianStep) : T_from;
    const SE2 to_plus = of_from ? T_to : perturbed(T_to, axis, kJacobianStep);
    const SE2 to_minus = of_from ? T_to : perturbed(T_to, axis, -kJacobianStep);
    Eigen::Vector3d difference =
        edgeError(edge, from_plus, to_plus) - edgeError(edge, from_minus, to_minus);
    difference.z() = wrapAngle(difference.z());
    jacobian.col(axis) = difference / (2.0 * kJacobianStep);
  }
  return jacobian;
}

double totalCost(const std::map<std::string, SE2>& poses, const std::vector<PoseGraphEdge>& edges) {
  double cost = 0.0;
  for (const PoseGraphEdge& edge : edges) {
    const Eigen::Vector3d e = edgeError(edge, poses.at(edge.from), poses.at(edge.to));
    cost += e.dot(informationOf(edge) * e);
  }
  return cost;
}

}  // namespace

Eigen::Vector3d edgeError(const PoseGraphEdge& edge, const SE2& T_reference_from,
                          const SE2& T_reference_to) {
  const SE2 error = edge.T_to_from.inverse() * (T_reference_to.inverse() * T_reference_from);
  return {error.x(), error.y(), wrapAngle(error.theta())};
}

PoseGraphResult optimisePoseGraph(const std::map<std::string, SE2>& initial,
                                  const std::vector<PoseGraphEdge>& edges,
                                  const std::vector<std::string>& fixed,
                                  const PoseGraphSettings& settings) {
  PoseGraphResult result;
  result.T_reference_robot = initial;
  std::vector<PoseGraphEdge> usable;
  for (const PoseGraphEdge& edge : edges) {
    if (initial.count(edge.from) && initial.count(edge.to) && edge.from != edge.to) {
      usable.push_back(edge);
    }
  }
  // Each free robot's block of 3 unknowns.
  const std::set<std::string> fixed_set(fixed.begin(), fixed.end());
  std::map<std::string, int> block;
  for (const auto& entry : initial) {
    if (!fixed_set.count(entry.first)) {
      const int index = static_cast<int>(block.size());
      block[entry.first] = index;
    }
  }
  result.initial_cost = totalCost(result.T_reference_robot, usable);
  result.final_cost = result.initial_cost;
  if (block.empty() || usable.empty()) {
    return result;
  }
  const int unknowns = 3 * static_cast<int>(block.size());
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(unknowns, unknowns);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(unknowns);
    for (const PoseGraphEdge& edge : usable) {
      const SE2& T_from = result.T_reference_robot.at(edge.from);
      const SE2& T_to = result.T_reference_robot.at(edge.to);
      const Eigen::Vector3d e = edgeError(edge, T_from, T_to);
      const Eigen::Matrix3d omega = informationOf(edge);
      // The edge's two ends: each free one's block and its Jacobian, computed once.
      struct End {
        int block;
        Eigen::Matrix3d J;
      };
      std::vector<End> ends;
      for (const bool of_from : {true, false}) {
        const auto found = block.find(of_from ? edge.from : edge.to);
        if (found != block.end()) {
          ends.push_back({found->second, numericJacobian(edge, T_from, T_to, of_from)});
        }
      }
      for (const End& i : ends) {
        b.segment<3>(3 * i.block) += i.J.transpose() * omega * e;
        for (const End& j : ends) {
          H.block<3, 3>(3 * i.block, 3 * j.block) += i.J.transpose() * omega * j.J;
        }
      }
    }
    // A robot no edge constrains keeps its pose (a tiny prior keeps H invertible).
    H.diagonal().array() += 1e-9;
    const Eigen::VectorXd delta = H.ldlt().solve(-b);
    for (const auto& [robot, index] : block) {
      SE2& pose = result.T_reference_robot.at(robot);
      pose = updated(pose, delta.segment<3>(3 * index));
    }
    result.iterations = iteration + 1;
    if (delta.cwiseAbs().maxCoeff() < settings.step_tolerance) {
      break;
    }
  }
  result.final_cost = totalCost(result.T_reference_robot, usable);
  return result;
}

}  // namespace mrslam::fusion
