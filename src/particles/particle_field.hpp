#pragma once
// A view of one per-particle array that a solver carries from step to step (n_owned * components
// contiguous doubles): what checkpoints save and what re-partitioning moves with the particles.
#include <string>

namespace sph {

struct ParticleField {
  std::string name;
  double* data;
  int components;
};

}  // namespace sph
