#include "solver/scene/resource_limits.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>

namespace dustlift {

double machine_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

double estimated_run_bytes(double cells, double parcels) {
  return kBytesBase + kBytesPerCell * cells + kBytesPerParcel * parcels;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 6) bytes /= 1000.0, ++u;
  return fmt::format("{:.3g} {}", bytes, units[u]);
}

std::string memory_shortfall(double cells, double parcels) {
  const double have = machine_memory_bytes(), need = estimated_run_bytes(cells, parcels);
  if (!(have > 0.0) || need <= 0.9 * have) return {};
  return fmt::format("needs about {} of memory; this machine has {}", format_bytes(need),
                     format_bytes(have));
}

}  // namespace dustlift
