#pragma once
// VTK-free entry point for the CLI: the observers a scene's [output] section asks for.
#include <memory>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

/// The scene's outputs (VTK series, filters, series files, Catalyst). With
/// `piece_writers_only`, just those that write pieces (Observer::writes_pieces), in the same
/// order: what the ranks other than 0 of a decomposed run add.
std::vector<std::unique_ptr<Observer>> make_output_observers(const Scene& scene,
                                                             const std::string& output_dir,
                                                             bool piece_writers_only = false);

}  // namespace dustlift
