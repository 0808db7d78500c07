#pragma once
// A view of one per-particle array that a solver carries from step to step (n_owned * components
// contiguous doubles): what checkpoints save and what re-partitioning moves with the particles.
#include <string>
#include <vector>

namespace sph {

struct ParticleField {
  std::string name;
  double* data;
  int components;
};

// A per-particle scalar to read (frames' extra arrays).
struct ScalarField {
  std::string name;
  const std::vector<double>* values;  // at least one value per owned particle (ghost entries are ignored)
};

}  // namespace sph
