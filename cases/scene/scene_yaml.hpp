#pragma once
// A scene described by shapes in a YAML file (-scene_file FILE.yaml or .yml), sampled on a lattice at
// the run's spacing: one file for every resolution. The result is what the .vtp reader gives (particles
// and field data, cases/scene/scene_file.hpp), so -case scene runs it the same way.
//
//   dimension: 2                      # 2 or 3 (required)
//   dx: 0.025                         # optional: -nx N (dx = 1/N) or -scene_dx override it
//   box: [-0.3, 1.3, -0.3, 20]        # the domain [x0, x1, y0, y1(, z0, z1)]; optional unless periodic
//   periodic: none                    # or x, or [x, y]
//   physics: {gravity: [0, -1], nu: 0.002, rho0: 1, free_surface: true, t_end: 4, U: 1}   # all optional
//   regions:                          # in order: later fluid regions override earlier ones
//     - {role: wall, shape: {difference: [{box: [-1, 2, -1, 1.3]}, {box: [0, 1, 0, 2]}]}}
//     - {role: {body: cylinder}, shape: {circle: {centre: [0.5, 0.45], radius: 0.12}}}
//     - {role: fluid, shape: {box: [0, 1, 0, 0.15]}, pressure: hydrostatic}
//     - {role: fluid, shape: {box: [0.3, 0.7, 0.75, 1.05]}, velocity: [0, 0], pressure: 0}
//
// Shapes (signed distances, cases/scene/shapes.hpp): box [x0, x1, y0, y1(, z0, z1)]; circle (2D) and
// sphere (3D) {centre, radius}; polygon (2D) [[x, y], ...]; cylinder (3D) {ends: [[x, y, z], [x, y, z]],
// radius}; half_space {point, normal}, solid where (x - point) . normal <= 0; union / intersection
// [shapes]; difference [A, B, ...], A minus the others; mesh FILE, a closed .stl, .obj or .vtp surface
// (3D; the path relative to the YAML file); plate {from, to, thickness} (2D walls and fixed bodies
// thinner than the kernel's support: each face's own layers, src/neighbours/screens.hpp).
// The flat form says the same: the physics keys at the top (gravity: [0, -1], nu: 0.01), a shape
// inline with its parameters beside it (shape: circle, centre: [1, 0.5], radius: 0.2; shape:
// difference, of: [...]; box: bounds, polygon: vertices, mesh: file), role: body with name: NAME.
// Roles: fluid (kind 0); wall (fixed wall, kind 1); {body: NAME} (or role: body, name: NAME), a fixed
// wall whose particles keep the body's name (YamlScene::body): timeseries.csv reports its force.
// Region values (fluid only): velocity (default zero); pressure, a number (default 0) or hydrostatic:
// rho0 |g| times the depth below the free surface above the particle (along -g, to the first point in
// no fluid region and no solid: a tilted surface starts in balance). Walls and bodies: slip: free
// (no shear on the fluid; default no_slip, src/boundary/moving_bodies.hpp) and wall_pressure: adami |
// continued (how their pressure continues the fluid's; default -wall_pressure's, src/boundary/adami_wall_model.hpp).
//
// Open boundaries: {role: inlet, side: x-, velocity: [u, v] or {parabolic: U_max}, ramp: T,
// speed_table: FILE} and
// {role: outlet, side: x+, pressure: p} (default 0; with level: H, p plus the hydrostatic pressure below
// the water level H, measured along -gravity: an open channel's outlet) on sides of the box (x-, x+, y-, y+, z-, z+).
// Each has a buffer beyond the side as deep as the walls (the kernel's support), over the section where a fluid region
// meets the side: the box grows by it. A parabolic inflow spans the section between the solids (a channel's or a duct's
// walls); a ramp starts it from rest, (1 - cos(pi t / T)) / 2, and speed_table: FILE (t,factor) scales it in time.
//
// Probes: probes: [{name: P1, at: [x, y]}, ...] adds the pressure at each point to timeseries.csv
// (probe_P1_p, src/run/probes.hpp); a name is letters, digits and _, a point lies within the box.
//
// Sampling: lattice points (i + 1/2) dx within the box (and within the regions' bounds), so a box from
// 0 to 1 holds 1/dx points per side. A point inside a wall or body is a wall particle when it lies
// within wall_layers dx of the solids' surface (thick walls do not fill up; a solid may run past the
// box, which cuts it), and anywhere inside a body (bodies are whole); a point in no solid and inside a
// fluid region is fluid; other points are dropped.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cases/scene/scene_file.hpp"
#include "src/core/expression.hpp"
#include "src/io/surface_writer.hpp"

