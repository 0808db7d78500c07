#pragma once
// Explicit time-step limits shared by the solvers (Morris, Fox & Zhu 1997; Monaghan 1992). The
// CFL numbers are each solver's own option (-cfl), since they bound different speeds.
namespace sph {

// Viscous diffusion: dt <= kViscousStepFactor h^2 / nu.
constexpr double kViscousStepFactor = 0.125;
// Body and pair forces: dt <= kForceStepFactor sqrt(h / max |a|).
constexpr double kForceStepFactor = 0.25;

}  // namespace sph
