#pragma once
// Error kinds the CLI maps to exit codes: bad input -> 2, numerical failure -> 3.
#include <stdexcept>
#include <string>

namespace dustlift {

/// The run became unphysical (NaN, rho <= 0, p <= 0, alpha_g out of (0, 1]).
/// The message names the step, time, cell or parcel and the variable.
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace dustlift
