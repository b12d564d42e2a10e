// [particles]: the DEM parcel system (owned by the DEM module).
#include "solver/scene/parse_sections.hpp"

namespace dustlift::scene_detail {

void parse_particles(TableReader t, DemConfig& dem) {
  dem.enabled = t.present();
  t.finish();
}

}  // namespace dustlift::scene_detail