namespace sph {

// A body's prescribed motion (src/boundary/moving_bodies.hpp): a translation, `fixed`, `constant`
// (velocity) or `sinusoidal` (displacement amplitude (sin(2 pi t / period + phase) - sin phase)), and a
// rotation about an axis through `centre` (moving with the translation): `constant` (rate) or
// `sinusoidal` (angle amplitude, period, phase). Angles in degrees.
struct MotionSpec {
  std::string type = "fixed", spin = "fixed";
  std::array<double, 3> velocity{}, amplitude{}, centre{}, axis{0.0, 0.0, 1.0};
  double period = 1.0, phase_degrees = 0.0;
  double rate_degrees = 0.0, angle_degrees = 0.0, spin_period = 1.0, spin_phase_degrees = 0.0;
  // type table: the rows of t, x, y(, z)(, angle in degrees) of a CSV file (spin "table" with an angle).
  std::vector<double> table_t, table_angle_degrees;
  std::array<std::vector<double>, 3> table_x;
  // type free (src/boundary/free_body.hpp): the fluid moves the body. Its density or mass (one of them,
  // the other 0), initial velocity (`velocity`) and rotation rate (degrees/s), the axes held fixed, and
  // a hinge (a fixed point, and in 3D its axis in `axis`).
  double density = 0.0, mass = 0.0;
  std::array<double, 3> rate3_degrees{};
  std::array<bool, 3> fixed_translation{}, fixed_rotation{};
  bool hinged = false;
  std::array<double, 3> hinge{};
};

// An inlet or an outlet on a side of the box (src/boundary/open_boundaries.hpp): its buffer lies
// beyond the side, `depth` deep, over the section where fluid meets the side.
struct OpenBoundarySpec {
  bool inlet = true;
  int axis = 0, side = -1;  // side -1: the box's low side along axis, +1: its high side
  double plane = 0.0, depth = 0.0;
  std::array<double, 3> section_lo{}, section_hi{};  // the section's extent along the other axes
  std::array<double, 3> velocity{};                  // inlet: uniform velocity
  double peak = 0.0;                                 // inlet: parabolic profile's centre speed (0: uniform)
  std::vector<Expression> expressions;               // inlet: the velocity's components as expressions of x, y(, z)
  double top_speed = 0.0;                            // inlet: the expressions' largest speed across the section
  double ramp = 0.0;                                 // inlet: time to full speed from rest
  std::vector<double> speed_t, speed_factor;         // inlet: its speed table (t, factor), if any
  double pressure = 0.0;                             // outlet: its pressure (at the level, if it keeps one)
  bool keeps_level = false;                          // outlet: hydrostatic below a water level (open channels)
  double level = 0.0;                                // outlet: that level's height along -gravity
};

// A pressure probe (src/run/probes.hpp): {name: P1, at: [x, y(, z)]}.
struct ProbeSpec {
  std::string name;
  std::array<double, 3> at{};
};

struct YamlScene {
  SceneFile file;                          // particles and field data, as read_scene_file gives them
  std::vector<int> body;                   // per particle: index into bodies, -1 for fluid and walls
  std::vector<char> free_slip;             // per particle: 1 on walls and bodies given slip: free
  std::vector<signed char> wall_pressure;  // per particle: a wall or body's wall_pressure (-1: none given)
  std::vector<std::string> bodies;         // the body names, in order of first appearance
  std::vector<MotionSpec> motions;         // per body
  std::vector<SurfaceMesh> surfaces;       // per body, where the body is at t = 0 (within the box)
  // Thin plates (2D): per particle, 0 or the face whose layers it belongs to, +-(k + 1) for plate k
  // (src/neighbours/screens.hpp); each plate's mid-line x0, y0, x1, y1.
  std::vector<std::int8_t> plate_face;
  std::vector<std::array<double, 4>> plates;
  std::vector<int> plate_body;         // per plate: the body it belongs to, -1 for a wall's
  std::vector<OpenBoundarySpec> open;  // inlets and outlets; their particles are kinds kSceneInlet, kSceneOutlet
  std::vector<ProbeSpec> probes;       // pressure probes, in the file's order
};

// By the extension: .yaml or .yml.
bool is_yaml_scene(const std::string& path);

// The file's `dimension` (2 or 3), without sampling it.
int yaml_scene_dimension(const std::string& path);

// Reads, checks and samples the file at spacing dx (dx <= 0: the file's own dx key), with walls
// wall_layers particles deep. checksum: the file's bytes (and its meshes'), dx and wall_layers.
// Throws sph::Error with one line naming the file, the line and key, and the fix.
YamlScene read_yaml_scene(const std::string& path, double dx, int wall_layers);

}  // namespace sph
