#include "insitu/parcel_arrays.hpp"

#include <stdexcept>
#include <string>

namespace dustlift {

const ParcelPointArray* ParcelArraysView::find(const std::string& name) const {
  for (const ParcelPointArray& a : arrays) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

void ParcelArraysView::check_sizes() const {
  auto check = [this](const std::string& name, std::size_t n) {
    if (n != 0 && n != count)
      throw std::invalid_argument("ParcelArraysView: " + name + " has " + std::to_string(n) +
                                  " values, expected " + std::to_string(count));
  };
  if (count > 0 && !position.present())
    throw std::invalid_argument("ParcelArraysView: position is required");
  check("position", position.x.size());
  check("position", position.y.size());
  for (const ParcelPointArray& a : arrays) {
    check(a.name, a.x.size());
    if (a.is_vector()) {
      check(a.name, a.y.size());
      if (a.x.size() != a.y.size())
        throw std::invalid_argument("ParcelArraysView: " + a.name + " x and y differ in length");
    }
  }
  check("id", id.size());
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
  ParcelArraysView out;
  out.count = kept;
  out.position = {copy(all.position.x), copy(all.position.y)};
  for (const ParcelPointArray& a : all.arrays) out.arrays.push_back({a.name, copy(a.x), copy(a.y)});
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
