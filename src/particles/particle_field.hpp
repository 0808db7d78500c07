#pragma once
// Views of per-particle arrays. ParticleField: n_owned * components contiguous doubles, what
// checkpoints save and re-partitioning moves with the particles (the declared fields' views,
// field_registry.hpp). ScalarField: a frame's extra array.
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
