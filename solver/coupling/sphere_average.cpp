#include "solver/coupling/sphere_average.hpp"

#include <cmath>
#include <numbers>

namespace dustlift {
namespace {

std::array<SpherePoint, kSpherePoints> make_points() {
  // Gauss-Legendre nodes and weights on [-1, 1], the positive half.
  static constexpr double kLegendre[8][2] = {
      {0.095012509837637454, 0.18945061045506859}, {0.28160355077925892, 0.18260341504492361},
      {0.45801677765722737, 0.16915651939500262},  {0.61787624440264377, 0.14959598881657676},
      {0.755404408355003, 0.12462897125553403},    {0.86563120238783176, 0.095158511682492591},
      {0.9445750230732326, 0.062253523938647706},  {0.98940093499164994, 0.027152459411754037}};
  std::array<SpherePoint, kSpherePoints> p{};
  int k = 0;
  const double volume = 4.0 / 3.0 * std::numbers::pi;
  for (int side : {-1, 1}) {
    for (const auto& [node, w_xi] : kLegendre) {
      const double xi = side * node, b = std::sqrt(1.0 - xi * xi);
      // int_{-b}^{b} 2 sqrt(b^2 - eta^2) g(eta) d eta = 2 b^2 int_{-1}^{1} sqrt(1 - t^2) g(b t) dt,
      // Gauss-Chebyshev (second kind): t_j = cos(j pi / 4), w_j = pi / 4 sin^2(j pi / 4).
      for (int j = 1; j <= 3; ++j) {
        const double angle = j * std::numbers::pi / 4.0, s = std::sin(angle);
        const double w_t = std::numbers::pi / 4.0 * s * s;
        p[static_cast<std::size_t>(k++)] = {xi, b * std::cos(angle),
                                            w_xi * 2.0 * b * b * w_t / volume};
      }
    }
  }
  return p;
}

}  // namespace

const std::array<SpherePoint, kSpherePoints>& sphere_points() {
  static const std::array<SpherePoint, kSpherePoints> points = make_points();
  return points;
}

}  // namespace dustlift
