// Row form of the Gordon-Wilke air table (transport.hpp). Compiled with -fno-math-errno
// -fno-trapping-math (solver/CMakeLists.txt) so that the lookups vectorise (gathers); the
// values are those of GordonWilkeAirTable::operator() bit for bit.
#include "solver/gas/transport.hpp"

namespace dustlift {

void GordonWilkeAirTable::apply(const double* __restrict T, double* __restrict mu, double* __restrict lambda,
                                int n) const {
  const double* __restrict m = mu_.data();
  const double* __restrict l = lambda_.data();
  const double last = static_cast<double>(count_ - 1);
  bool all_inside = true;
  for (int i = 0; i < n; ++i) {
    const double x = (T[i] - kTmin) * kInvStep;
    all_inside = all_inside && (x >= 0.0 && x < last);
  }
  if (!all_inside) {
    for (int i = 0; i < n; ++i) {
      const TransportProperties p = (*this)(T[i]);
      mu[i] = p.mu;
      lambda[i] = p.lambda;
    }
    return;
  }
  for (int i = 0; i < n; ++i) {
    const double x = (T[i] - kTmin) * kInvStep;
    const auto k = static_cast<int>(x);
    const double w = x - static_cast<double>(k);
    mu[i] = m[k] + w * (m[k + 1] - m[k]);
    lambda[i] = l[k] + w * (l[k + 1] - l[k]);
  }
}

}  // namespace dustlift
