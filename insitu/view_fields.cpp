#include "insitu/view_fields.hpp"

#include <stdexcept>
#include <string>

#include "solver/sim/derived_fields.hpp"

namespace dustlift {

const Field2D& derived_field(const StateView& view, std::string_view name) {
  if (view.derived == nullptr)
    throw std::invalid_argument("the state view has no derived fields for " + std::string(name) +
                                " (StateView::derived)");
  return view.derived->field(name);
}

}  // namespace dustlift
