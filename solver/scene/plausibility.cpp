// Plausibility checks that name the unit: a value that is legal but far outside what the unit
// makes plausible is most often a unit slip (a pressure of 1.0 meant as 1 atm, a temperature
// of 20 meant as 20 degrees Celsius). Refused unless run.allow_implausible = true.
#include <fmt/format.h>

#include <string>
#include <utility>
#include <vector>

#include "solver/scene/parse_sections.hpp"

namespace dustlift::scene_detail {

namespace {

/// "set run.allow_implausible = true" with the value as written.
std::string confirm(double value, const char* unit) {
  return fmt::format("if {:g} {} is meant, set run.allow_implausible = true", value, unit);
}

}  // namespace

void check_plausible_pressure(TableReader& t, std::string_view key, double p) {
  if (p >= kPlausiblePressureMin || t.implausible_allowed()) return;
  // What the number would be in the usual other units, where that is a plausible pressure.
  std::vector<std::string> candidates;
  for (const auto& [unit, pa] :
       {std::pair{"atm", 101325.0}, std::pair{"bar", 1e5}, std::pair{"kPa", 1e3}})
    if (p * pa >= kPlausiblePressureMin)
      candidates.push_back(fmt::format("{:g} {} = {:g} Pa", p, unit, p * pa));
  std::string meant;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    meant += (k == 0 ? "" : k + 1 == candidates.size() ? " or " : ", ") + candidates[k];
  t.fail(key,
         fmt::format(
             "{:g} Pa is below {:g} kPa, implausible for a gas pressure: pressures are in Pa{}; {}",
             p, kPlausiblePressureMin / 1e3, meant.empty() ? "" : " (did you mean " + meant + "?)",
             confirm(p, "Pa")));
}

void check_plausible_temperature(TableReader& t, std::string_view key, double T) {
  if (T >= kPlausibleTemperatureMin || t.implausible_allowed()) return;
  t.fail(
      key,
      fmt::format(
          "{:g} K is below {:g} K, implausible for a temperature: temperatures are in K (did you "
          "mean {:g} degC = {:g} K?); {}",
          T, kPlausibleTemperatureMin, T, T + 273.15, confirm(T, "K")));
}

}  // namespace dustlift::scene_detail
