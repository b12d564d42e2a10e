#include "insitu/outputs.hpp"

namespace dustlift {

std::vector<std::unique_ptr<Observer>> make_output_observers(const Scene&, const std::string&) {
  return {};
}

}  // namespace dustlift
