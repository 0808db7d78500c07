#include "cases/registry.hpp"

#include "cases/beltrami/beltrami.hpp"
#include "cases/dam_break/dam_break.hpp"
#include "cases/elliptical_drop/elliptical_drop.hpp"
#include "cases/lid_driven_cavity/lid_driven_cavity.hpp"
#include "cases/poiseuille/poiseuille.hpp"
#include "cases/scene/scene.hpp"
#include "cases/sedov/sedov.hpp"
#include "cases/sod/sod.hpp"
#include "cases/square_patch/square_patch.hpp"
#include "cases/standing_wave/standing_wave.hpp"
#include "cases/still_water/still_water.hpp"
#include "cases/taylor_green/taylor_green.hpp"
#include "cases/toy_star/toy_star.hpp"
#include "src/core/error.hpp"

namespace sph {

const std::vector<CaseEntry>& case_registry() {
  static const std::vector<CaseEntry> entries = {
      {"taylor_green", "decaying Taylor-Green vortex, periodic unit square, analytic reference", 2, nullptr,
       [] { return std::make_unique<TaylorGreen>(); }, nullptr},
      {"beltrami", "decaying Arnold-Beltrami-Childress flow, periodic cube [0, 2 pi)^3, 3D, analytic reference", 3,
       nullptr, nullptr, [] { return std::make_unique<Beltrami>(); }},
      {"lid_driven_cavity",
       "unit cavity (cube in 3D) with a sliding lid, Adami walls, to steady state; Ghia et al. (1982), "
       "3D Albensoeder & Kuhlmann (2005) and a finite-difference reference",
       2, nullptr, [] { return std::make_unique<LidDrivenCavity<2>>(); },
       [] { return std::make_unique<LidDrivenCavity<3>>(); }},
      {"dam_break",
       "collapsing water column (a x 2a, x a in 3D) in a 4a tank, free surface; Martin & Moyce (1952) front", 2,
       nullptr, [] { return std::make_unique<DamBreak<2>>(); }, [] { return std::make_unique<DamBreak<3>>(); }},
      {"still_water",
       "water at rest in an open tank (x L deep in 3D), free surface; the hydrostatic state it starts in", 2, nullptr,
       [] { return std::make_unique<StillWater<2>>(); }, [] { return std::make_unique<StillWater<3>>(); }},
      {"elliptical_drop",
       "inviscid circular drop stretched by u = A0 (x, -y), free surface, no gravity; its semi-axes "
       "against the ODE of Monaghan (1994)",
       2, nullptr, [] { return std::make_unique<EllipticalDrop>(); }, nullptr},
      {"standing_wave",
       "first sloshing mode of a tank, small amplitude, free surface; its period against linear theory", 2, nullptr,
       [] { return std::make_unique<StandingWave>(); }, nullptr},
      {"square_patch", "rotating square of fluid in vacuum, free surface; invariants of inviscid flow", 2, nullptr,
       [] { return std::make_unique<SquarePatch>(); }, nullptr},
      {"poiseuille", "body-force-driven channel between walls, periodic in x; series solution (Morris et al. 1997)", 2,
       nullptr, [] { return std::make_unique<Poiseuille>(); }, nullptr},
      {"sod", "Sod shock tube (gamma = 1.4), periodic x in [-1, 1), 1D/2D/3D; exact Riemann solution (Toro 2009)", 1,
       [] { return std::make_unique<SodShockTube<1>>(); }, [] { return std::make_unique<SodShockTube<2>>(); },
       [] { return std::make_unique<SodShockTube<3>>(); }},
      {"toy_star", "1D polytropic toy star in -Omega^2 x, breathing; exact ODE solution (Monaghan & Price 2004)", 1,
       [] { return std::make_unique<ToyStar>(); }, nullptr, nullptr},
      {"sedov", "2D Sedov-Taylor blast wave (gamma = 1.4), periodic box; self-similar solution (Sedov 1959)", 2,
       nullptr, [] { return std::make_unique<SedovBlast>(); }, nullptr},
      {"scene", "a scene file (-scene_file): shapes in YAML sampled at -nx, or particles in a .vtp file; 2D or 3D", 2,
       nullptr, [] { return std::make_unique<SceneCase<2>>(); }, [] { return std::make_unique<SceneCase<3>>(); },
       scene_file_dimension},
  };
  return entries;
}

const CaseEntry& find_case(const std::string& name) {
  std::string list;
  for (const auto& e : case_registry()) {
    if (e.name == name) return e;
    list += (list.empty() ? "" : ", ") + e.name;
  }
  throw Error("unknown case '" + name + "'; choose -case from: " + list);
}

int case_dimension(const std::string& name) {
  const CaseEntry& e = find_case(name);
  return e.input_dim ? e.input_dim() : e.default_dim;
}

template <int D> std::unique_ptr<Case<D>> create_case(const std::string& name) {
  const CaseEntry& e = find_case(name);
  std::function<std::unique_ptr<Case<D>>()> make;
  if constexpr (D == 1) make = e.make1;
  if constexpr (D == 2) make = e.make2;
  if constexpr (D == 3) make = e.make3;
  if (!make)
    throw Error("case '" + name + "' has no " + std::to_string(D) + "D form; use -dim " +
                std::to_string(e.default_dim));
  return make();
}

template std::unique_ptr<Case<1>> create_case<1>(const std::string&);
template std::unique_ptr<Case<2>> create_case<2>(const std::string&);
template std::unique_ptr<Case<3>> create_case<3>(const std::string&);

}  // namespace sph
