#pragma once
// Rigid transforms in the plane. A transform is named by its frames: T_a_b maps coordinates in
// frame b to coordinates in frame a (equivalently, it is the pose of frame b expressed in a).

#include <Eigen/Core>
#include <cmath>

namespace mrslam {

/// Wraps an angle to (-pi, pi].
inline double wrapAngle(double angle_rad) {
  double wrapped = std::remainder(angle_rad, 2.0 * M_PI);
  if (wrapped <= -M_PI) {
    wrapped += 2.0 * M_PI;
  }
  return wrapped;
}

/// An element of SE(2): translation (x, y) in metres and rotation theta in radians.
class SE2 {
 public:
  SE2() = default;
  SE2(double x, double y, double theta) : x_(x), y_(y), theta_(wrapAngle(theta)) {}

  double x() const { return x_; }
  double y() const { return y_; }
  double theta() const { return theta_; }
  Eigen::Vector2d translation() const { return {x_, y_}; }
  Eigen::Matrix2d rotation() const {
    const double c = std::cos(theta_);
    const double s = std::sin(theta_);
    Eigen::Matrix2d r;
    r << c, -s, s, c;
    return r;
  }

  /// T_a_c = T_a_b * T_b_c.
  SE2 operator*(const SE2& T_b_c) const {
    const Eigen::Vector2d t = rotation() * T_b_c.translation() + translation();
    return SE2(t.x(), t.y(), theta_ + T_b_c.theta_);
  }

  /// p_a = T_a_b * p_b.
  Eigen::Vector2d operator*(const Eigen::Vector2d& p_b) const {
    return rotation() * p_b + translation();
  }

  /// T_b_a from T_a_b.
  SE2 inverse() const {
    const Eigen::Vector2d t = -(rotation().transpose() * translation());
    return SE2(t.x(), t.y(), -theta_);
  }

 private:
  double x_ = 0.0;
  double y_ = 0.0;
  double theta_ = 0.0;
};

}  // namespace mrslam
