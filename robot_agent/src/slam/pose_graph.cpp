#include "mrslam/robot/slam/pose_graph.hpp"

#include <ceres/ceres.h>

#include <array>
#include <cmath>
#include <stdexcept>

namespace mrslam::robot::slam {

namespace {

template <typename T>
T wrapped(const T& angle) {
  const T two_pi(2.0 * M_PI);
  return angle - two_pi * ceres::floor((angle + T(M_PI)) / two_pi);
}

// The relative pose error of b seen from a against the measured T_a_b, over σ.
struct RelativePoseCost {
  Eigen::Vector3d measured;  // x, y, θ of T_a_b
  double translation_weight;
  double rotation_weight;
  template <typename T>
  bool operator()(const T* const a, const T* const b, T* residuals) const {
    const T c = ceres::cos(a[2]);
    const T s = ceres::sin(a[2]);
    const T dx = b[0] - a[0];
    const T dy = b[1] - a[1];
    residuals[0] = translation_weight * (c * dx + s * dy - measured.x());
    residuals[1] = translation_weight * (-s * dx + c * dy - measured.y());
    residuals[2] = rotation_weight * wrapped(b[2] - a[2] - measured.z());
    return true;
  }
  static ceres::CostFunction* create(const SE2& T_a_b, double sigma_m, double sigma_rad) {
    return new ceres::AutoDiffCostFunction<RelativePoseCost, 3, 3, 3>(new RelativePoseCost{
        Eigen::Vector3d(T_a_b.x(), T_a_b.y(), T_a_b.theta()), 1.0 / sigma_m, 1.0 / sigma_rad});
  }
};

std::array<double, 3> toArray(const SE2& pose) {
  return {pose.x(), pose.y(), pose.theta()};
}
SE2 fromArray(const std::array<double, 3>& pose) {
  return SE2(pose[0], pose[1], pose[2]);
}

}  // namespace

PoseGraph::PoseGraph(const PoseGraphSettings& settings) : settings_(settings) {
  for (const double sigma :
       {settings_.local_sigma_m, settings_.local_sigma_rad, settings_.intra_sigma_m,
        settings_.intra_sigma_rad, settings_.closure_sigma_m, settings_.closure_sigma_rad}) {
    if (!(sigma > 0.0)) {
      throw std::invalid_argument("pose graph: every σ must be > 0");
    }
  }
  if (!(settings_.closure_huber_scale > 0.0) || settings_.max_iterations < 1) {
    throw std::invalid_argument("pose graph: Huber scale and iterations must be > 0");
  }
}

int PoseGraph::addNode(const SE2& T_map_node, const SE2& T_local_node) {
  nodes_.push_back({T_map_node, T_local_node});
  return static_cast<int>(nodes_.size()) - 1;
}

int PoseGraph::addSubmap(const SE2& T_map_submap) {
  submaps_.push_back(T_map_submap);
  return static_cast<int>(submaps_.size()) - 1;
}

void PoseGraph::addConstraint(const PoseGraphConstraint& constraint) {
  if (constraint.node < 0 || constraint.node >= nodeCount() || constraint.submap < 0 ||
      constraint.submap >= submapCount()) {
    throw std::out_of_range("pose graph: constraint on an unknown node or submap");
  }
  constraints_.push_back(constraint);
}

std::pair<double, double> PoseGraph::errorOf(const PoseGraphConstraint& constraint) const {
  const SE2 T_submap_node = submapPose(constraint.submap).inverse() * nodePose(constraint.node);
  const SE2 error = constraint.T_submap_node.inverse() * T_submap_node;
  return {error.translation().norm(), std::abs(error.theta())};
}

void PoseGraph::solve() {
  if (submaps_.empty() || nodes_.empty()) {
    return;
  }
  std::vector<std::array<double, 3>> nodes;
  std::vector<std::array<double, 3>> submaps;
  nodes.reserve(nodes_.size());
  submaps.reserve(submaps_.size());
  for (const Node& node : nodes_) {
    nodes.push_back(toArray(node.T_map));
  }
  for (const SE2& submap : submaps_) {
    submaps.push_back(toArray(submap));
  }
  ceres::Problem problem;
  for (const PoseGraphConstraint& c : constraints_) {
    if (!c.active) {
      continue;
    }
    const bool closure = c.kind == PoseGraphConstraint::Kind::kLoopClosure;
    ceres::LossFunction* loss =
        closure ? new ceres::HuberLoss(settings_.closure_huber_scale) : nullptr;
    problem.AddResidualBlock(
        RelativePoseCost::create(c.T_submap_node,
                                 closure ? settings_.closure_sigma_m : settings_.intra_sigma_m,
                                 closure ? settings_.closure_sigma_rad : settings_.intra_sigma_rad),
        loss, submaps[static_cast<std::size_t>(c.submap)].data(),
        nodes[static_cast<std::size_t>(c.node)].data());
  }
  for (std::size_t i = 1; i < nodes_.size(); ++i) {
    const SE2 T_previous_node = nodes_[i - 1].T_local.inverse() * nodes_[i].T_local;
    problem.AddResidualBlock(RelativePoseCost::create(T_previous_node, settings_.local_sigma_m,
                                                      settings_.local_sigma_rad),
                             nullptr, nodes[i - 1].data(), nodes[i].data());
  }
  problem.SetParameterBlockConstant(submaps.front().data());
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = settings_.max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  ++counters_.solves;
  if (!summary.IsSolutionUsable()) {
    return;  // the poses stay as they were
  }
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    nodes_[i].T_map = fromArray(nodes[i]);
  }
  for (std::size_t i = 0; i < submaps_.size(); ++i) {
    submaps_[i] = fromArray(submaps[i]);
  }
}

bool PoseGraph::refuseClosuresOffTheSolution() {
  bool refused = false;
  for (PoseGraphConstraint& c : constraints_) {
    if (!c.active || c.kind != PoseGraphConstraint::Kind::kLoopClosure) {
      continue;
    }
    const auto [translation, rotation] = errorOf(c);
    if (translation > settings_.max_closure_error_m || rotation > settings_.max_closure_error_rad) {
      c.active = false;
      ++counters_.closures_refused;
      refused = true;
    }
  }
  return refused;
}

void PoseGraph::optimise() {
  solve();
  if (refuseClosuresOffTheSolution()) {
    solve();
  }
}

}  // namespace mrslam::robot::slam
