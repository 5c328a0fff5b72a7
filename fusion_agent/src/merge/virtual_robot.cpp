// The virtual robot's walk, scans and Monte Carlo localisation (virtual_robot.hpp).

#include "mrslam/fusion/merge/virtual_robot.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "mrslam/common/se2.hpp"
#include "mrslam/fusion/merge/hit_costs.hpp"
#include "mrslam/fusion/merge/similarity.hpp"
#include "mrslam/fusion/merge/skeleton.hpp"

namespace mrslam::fusion {

namespace {

constexpr int kOccupiedThreshold = 65;       ///< occupancy (percent) of a wall cell
constexpr double kRayStepCells = 0.5;        ///< ray marching step
constexpr std::size_t kScanPointsUsed = 60;  ///< end points of a scan used to weigh particles
constexpr double kFieldCapSigmas = 3.0;      ///< a point farther from a wall costs as if this far

std::vector<Eigen::Vector2i> skeletonCells(const cv::Mat& skeleton) {
  std::vector<Eigen::Vector2i> cells;
  for (int y = 0; y < skeleton.rows; ++y) {
    for (int x = 0; x < skeleton.cols; ++x) {
      if (skeleton.at<std::uint8_t>(y, x) != 0) {
        cells.emplace_back(x, y);
      }
    }
  }
  return cells;
}

/// The next unvisited skeleton neighbour of `cell`, preferring the one straightest ahead.
bool nextOnSkeleton(const cv::Mat& skeleton, const cv::Mat& visited, const Eigen::Vector2i& cell,
                    const Eigen::Vector2d& direction, Eigen::Vector2i& next) {
  double best = -2.0;
  bool found = false;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const Eigen::Vector2i candidate = cell + Eigen::Vector2i(dx, dy);
      if ((dx == 0 && dy == 0) || candidate.x() < 0 || candidate.y() < 0 ||
          candidate.x() >= skeleton.cols || candidate.y() >= skeleton.rows ||
          skeleton.at<std::uint8_t>(candidate.y(), candidate.x()) == 0 ||
          visited.at<std::uint8_t>(candidate.y(), candidate.x()) != 0) {
        continue;
      }
      const double straightness = Eigen::Vector2d(dx, dy).normalized().dot(direction);
      if (straightness > best) {
        best = straightness;
        next = candidate;
        found = true;
      }
    }
  }
  return found;
}

SE2 asSe2(const CellPose& pose) {
  return SE2(pose.cell.x(), pose.cell.y(), pose.heading_rad);
}

struct Particle {
  SE2 pose;  ///< in `to`'s cells
  double log_weight = 0.0;
};

/// Systematic resampling by weight (the log weights are reset).
void resample(std::vector<Particle>& particles, std::mt19937_64& rng) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Particle& particle : particles) {
    best = std::max(best, particle.log_weight);
  }
  std::vector<double> cumulative(particles.size());
  double total = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    total += std::exp(particles[i].log_weight - best);
    cumulative[i] = total;
  }
  std::uniform_real_distribution<double> offset(0.0, total / particles.size());
  double target = offset(rng);
  std::vector<Particle> drawn;
  drawn.reserve(particles.size());
  std::size_t i = 0;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    while (i + 1 < particles.size() && cumulative[i] < target) {
      ++i;
    }
    drawn.push_back({particles[i].pose, 0.0});
    target += total / particles.size();
  }
  particles = std::move(drawn);
}

/// The `count` most populated clusters of particles (mean poses), largest first.
std::vector<SE2> clusters(const std::vector<Particle>& particles,
                          const VirtualRobotSettings& settings, int count) {
  std::map<std::tuple<long, long, long>, std::vector<const Particle*>> bins;
  for (const Particle& particle : particles) {
    const SE2& p = particle.pose;
    bins[{std::lround(p.x() / settings.cluster_radius_cells),
          std::lround(p.y() / settings.cluster_radius_cells),
          std::lround(wrapAngle(p.theta()) / settings.cluster_angle_rad)}]
        .push_back(&particle);
  }
  std::vector<std::vector<const Particle*>> ordered;
  for (auto& entry : bins) {
    ordered.push_back(std::move(entry.second));
  }
  std::sort(ordered.begin(), ordered.end(),
            [](const auto& a, const auto& b) { return a.size() > b.size(); });
  std::vector<SE2> means;
  for (int k = 0; k < count && k < static_cast<int>(ordered.size()); ++k) {
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
    double c = 0.0;
    double s = 0.0;
    for (const Particle* particle : ordered[k]) {
      position += particle->pose.translation();
      c += std::cos(particle->pose.theta());
      s += std::sin(particle->pose.theta());
    }
    position /= static_cast<double>(ordered[k].size());
    means.emplace_back(position.x(), position.y(), std::atan2(s, c));
  }
  return means;
}

}  // namespace

