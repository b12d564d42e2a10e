#pragma once
// The progress line's estimate of the wall time left. A coupled run grows dearer as it goes:
// the shock sweeps more of the layer, more parcels move and fewer cells rest, so the average
// rate since the start (cheap early steps ahead of the dust included) underestimates what is
// left. The rate over the last progress interval follows that growth. Pure function.

namespace dustlift {

/// Seconds of wall time left to reach `end`, at the wall-time rate between the previous report
/// (t_prev, wall_prev) and now (t, wall); at the first report (t_prev = start, wall_prev = 0)
/// that is the average since the start. 0 when no simulated time has passed.
inline double remaining_wall_seconds(double t, double end, double wall, double t_prev,
                                     double wall_prev) {
  if (!(t > t_prev) || !(end > t)) return 0.0;
  return (wall - wall_prev) * (end - t) / (t - t_prev);
}

}  // namespace dustlift
