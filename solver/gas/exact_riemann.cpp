#include "solver/gas/exact_riemann.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dustlift {

ExactRiemannSolver::ExactRiemannSolver(const RiemannState& left, const RiemannState& right, double gamma)
    : left_(left), right_(right), gamma_(gamma) {
  if (!(left.rho > 0 && left.p > 0 && right.rho > 0 && right.p > 0 && gamma > 1)) {
    throw std::invalid_argument("ExactRiemannSolver: densities, pressures must be > 0 and gamma > 1");
  }
  c_left_ = std::sqrt(gamma * left.p / left.rho);
  c_right_ = std::sqrt(gamma * right.p / right.rho);
  const double du = right.u - left.u;
  if (2.0 / (gamma - 1.0) * (c_left_ + c_right_) <= du) {
    throw std::invalid_argument("ExactRiemannSolver: the states generate vacuum");
  }
  // Initial guess: primitive-variable (PVRS) estimate, Toro eq. (4.47), kept positive.
  const double p_pv = 0.5 * (left.p + right.p) -
                      0.125 * du * (left.rho + right.rho) * (c_left_ + c_right_);
  double p = std::max(1e-8 * std::min(left.p, right.p), p_pv);
  for (int iter = 0; iter < 200; ++iter) {
    double fl, dfl, fr, dfr;
    pressure_function(p, left_, c_left_, fl, dfl);
    pressure_function(p, right_, c_right_, fr, dfr);
    double next = p - (fl + fr + du) / (dfl + dfr);
    if (next <= 0) next = 0.5 * p;
    const double change = 2.0 * std::abs(next - p) / (next + p);
    p = next;
    if (change < 1e-15) break;
  }
  double fl, dfl, fr, dfr;
  pressure_function(p, left_, c_left_, fl, dfl);
  pressure_function(p, right_, c_right_, fr, dfr);
  p_star_ = p;
  u_star_ = 0.5 * (left.u + right.u) + 0.5 * (fr - fl);
}

void ExactRiemannSolver::pressure_function(double p, const RiemannState& s, double c, double& f,
                                           double& df) const {
  const double g = gamma_;
  if (p > s.p) {  // shock
    const double a = 2.0 / ((g + 1.0) * s.rho);
    const double b = (g - 1.0) / (g + 1.0) * s.p;
    const double q = std::sqrt(a / (p + b));
    f = (p - s.p) * q;
    df = q * (1.0 - 0.5 * (p - s.p) / (b + p));
  } else {  // rarefaction
    const double r = p / s.p;
    f = 2.0 * c / (g - 1.0) * (std::pow(r, (g - 1.0) / (2.0 * g)) - 1.0);
    df = 1.0 / (s.rho * c) * std::pow(r, -(g + 1.0) / (2.0 * g));
  }
}

static double star_density(const RiemannState& s, double p_star, double g) {
  if (p_star > s.p) {
    const double r = p_star / s.p, k = (g - 1.0) / (g + 1.0);
    return s.rho * (r + k) / (k * r + 1.0);
  }
  return s.rho * std::pow(p_star / s.p, 1.0 / g);
}

double ExactRiemannSolver::star_density_left() const { return star_density(left_, p_star_, gamma_); }
double ExactRiemannSolver::star_density_right() const { return star_density(right_, p_star_, gamma_); }

RiemannState ExactRiemannSolver::sample(double xi) const {
  const double g = gamma_;
  if (xi <= u_star_) {  // left of the contact
    const RiemannState& s = left_;
    const double c = c_left_;
    if (p_star_ > s.p) {
      const double speed = s.u - c * std::sqrt((g + 1.0) / (2.0 * g) * p_star_ / s.p + (g - 1.0) / (2.0 * g));
      if (xi <= speed) return s;
      return {star_density_left(), u_star_, p_star_};
    }
    const double head = s.u - c;
    const double c_star = c * std::pow(p_star_ / s.p, (g - 1.0) / (2.0 * g));
    const double tail = u_star_ - c_star;
    if (xi <= head) return s;
    if (xi >= tail) return {star_density_left(), u_star_, p_star_};
    const double u = 2.0 / (g + 1.0) * (c + 0.5 * (g - 1.0) * s.u + xi);
    const double cf = 2.0 / (g + 1.0) * (c + 0.5 * (g - 1.0) * (s.u - xi));
    const double rho = s.rho * std::pow(cf / c, 2.0 / (g - 1.0));
    return {rho, u, s.p * std::pow(cf / c, 2.0 * g / (g - 1.0))};
  }
  const RiemannState& s = right_;
  const double c = c_right_;
  if (p_star_ > s.p) {
    const double speed = s.u + c * std::sqrt((g + 1.0) / (2.0 * g) * p_star_ / s.p + (g - 1.0) / (2.0 * g));
    if (xi >= speed) return s;
    return {star_density_right(), u_star_, p_star_};
  }
  const double head = s.u + c;
  const double c_star = c * std::pow(p_star_ / s.p, (g - 1.0) / (2.0 * g));
  const double tail = u_star_ + c_star;
  if (xi >= head) return s;
  if (xi <= tail) return {star_density_right(), u_star_, p_star_};
  const double u = 2.0 / (g + 1.0) * (-c + 0.5 * (g - 1.0) * s.u + xi);
  const double cf = 2.0 / (g + 1.0) * (c - 0.5 * (g - 1.0) * (s.u - xi));
  const double rho = s.rho * std::pow(cf / c, 2.0 / (g - 1.0));
  return {rho, u, s.p * std::pow(cf / c, 2.0 * g / (g - 1.0))};
}

}  // namespace dustlift
