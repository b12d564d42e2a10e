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

}  // namespace dustlift
