#pragma once
// A scene that exercises every output in a second: the tests of restarts and of the output
// contract run it.

namespace dustlift::testing {

/// A Mach 1.44 shock over a 16 mm x 2 mm layer (2,404 parcels, drag, Magnus, pressure force),
/// 0.5 mm cells, outputs every 5 us, a pressure gauge every step, 20 us in ~93 steps (about
/// half a second).
inline const char* kShockOverDust = R"([run]
name = "mini"
end_time = 2.0e-5
[grid]
x = { start = -0.004, end = 0.016, cells = 40 }
y = { start = -0.002, end = 0.004, cells = 12 }
[gas]
thermo = "thermally_perfect"
[boundary]
left = "inflow"
right = "outflow"
bottom = "no_slip_wall"
top = "slip_wall"
[initial]
kind = "shock"
mach = 1.44
position = 0.0005
state = { p = 101.0e3, T = 300.0 }
[particles]
diameter = 100e-6
density = 980.0
[particles.layer]
x_min = 0.0
x_max = 0.016
y_min = -0.002
y_max = 0.0
volume_fraction = 0.59
[particles.contact]
k_n = 5.0e4
k_t = 100.0
damping = 1.0e-4
[coupling]
magnus = true
magnus_coefficient = 1.0
pressure_force = true
[output]
interval = 5.0e-6
[[output.probes]]
name = "gauge"
x = 0.008
y = 0.001
)";

}  // namespace dustlift::testing
