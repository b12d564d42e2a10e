#include "solver/core/wait_policy.hpp"

#include <unistd.h>

#include <cstdlib>

namespace dustlift {

bool set_default_wait_policy() {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr)
    return false;
  return setenv("OMP_WAIT_POLICY", "passive", 1) == 0 &&
         setenv("GOMP_SPINCOUNT", kDefaultSpinCount, 1) == 0;
}

void reexec_with_default_wait_policy(char** argv) {
  if (set_default_wait_policy()) execv("/proc/self/exe", argv);
}

std::string wait_policy_description() {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  const char* spins = std::getenv("GOMP_SPINCOUNT");
  std::string s = "OpenMP wait: OMP_WAIT_POLICY=";
  s += policy != nullptr ? policy : "(unset)";
  s += ", GOMP_SPINCOUNT=";
  s += spins != nullptr ? spins : "(unset)";
  return s;
}

}  // namespace dustlift
