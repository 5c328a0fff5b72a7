#include "mrslam/robot/chi_square.hpp"

#include <cmath>
#include <stdexcept>

namespace mrslam::robot {

namespace {

constexpr int kMaxTerms = 1000;
constexpr double kEpsilon = 1e-15;

// P(a, x) = e^{-x} x^a / Γ(a) Σ_n x^n / (a (a+1) … (a+n)).
double lowerGammaSeries(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < kMaxTerms; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * kEpsilon) {
      break;
    }
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) = 1 − P(a, x) by the continued fraction, evaluated with Lentz's method.
double upperGammaFraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < kMaxTerms; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < kTiny ? kTiny : d;
    c = b + an / c;
    c = std::abs(c) < kTiny ? kTiny : c;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < kEpsilon) {
      break;
    }
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double chiSquareCdf(double x, int dof) {
  if (dof <= 0) {
    throw std::invalid_argument("chiSquareCdf: dof must be positive");
  }
  if (x <= 0.0) {
    return 0.0;
  }
  const double a = 0.5 * dof;
  const double half_x = 0.5 * x;
  return half_x < a + 1.0 ? lowerGammaSeries(a, half_x) : 1.0 - upperGammaFraction(a, half_x);
}

double chiSquareQuantile(double probability, int dof) {
  if (!(probability > 0.0 && probability < 1.0)) {
    throw std::invalid_argument("chiSquareQuantile: probability must be in (0, 1)");
  }
  double low = 0.0;
  double high = dof + 10.0 * std::sqrt(2.0 * dof) + 50.0;
  while (chiSquareCdf(high, dof) < probability) {
    high *= 2.0;
  }
  for (int i = 0; i < 200 && high - low > 1e-12 * high; ++i) {
    const double mid = 0.5 * (low + high);
    (chiSquareCdf(mid, dof) < probability ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace mrslam::robot
