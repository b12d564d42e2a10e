#pragma once
// VTK-free entry point for the CLI: the observers a scene's [output] section asks for.
#include <memory>
#include <string>
#include <vector>

#include "insitu/dust_cloud.hpp"
#include "insitu/entrainment.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

/// The scene's outputs (VTK series, filters, series files, Catalyst). With
/// `piece_writers_only`, just those that write pieces (Observer::writes_pieces), in the same
/// order: what the ranks other than 0 of a decomposed run add.
std::vector<std::unique_ptr<Observer>> make_output_observers(const Scene& scene,
                                                             const std::string& output_dir,
                                                             bool piece_writers_only = false);

/// The dust-cloud observer's settings from a scene with particles and output.dust_cloud (what
/// `dustlift info` reports too).
DustCloudOptions dust_cloud_options(const Scene& scene);
EntrainmentOptions entrainment_options(const Scene& scene);

}  // namespace dustlift
