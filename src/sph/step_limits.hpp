#pragma once
// Explicit time-step limits shared by the solvers (Morris, Fox & Zhu 1997; Monaghan 1992), and the
// names of the Courant numbers each solver reads as its own option.
#include <string>

#include "src/core/options.hpp"

namespace sph {

// Viscous diffusion: dt <= kViscousStepFactor h^2 / nu.
constexpr double kViscousStepFactor = 0.125;
// Body and pair forces: dt <= kForceStepFactor sqrt(h / max |a|).
constexpr double kForceStepFactor = 0.25;

// One name per Courant number, so that a command line compared across schemes says which speed it
// bounds: -cfl on the flow speed (ISPH: dt <= cfl h / U), -acoustic_cfl on the sound or signal speed
// plus the flow's (the explicit schemes: dt <= acoustic_cfl h / (c + |u|)).
inline constexpr const char* kAdvectiveCfl = "-cfl";
inline constexpr const char* kAcousticCfl = "-acoustic_cfl";

// For an explicit scheme: the advective name given to it, told the acoustic one (check_unused_options).
inline RenamedOption acoustic_cfl_rename(const std::string& option) {
  if (option != std::string(kAdvectiveCfl).substr(1)) return {};
  return {std::string(kAcousticCfl).substr(1),
          "the explicit schemes' step is set by the acoustic Courant number; -cfl is ISPH's advective one"};
}

}  // namespace sph
