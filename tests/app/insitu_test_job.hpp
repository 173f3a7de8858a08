// The small coupled job of the in-situ tests (test_insitu.cpp, test_dem_pool_mpi.cpp).
#pragma once

#include <string>

namespace app_test {

// Three bodies: a geostatic column (2 points, K0 = 0.5, surface at the top z = 2 m; the upper point
// is floored at 10 kPa), a uniform anisotropic one and a prepared one.
inline std::string insitu_job(const std::string& initial_state_table) {
  return R"([dem.material]
density = "2650 kg/m^3"
young_modulus = "300 MPa"
stiffness_ratio = 0.5
friction_angle = "30 deg"
rolling_stiffness = 2.0
rolling_strength = 0.3

[dem.sample]
spheres = 60
psd_diameters = ["130 um", "270 um"]
psd_passing = [0.0, 1.0]
seed = 5

[dem.preparation]
pressure = "50 kPa"
friction_angle = "10 deg"
inertial_number = 1e-2
unbalanced_force = 0.05
stress_tolerance = 0.02

[dem.coupling]
inertial_number = 1e-2
)" + initial_state_table +
         R"(
[mpm]
end_time = 1.0
gravity = [0.0, 0.0, -9.81]

[mpm.grid]
origin = [0.0, 0.0, 0.0]
spacing = [1.0, 1.0, 1.0]
cells = [3, 1, 2]

[[mpm.body]]
min = [0.0, 0.0, 0.0]
max = [1.0, 1.0, 2.0]
points_per_cell = 1
density = 1700.0
material = "dem"
initial_state = "geostatic"
k0 = 0.5

[[mpm.body]]
min = [1.0, 0.0, 0.0]
max = [2.0, 1.0, 1.0]
points_per_cell = 1
density = 1700.0
material = "dem"
initial_state = "uniform"
initial_stress = ["-30 kPa", "-30 kPa", "-60 kPa", 0.0, "5 kPa", 0.0]

[[mpm.body]]
min = [2.0, 0.0, 0.0]
max = [3.0, 1.0, 1.0]
points_per_cell = 1
density = 1700.0
material = "dem"
)";
}

}  // namespace app_test
