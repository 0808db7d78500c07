#pragma once
// File work done by rank 0 alone (checkpoints, output directories) must end the same way on every
// rank: these share rank 0's text and turn its error into the same sph::Error everywhere.
#include <string>

namespace sph {

// Replaces `text` on every rank by rank 0's. Collective on PETSC_COMM_WORLD.
void broadcast_from_root(std::string& text);

// Throws sph::Error(rank 0's message) on every rank when rank 0's `error` is not empty. Collective.
void throw_if_root_failed(std::string error);

}  // namespace sph