std::vector<CellPose> skeletonWalk(const cv::Mat& skeleton, const Eigen::Vector2i& start, int poses,
                                   int step_cells) {
  std::vector<CellPose> walk;
  cv::Mat visited = cv::Mat::zeros(skeleton.size(), CV_8U);
  Eigen::Vector2i cell = start;
  Eigen::Vector2d direction(1.0, 0.0);
  std::vector<Eigen::Vector2i> cells = {cell};
  visited.at<std::uint8_t>(cell.y(), cell.x()) = 1;
  const int needed = (poses - 1) * step_cells + 1;
  Eigen::Vector2i next = Eigen::Vector2i::Zero();
  while (static_cast<int>(cells.size()) < needed &&
         nextOnSkeleton(skeleton, visited, cell, direction, next)) {
    direction = 0.7 * direction + 0.3 * (next - cell).cast<double>().normalized();
    direction.normalize();
    cell = next;
    visited.at<std::uint8_t>(cell.y(), cell.x()) = 1;
    cells.push_back(cell);
  }
  for (std::size_t i = 0; i < cells.size(); i += static_cast<std::size_t>(step_cells)) {
    CellPose pose;
    pose.cell = cells[i].cast<double>();
    const std::size_t ahead = std::min(cells.size() - 1, i + static_cast<std::size_t>(step_cells));
    const std::size_t behind = i >= static_cast<std::size_t>(step_cells) ? i - step_cells : 0;
    const Eigen::Vector2d along = (cells[ahead] - cells[behind]).cast<double>();
    pose.heading_rad = along.norm() > 0.0 ? std::atan2(along.y(), along.x()) : 0.0;
    walk.push_back(pose);
  }
  return walk;
}

std::vector<Eigen::Vector2d> scanPointsUsed(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() <= kScanPointsUsed) {
    return points;
  }
  std::vector<Eigen::Vector2d> kept;
  const double step = static_cast<double>(points.size()) / kScanPointsUsed;
  for (std::size_t i = 0; i < kScanPointsUsed; ++i) {
    kept.push_back(points[static_cast<std::size_t>(i * step)]);
  }
  return kept;
}

std::vector<Eigen::Vector2d> virtualScan(const GridMap& map, const CellPose& pose,
                                         const VirtualRobotSettings& settings) {
  std::vector<Eigen::Vector2d> points;
  const GridGeometry& g = map.geometry;
  for (int beam = 0; beam < settings.beams; ++beam) {
    const double angle = 2.0 * M_PI * beam / settings.beams;  // robot frame
    const Eigen::Vector2d ray(std::cos(pose.heading_rad + angle),
                              std::sin(pose.heading_rad + angle));
    for (double r = kRayStepCells; r <= settings.max_range_cells; r += kRayStepCells) {
      const Eigen::Vector2d p = pose.cell + r * ray;
      const int x = roundToInt(p.x());
      const int y = roundToInt(p.y());
      if (!g.contains(x, y) || map.at(x, y) == GridMap::kUnknown) {
        break;
      }
      if (map.at(x, y) >= kOccupiedThreshold) {
        points.emplace_back(r * std::cos(angle), r * std::sin(angle));
        break;
      }
    }
  }
  return points;
}

std::vector<GridTransform> VirtualRobotMerger::hypotheses(const GridMap& from,
                                                          const GridMap& to) const {
  const SimilaritySettings similarity;
  const cv::Mat skeleton_from = freeSpaceSkeleton(from, similarity);
  const std::vector<Eigen::Vector2i> starts = skeletonCells(skeleton_from);
  const std::vector<Eigen::Vector2i> places_to = skeletonCells(freeSpaceSkeleton(to, similarity));
  std::vector<GridTransform> found;
  if (starts.empty() || places_to.empty()) {
    return found;
  }
  const HitCosts costs(wallDistance(to, kOccupiedThreshold),
                       kFieldCapSigmas * settings_.hit_sigma_cells, settings_.hit_sigma_cells);
  std::mt19937_64 rng(settings_.seed);
  std::uniform_int_distribution<std::size_t> pick_start(0, starts.size() - 1);
  std::uniform_int_distribution<std::size_t> pick_place(0, places_to.size() - 1);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  std::uniform_real_distribution<double> heading(-M_PI, M_PI);
  std::normal_distribution<double> step_noise(0.0, settings_.motion_sigma_cells);
  std::normal_distribution<double> turn_noise(0.0, settings_.motion_sigma_rad);
  for (int walk_index = 0; walk_index < settings_.walks; ++walk_index) {
    const std::vector<CellPose> walk = skeletonWalk(
        skeleton_from, starts[pick_start(rng)], settings_.path_poses, settings_.path_step_cells);
    if (walk.size() < 3) {
      continue;
    }
    std::vector<Particle> particles(static_cast<std::size_t>(settings_.particles));
    for (Particle& particle : particles) {
      const Eigen::Vector2i place = places_to[pick_place(rng)];
      particle.pose = SE2(place.x() + jitter(rng), place.y() + jitter(rng), heading(rng));
    }
    for (std::size_t k = 0; k < walk.size(); ++k) {
      if (k > 0) {
        const SE2 step = asSe2(walk[k - 1]).inverse() * asSe2(walk[k]);
        for (Particle& particle : particles) {
          particle.pose =
              particle.pose * SE2(step.x() + step_noise(rng), step.y() + step_noise(rng),
                                  step.theta() + turn_noise(rng));
        }
      }
      const std::vector<Eigen::Vector2d> scan =
          scanPointsUsed(virtualScan(from, walk[k], settings_));
      for (Particle& particle : particles) {
        particle.log_weight += costs.scanLogLikelihood(scan, particle.pose);
      }
      resample(particles, rng);
    }
    // T_to_from = T_to_virtual · T_from_virtual⁻¹, in cells.
    const SE2 T_from_virtual = asSe2(walk.back());
    for (const SE2& T_to_virtual : clusters(particles, settings_, settings_.hypotheses_per_walk)) {
      const SE2 T = T_to_virtual * T_from_virtual.inverse();
      GridTransform transform;
      transform.theta_rad = T.theta();
      transform.t_cells = T.translation();
      found.push_back(transform);
    }
  }
  return found;
}

}  // namespace mrslam::fusion
