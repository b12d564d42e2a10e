#pragma once
// VTK-free entry point for the CLI: the observers a scene's [output] section asks for.
#include <memory>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

std::vector<std::unique_ptr<Observer>> make_output_observers(const Scene& scene,
                                                             const std::string& output_dir);

}  // namespace dustlift
