#include "mrslam/robot/relations.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace mrslam::robot {

namespace {

std::runtime_error lineError(const std::string& path, std::size_t line, const std::string& what) {
  return std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

bool isBlankOrComment(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

Relation parseRelation(const std::string& text, const std::string& path, std::size_t line) {
  std::istringstream fields(text);
  std::string t1;
  std::string t2;
  double values[6] = {};
  fields >> t1 >> t2;
  for (double& value : values) {
    fields >> value;
  }
  std::string extra;
  if (!fields || (fields >> extra)) {
    throw lineError(path, line, "not a relation (t1 t2 x y z roll pitch yaw)");
  }
  const std::optional<Stamp> from = Stamp::parseSeconds(t1);
  const std::optional<Stamp> to = Stamp::parseSeconds(t2);
  if (!from || !to) {
    throw lineError(path, line, "'" + (from ? t2 : t1) + "' is not a time stamp");
  }
  for (const double value : values) {
    if (!std::isfinite(value)) {
      throw lineError(path, line, "a relation value is not finite");
    }
  }
  return Relation{*from, *to, SE2(values[0], values[1], values[5])};
}

// The trajectory pose stamped nearest `stamp`, when within kStampToleranceS.
const SE2* poseAt(const std::vector<StampedPose>& by_stamp, Stamp stamp) {
  const std::optional<std::size_t> index = nearestStampIndex(by_stamp, stamp);
  return index ? &by_stamp[*index].pose : nullptr;
}

struct ErrorSums {
  std::vector<double> translations;
  std::vector<double> rotations_deg;
  void add(double translation, double rotation_deg) {
    translations.push_back(translation);
    rotations_deg.push_back(rotation_deg);
  }
};

void meanAndSigma(const std::vector<double>& values, double& mean, double& sigma) {
  mean = 0.0;
  sigma = 0.0;
  if (values.empty()) {
    return;
  }
  for (const double value : values) {
    mean += value;
  }
  mean /= static_cast<double>(values.size());
  for (const double value : values) {
    sigma += (value - mean) * (value - mean);
  }
  sigma = std::sqrt(sigma / static_cast<double>(values.size()));
}

RelationErrorStats statsOf(const ErrorSums& sums) {
  RelationErrorStats stats;
  stats.count = sums.translations.size();
  meanAndSigma(sums.translations, stats.translation_mean_m, stats.translation_sigma_m);
  meanAndSigma(sums.rotations_deg, stats.rotation_mean_deg, stats.rotation_sigma_deg);
  return stats;
}

}  // namespace

std::vector<Relation> readRelations(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error("cannot read relations file " + path);
  }
  std::vector<Relation> relations;
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    if (!isBlankOrComment(text)) {
      relations.push_back(parseRelation(text, path, line));
    }
  }
  return relations;
}

std::optional<std::size_t> nearestStampIndex(const std::vector<StampedPose>& by_stamp,
                                             Stamp stamp) {
  const auto after =
      std::lower_bound(by_stamp.begin(), by_stamp.end(), stamp,
                       [](const StampedPose& pose, Stamp value) { return pose.stamp < value; });
  std::optional<std::size_t> best;
  double best_s = kStampToleranceS;
  for (auto it : {after, after == by_stamp.begin() ? after : std::prev(after)}) {
    if (it == by_stamp.end()) {
      continue;
    }
    const double apart = std::abs(secondsBetween(it->stamp, stamp));
    if (apart <= best_s) {
      best_s = apart;
      best = static_cast<std::size_t>(it - by_stamp.begin());
    }
  }
  return best;
}

RelationReport evaluateRelations(const std::vector<StampedPose>& trajectory,
                                 const std::vector<Relation>& relations) {
  std::vector<StampedPose> by_stamp = trajectory;
  std::stable_sort(by_stamp.begin(), by_stamp.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.stamp < b.stamp; });
  RelationReport report;
  ErrorSums all;
  ErrorSums near;
  ErrorSums far;
  for (const Relation& relation : relations) {
    const SE2* T_world_from = poseAt(by_stamp, relation.from);
    const SE2* T_world_to = poseAt(by_stamp, relation.to);
    if (!T_world_from || !T_world_to) {
      ++report.unmatched;
      continue;
    }
    const SE2 T_from_to = T_world_from->inverse() * *T_world_to;
    const SE2 error = relation.T_from_to.inverse() * T_from_to;
    const double translation = error.translation().norm();
    const double rotation_deg = std::abs(error.theta()) * 180.0 / M_PI;
    all.add(translation, rotation_deg);
    const bool is_near = std::abs(secondsBetween(relation.from, relation.to)) < kNearSeconds;
    (is_near ? near : far).add(translation, rotation_deg);
  }
  report.all = statsOf(all);
  report.near = statsOf(near);
  report.far = statsOf(far);
  return report;
}

}  // namespace mrslam::robot
