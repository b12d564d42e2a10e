#include "insitu/parcel_arrays.hpp"

#include <stdexcept>
#include <string>

namespace dustlift {

void ParcelArraysView::check_sizes() const {
  auto check = [this](const char* name, std::size_t n) {
    if (n != 0 && n != count)
      throw std::invalid_argument(std::string("ParcelArraysView: ") + name + " has " +
                                  std::to_string(n) + " values, expected " +
                                  std::to_string(count));
  };
  auto check2 = [&](const char* name, const Vec2Columns& v) {
    check(name, v.x.size());
    check(name, v.y.size());
    if (v.x.size() != v.y.size())
      throw std::invalid_argument(std::string("ParcelArraysView: ") + name +
                                  " x and y differ in length");
  };
  if (count > 0 && !position.present())
    throw std::invalid_argument("ParcelArraysView: position is required");
  check2("position", position);
  check2("velocity", velocity);
  check("angular_velocity", angular_velocity.size());
  check("temperature", temperature.size());
  check("diameter", diameter.size());
  check2("initial_position", initial_position);
  check2("force_contact", force_contact);
  check2("force_drag", force_drag);
  check2("force_magnus", force_magnus);
  check2("force_pressure", force_pressure);
  check("id", id.size());
  for (const auto& c : extra) check(c.name.c_str(), c.values.size());
}

ParcelArraysView kept_rows(const ParcelArraysView& all, std::span<const std::uint8_t> drop,
                           ParcelArraysCopy& storage) {
  all.check_sizes();
  if (!drop.empty() && drop.size() != all.count)
    throw std::invalid_argument("kept_rows: drop has " + std::to_string(drop.size()) +
                                " flags for " + std::to_string(all.count) + " parcels");
  std::size_t kept = 0;
  for (std::size_t i = 0; i < all.count; ++i) kept += drop.empty() || drop[i] == 0;
  std::size_t next_column = 0;
  const auto copy = [&](std::span<const double> from) -> std::span<const double> {
    if (!is_present(from)) return {};
    if (storage.columns.size() <= next_column) storage.columns.resize(next_column + 1);
    std::vector<double>& to = storage.columns[next_column++];
    to.resize(kept);
    std::size_t k = 0;
    for (std::size_t i = 0; i < all.count; ++i)
      if (drop.empty() || drop[i] == 0) to[k++] = from[i];
    return present_column(to);
  };
  const auto copy2 = [&](const Vec2Columns& v) { return Vec2Columns{copy(v.x), copy(v.y)}; };
  ParcelArraysView out;
  out.count = kept;
  out.position = copy2(all.position);
  out.velocity = copy2(all.velocity);
  out.angular_velocity = copy(all.angular_velocity);
  out.temperature = copy(all.temperature);
  out.diameter = copy(all.diameter);
  out.initial_position = copy2(all.initial_position);
  out.force_contact = copy2(all.force_contact);
  out.force_drag = copy2(all.force_drag);
  out.force_magnus = copy2(all.force_magnus);
  out.force_pressure = copy2(all.force_pressure);
  for (const auto& c : all.extra) out.extra.push_back({c.name, copy(c.values)});
  if (all.id.data() != nullptr) {
    storage.id.resize(kept);
    storage.id.reserve(1);  // a data pointer even for no parcel: the id column is present
    std::size_t k = 0;
    for (std::size_t i = 0; i < all.count; ++i)
      if (drop.empty() || drop[i] == 0) storage.id[k++] = all.id[i];
    out.id = std::span<const std::int32_t>(storage.id.data(), kept);
  }
  return out;
}

}  // namespace dustlift
