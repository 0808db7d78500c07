#pragma once
// The forms in which a wall's pressure continues the fluid's (src/boundary/adami_wall.hpp), named by
// -wall_pressure and by a scene's wall groups (wall_pressure: on a wall or body region).

namespace sph {

// -wall_pressure: how a wall particle's pressure continues the fluid's along the wall (AdamiWall).
enum class WallPressure { Adami, Continued };
inline const char* const wall_pressure_names[] = {"adami", "continued"};
inline constexpr const char* wall_pressure_help =
    "How the walls' pressure continues the fluid's: adami (the fluid's pressure plus rho (g - a_w) . r, "
    "Adami et al. 2012: the fluid taken to accelerate with the wall along it too, so a lone particle on "
    "a side wall is held up) or continued (rho (g - a_w) across the wall, the fluid's own pressure gradient "
    "along it: a lone particle falls; not yet the default: docs/verification/free_surface.md, \"Walls that "
    "continue the fluid's own pressure\"). A wall or body region of a YAML scene may choose its own "
    "(wall_pressure:)";

}  // namespace sph
