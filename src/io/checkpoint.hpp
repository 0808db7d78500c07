#pragma once
// Checkpoints for restart: every particle field in permanent-id order, written with PETSc's binary
// viewer (so a checkpoint written on N ranks can be read on M), plus a JSON header with the time,
// step, field names and whatever scalars the solver needs. Written to a temporary name and renamed,
// so the previous checkpoint survives a crash during writing.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "src/particles/particles.hpp"

namespace sph {

// A per-particle array to save: n_owned * components contiguous doubles.
struct CheckpointField {
  std::string name;
  double* data;
  int components;
};

template <int D> struct CheckpointState {
  double t = 0.0;
  long step = 0;
  nlohmann::json scalars = nlohmann::json::object();  // solver and driver scalars
};

// Writes <path> (binary) and <path>.json.
template <int D>
void write_checkpoint(const std::string& path, Particles<D>& P, const std::vector<CheckpointField>& extra,
                      const CheckpointState<D>& state);

// Reads a checkpoint into particles already created with the same global count (any split over ranks).
// Throws sph::Error when the file does not match the run (count, fields).
template <int D>
CheckpointState<D> read_checkpoint(const std::string& path, Particles<D>& P, const std::vector<CheckpointField>& extra);

}  // namespace sph
