// Filling a scene's lattice: each point (i + 1/2) dx within the box becomes a particle of the solid or
// the fluid region that holds it, or of an open boundary's buffer, with its start velocity and pressure;
// the checks that every region got its share. Internal to cases/scene/.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cases/scene/scene_reader.hpp"

namespace sph::scene_detail {

// What the regions are laid out in: the spacing, the box, the periodic axes, and the physics a
// hydrostatic start needs.
struct SceneFrame {
  int dim = 2;
  double dx = 0.0;
  bool has_box = false;
  Point3 box_lo = Point3::Constant(-kInf), box_hi = Point3::Constant(kInf);
  std::vector<double> periodic;  // per axis, 1 when periodic
  double rho0 = 1.0;
  Point3 g = Point3::Zero();
};

// The regions as read, sorted by what the lattice makes of them.
struct SceneRegions {
  YAML::Node list;                                                // regions:, for the messages
  std::vector<Region> solids, fluids, plates;                     // plates: walls or bodies of shape: plate
  Bounds reach{Point3::Constant(kInf), Point3::Constant(-kInf)};  // of every region's shape
  std::vector<std::pair<YAML::Node, std::string>> open_nodes;     // each open boundary's region and key
  std::vector<char> free;                                         // per body, 1 where the fluid moves it
};

// Per body, 1 where the fluid moves it; such a body in a scene without fluid, or with a plate, is refused.
std::vector<char> free_bodies(const Reader& r, const std::vector<Region>& solids, const std::vector<Region>& fluids,
                              const std::vector<Region>& plates, const std::vector<MotionSpec>& motions,
                              const std::vector<std::string>& names);

// Adds the particles of the lattice's points, the plates' layers and the open boundaries' buffers to
// out (out.open's sections placed), after the memory check, and refuses a region that got no particle
// or far fewer than its shape holds.
void fill_lattice(const Reader& r, const SceneFrame& frame, const SceneRegions& regions, int wall_layers,
                  YamlScene& out);

}  // namespace sph::scene_detail
