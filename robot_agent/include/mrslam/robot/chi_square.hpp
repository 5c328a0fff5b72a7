#pragma once
// The χ² distribution for Mahalanobis gates and NEES bounds.

namespace mrslam::robot {

/// P(X ≤ x) for X ~ χ²(dof): the regularised lower incomplete gamma function P(dof/2, x/2),
/// by its series below a + 1 and its continued fraction above (Numerical Recipes, 3rd ed., §6.2).
double chiSquareCdf(double x, int dof);

/// The x with P(X ≤ x) = probability (0 < probability < 1), by bisection on chiSquareCdf.
double chiSquareQuantile(double probability, int dof);

}  // namespace mrslam::robot
