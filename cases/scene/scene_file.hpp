#pragma once
// A scene file: particles in a VTK XML PolyData file (.vtp), read with VTK's own reader and checked
// for what makes no scene (one-line sph::Error naming the file, what is wrong and the fix).
//   point arrays: kind (required; 0 fluid, 1 fixed wall, 2 moving wall), velocity (optional, 1-3
//                 components), pressure (optional)
//   field data:   optional scene parameters by name (dx, box, periodic, gravity, nu, rho0, U,
//                 free_surface, t_end), each an array of numbers; see cases/scene/scene.hpp
// The points are 3D in VTK; the scene is 2D when all z coordinates are equal.
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sph {

// Inlet and outlet buffer particles come from YAML scenes only (scene_yaml.hpp).
enum SceneKind : int { kSceneFluid = 0, kSceneFixedWall = 1, kSceneMovingWall = 2, kSceneInlet = 3, kSceneOutlet = 4 };

struct SceneFile {
  std::string path;
  int dim = 2;
  std::vector<std::array<double, 3>> x, v;           // positions; velocities (zero without the array)
  std::vector<double> p;                             // pressures (zero without the array)
  std::vector<int> kind;                             // SceneKind
  std::vector<char> free_slip;                       // 1 on free-slip wall particles (empty without the array)
  std::map<std::string, std::vector<double>> field;  // numeric field data arrays, by name
  std::uint64_t checksum = 0;                        // 64-bit FNV-1a of the file's bytes: the scene's identity

  // "scene file 'PATH': " + what, for one-line errors.
  std::string error(const std::string& what) const;
};

// 64-bit FNV-1a: h continued over n bytes (start from kFnv1aBasis). The scenes' identity (checksum).
constexpr std::uint64_t kFnv1aBasis = 1469598103934665603ull;
inline std::uint64_t fnv1a(std::uint64_t h, const void* data, std::size_t n) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < n; ++k) h = (h ^ bytes[k]) * 1099511628211ull;
  return h;
}

// Reads and checks the file: readable VTK XML PolyData with points, a `kind` array of 0/1/2, finite
// coordinates, velocities and pressures, at least one fluid particle; an optional `free_slip` array,
// 1 on free-slip wall particles (src/boundary/moving_bodies.hpp), 0 elsewhere. Throws sph::Error otherwise.
SceneFile read_scene_file(const std::string& path);

// The particles' spacing as they lie: the median distance to each particle's nearest neighbour
// (a sample of at most about 20000 particles); 0 for fewer than two particles or most of them coincident.
double median_spacing(const SceneFile& s);

}  // namespace sph
