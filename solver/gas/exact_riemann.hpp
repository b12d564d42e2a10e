#pragma once
// Exact solution of the 1-D Riemann problem for a gamma-law gas (Toro, "Riemann Solvers and
// Numerical Methods for Fluid Dynamics", ch. 4): Newton iteration for the star pressure,
// then sampling of the self-similar solution at xi = (x - x0)/t.
namespace dustlift {

/// 1-D primitive state (density, normal velocity, pressure).
struct RiemannState {
  double rho, u, p;
};

class ExactRiemannSolver {
 public:
  /// Throws std::invalid_argument for non-positive states or when vacuum would form.
  ExactRiemannSolver(const RiemannState& left, const RiemannState& right, double gamma);

  double star_pressure() const { return p_star_; }
  double star_velocity() const { return u_star_; }
  /// Density left/right of the contact in the star region.
  double star_density_left() const;
  double star_density_right() const;
  /// The solution at xi = (x - x0) / t.
  RiemannState sample(double xi) const;

 private:
  /// Pressure function f_K(p) of Toro eq. (4.6)-(4.7) and its derivative.
  void pressure_function(double p, const RiemannState& s, double c, double& f, double& df) const;

  RiemannState left_, right_;
  double gamma_, c_left_, c_right_;
  double p_star_ = 0.0, u_star_ = 0.0;
};

}  // namespace dustlift
