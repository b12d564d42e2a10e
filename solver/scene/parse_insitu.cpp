// [insitu]: in-situ pipelines beyond the built-in observers (ParaView Catalyst).
#include "solver/scene/parse_sections.hpp"

namespace dustlift::scene_detail {

namespace {

void parse_catalyst(TableReader t, CatalystConfig& c) {
  c.enabled = t.present();
  if (!c.enabled) return;
  t.expect_keys({"scripts", "interval_steps", "interval", "live", "live_url"});
  c.scripts = t.existing_file_list("scripts", {});
  c.live = t.boolean("live", c.live);
  c.live_url = t.string("live_url", c.live_url);
  if (c.live_url.empty())
    t.fail("live_url", "must name host:port of the ParaView GUI (Catalyst > Connect)");
  if (c.scripts.empty() && !c.live)
    t.fail("scripts", "give at least one Catalyst script, or live = true");
  if (t.has("interval_steps") && t.has("interval")) {
    t.fail("interval", "give either interval (s of simulated time) or interval_steps, not both");
  }
  // Only the one given is recorded: the resolved scene must parse back without "both".
  if (t.has("interval")) {
    c.interval = t.required_number("interval", Range::positive());
  } else {
    c.interval_steps = t.integer("interval_steps", c.interval_steps, 1, 1'000'000'000);
  }
  t.finish();
}

}  // namespace

void parse_insitu(TableReader t, InsituConfig& insitu) {
  t.expect_keys({"catalyst"});
  parse_catalyst(t.table("catalyst"), insitu.catalyst);
  t.finish();
}

}  // namespace dustlift::scene_detail
