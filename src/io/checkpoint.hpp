#pragma once
// Checkpoints for restart, one self-checking file:
//
//   [every particle field in permanent-id order, PETSc binary vectors][header JSON][u64 length]["SPHCKPT1"]
//
// The vectors come from PETSc's binary viewer, so a checkpoint written on N ranks reads on M. The
// header (time, step, field names, the solver's scalars, the driver's record of the run) carries the
// size and a 64-bit FNV-1a checksum of the data before it: a changed byte, a truncated file or a
// header from another write is refused on read. Data and header live in one file, written to
// <path>.tmp, synced and renamed, so a crash at any point leaves the previous checkpoint or the new
// one, never a mix, and no temporary file survives a failed write.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "src/particles/particle_field.hpp"
#include "src/particles/particles.hpp"

namespace sph {

// A per-particle array to save.
using CheckpointField = ParticleField;

// The kind a checkpoint gives the slot of a particle taken out of the run (-box_exit remove): read
// back, such particles are to be removed again.
inline constexpr int kRemovedKind = -1;

template <int D> struct CheckpointState {
  double t = 0.0;
  long step = 0;
  nlohmann::json scalars = nlohmann::json::object();  // the solver's scalars
  nlohmann::json run = nlohmann::json::object();      // the driver's: identity, statistics, history
};

// Writes <path> (collective). Throws sph::Error naming the checkpoint when any part fails, after
// removing <path>.tmp; the previous <path> is then untouched. With `kept` > 1 the previous ones move
// along, <path> to <path>.1, <path>.1 to <path>.2, ..., up to <path>.<kept-1>, just before the new
// one is renamed into place (the moves are renames and a hard link: <path> never goes missing).
// The particles' carried fields (FieldUse kCarried) follow the Particles' own.
template <int D>
void write_checkpoint(const std::string& path, Particles<D>& P, const CheckpointState<D>& state, int kept = 1);

// The header of a checkpoint after checking its trailer and the data's checksum (collective: rank 0
// reads, every rank gets the header). Throws sph::Error naming the file and what is wrong with it.
nlohmann::json read_checkpoint_header(const std::string& path);

// Reads a checkpoint into particles already created as the run started (any split over ranks); those
// taken out of the run since come back with kind kRemovedKind, for the caller to remove. A carried
// field declared kOptional that the checkpoint lacks comes back zero.
// With open boundaries (`grows`) the checkpoint may hold particles made since the start (ids beyond
// the case's): rank 0 takes them.
// Throws sph::Error when the file is damaged or does not match the run (count, fields).
template <int D> CheckpointState<D> read_checkpoint(const std::string& path, Particles<D>& P, bool grows = false);

// Bytes of the field data at the start of a checkpoint file (what two runs' checkpoints share when
// they reached the same state), or 0 when the file has no valid trailer. Not collective.
std::size_t checkpoint_data_bytes(const std::string& path);

}  // namespace sph
