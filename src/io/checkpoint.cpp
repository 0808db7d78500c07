#include "src/io/checkpoint.hpp"

#include <petscis.h>
#include <petscvec.h>
#include <petscviewer.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "src/core/collective.hpp"
#include "src/core/error.hpp"
#include "src/io/json_file.hpp"
#include "src/io/output_dir.hpp"
#include "src/particles/global_indices.hpp"

namespace sph {

namespace {

// The Particles fields themselves (kind stored as doubles), then the schemes' carried fields.
template <int D> std::vector<CheckpointField> particle_fields(Particles<D>& P, std::vector<double>& kind) {
  double* x = P.x.empty() ? nullptr : P.x[0].data();
  double* v = P.v.empty() ? nullptr : P.v[0].data();
  std::vector<CheckpointField> fields{{"x", x, D},          {"v", v, D},
                                      {"m", P.m.data(), 1}, {"rho", P.rho.data(), 1},
                                      {"p", P.p.data(), 1}, {"kind", kind.data(), 1}};
  for (const CheckpointField& f : P.fields.with(kCarried, P.n_owned)) fields.push_back(f);
  return fields;
}

// This rank's share of the id range in the file's vectors (whole particles, so blocks stay whole).
PetscInt id_share(PetscInt ids) {
  PetscInt local = PETSC_DECIDE, total = ids;
  SPH_PETSC(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &total));
  return local;
}

// The file's vectors hold a slot per permanent id, 0 to the largest + 1: the run's particles, and
// those taken out of it (-box_exit remove), whose slots keep kind -1 (kRemovedKind).
template <int D> PetscInt id_count(const Particles<D>& P) {
  GlobalIndex largest = -1;
  for (std::size_t i = 0; i < P.n_owned; ++i) largest = std::max(largest, P.id[i]);
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD);
  return static_cast<PetscInt>(largest + 1);
}

// Moves a field between this rank's particles and a global vector ordered by permanent particle id
// (entry id * components + c), whichever rank holds the particle: what makes a checkpoint readable on
// another rank count and independent of how the particles were partitioned.
template <int D> void transfer(::Vec global, const Particles<D>& P, double* data, int components, bool to_global) {
  const PetscInt n = static_cast<PetscInt>(P.n_owned) * components;
  std::vector<PetscInt> where(n);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    for (int c = 0; c < components; ++c) where[i * components + c] = static_cast<PetscInt>(P.id[i]) * components + c;
  ::Vec local;
  IS is;
  VecScatter scatter;
  SPH_PETSC(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, data, &local));
  SPH_PETSC(ISCreateGeneral(PETSC_COMM_SELF, n, where.data(), PETSC_USE_POINTER, &is));
  SPH_PETSC(VecScatterCreate(local, nullptr, global, is, &scatter));
  const ScatterMode mode = to_global ? SCATTER_FORWARD : SCATTER_REVERSE;
  ::Vec from = to_global ? local : global, to = to_global ? global : local;
  SPH_PETSC(VecScatterBegin(scatter, from, to, INSERT_VALUES, mode));
  SPH_PETSC(VecScatterEnd(scatter, from, to, INSERT_VALUES, mode));
  SPH_PETSC(VecScatterDestroy(&scatter));
  SPH_PETSC(ISDestroy(&is));
  SPH_PETSC(VecDestroy(&local));
}

// Slots for the ids from P.n_global to ids - 1 (particles an inlet made), on rank 0: the checkpoint
// fills those it holds, and the others come back kRemovedKind.
template <int D> void add_slots(Particles<D>& P, long ids) {
  P.set_ghost_count(0);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
    for (long id = static_cast<long>(P.n_global); id < ids; ++id) {
      P.add(Vector<D>::Zero(), Vector<D>::Zero(), 0.0, 1.0);
      P.id.back() = static_cast<GlobalIndex>(id);
    }
  assign_global_indices(P);
}

PetscViewer open_viewer(const std::string& path, PetscFileMode mode) {
  PetscViewer viewer;
  SPH_PETSC(PetscViewerCreate(PETSC_COMM_WORLD, &viewer));
  SPH_PETSC(PetscViewerSetType(viewer, PETSCVIEWERBINARY));
  SPH_PETSC(PetscViewerBinarySetSkipInfo(viewer, PETSC_TRUE));
  SPH_PETSC(PetscViewerFileSetMode(viewer, mode));
  if (mode == FILE_MODE_READ) {
    std::ifstream probe(path);
    if (!probe) throw Error("cannot read checkpoint " + path + "; check the -restart path");
  }
  SPH_PETSC(PetscViewerFileSetName(viewer, path.c_str()));
  return viewer;
}

PetscMPIInt world_rank() {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

constexpr char kMagic[8] = {'S', 'P', 'H', 'C', 'K', 'P', 'T', '1'};
constexpr std::size_t kTrailer = 24;  // u64 header length, u64 header checksum, magic
constexpr std::uint64_t kFnvStart = 1469598103934665603ull;

std::uint64_t fnv1a(std::uint64_t h, const unsigned char* p, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k) h = (h ^ p[k]) * 1099511628211ull;
  return h;
}
std::uint64_t fnv1a(const std::string& s) {
  return fnv1a(kFnvStart, reinterpret_cast<const unsigned char*>(s.data()), s.size());
}

// 64-bit FNV-1a over the first `bytes` bytes of an open file; false if they cannot all be read.
bool checksum(std::FILE* f, std::uint64_t bytes, std::uint64_t* hash) {
  std::uint64_t h = kFnvStart;
  std::vector<unsigned char> buf(1 << 20);
  std::rewind(f);
  while (bytes > 0) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(bytes, buf.size()));
    if (std::fread(buf.data(), 1, want, f) != want) return false;
    h = fnv1a(h, buf.data(), want);
    bytes -= want;
  }
  *hash = h;
  return true;
}

void put_u64(unsigned char* out, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) out[k] = static_cast<unsigned char>(v >> (8 * k));  // little-endian
}
std::uint64_t get_u64(const unsigned char* in) {
  std::uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v |= static_cast<std::uint64_t>(in[k]) << (8 * k);
  return v;
}

// Fault injection for the crash tests: SPH_FAULT_CHECKPOINT="<stage>:<n>" acts at that stage of the
// process's n-th checkpoint write. Stages that kill the process (as a power cut would): data (vectors
// written, no trailer yet), trailer (complete temporary file, not yet renamed), renamed. Stage full:
// the trailer's write fails with ENOSPC, as on a full disk.
bool fault_at(const char* stage, int write_number) {
  const char* spec = std::getenv("SPH_FAULT_CHECKPOINT");
  if (!spec) return false;
  const std::string s = spec;
  const auto colon = s.find(':');
  return colon != std::string::npos && s.substr(0, colon) == stage && std::atoi(s.c_str() + colon + 1) == write_number;
}
void fault_point(const char* stage, int write_number) {
  if (fault_at(stage, write_number)) std::raise(SIGKILL);
}

// Moves the older checkpoints along to make room for a new <path>: <path>.<k> to <path>.<k+1>, the
// oldest dropped, and <path> linked as <path>.1, so <path> itself stays until the new one replaces it.
// Only the chain that exists moves (up to the first missing number): the cost follows the files on
// disk, not -checkpoints_kept.
std::string keep_older(const std::string& path, int kept) {
  if (kept <= 1) return "";
  auto older = [&path](int k) { return path + "." + std::to_string(k); };
  int last = 0;  // <path>.1 ... <path>.<last> exist
  while (last < kept - 1 && access(older(last + 1).c_str(), F_OK) == 0) ++last;
  if (last == kept - 1) std::remove(older(last--).c_str());
  for (int k = last; k >= 1; --k) {
    note_output(older(k + 1));
    if (std::rename(older(k).c_str(), older(k + 1).c_str()) != 0 && errno != ENOENT)
      return "cannot move " + older(k) + " to " + older(k + 1) + " (" + std::strerror(errno) + ")";
  }
  note_output(older(1));
  if (link(path.c_str(), older(1).c_str()) != 0 && errno != ENOENT)
    return "cannot keep " + path + " as " + older(1) + " (" + std::strerror(errno) + ")";
  return "";
}

// PETSc's binary writer reports a failed write by its byte counts alone ("Error writing to file total
// size ..."); the file system tells whether it was full. Called before the partial file is removed, so
// a full disk has (next to) nothing left.
std::string full_disk(const std::string& tmp) {
  constexpr std::uintmax_t kFull = 1 << 20;  // bytes: less than a checkpoint of a few thousand particles
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::path(tmp).parent_path();
  const std::filesystem::space_info space = std::filesystem::space(dir.empty() ? "." : dir, ec);
  if (ec || space.available >= kFull) return "";
  return std::string(std::strerror(ENOSPC)) + " (" + std::to_string(space.available / 1024) + " kB left)";
}

// Appends header + trailer to the data in `tmp`, syncs it and renames it over `path` (after moving
// the older ones along). Rank 0 only; returns an error message, empty on success.
std::string seal(const std::string& tmp, const std::string& path, nlohmann::json header, int write_number, int kept) {
  std::FILE* f = std::fopen(tmp.c_str(), "r+b");
  if (!f) return "cannot reopen " + tmp + " (" + std::strerror(errno) + ")";
  std::fseek(f, 0, SEEK_END);
  const std::uint64_t data_bytes = static_cast<std::uint64_t>(std::ftell(f));
  std::uint64_t hash = 0;
  if (!checksum(f, data_bytes, &hash)) {
    std::fclose(f);
    return "cannot read back " + tmp;
  }
  fault_point("data", write_number);
  header["data_bytes"] = data_bytes;
  header["data_checksum"] = hash;
  const std::string text = header.dump();
  unsigned char tail[kTrailer];
  put_u64(tail, text.size());
  put_u64(tail + 8, fnv1a(text));
  std::memcpy(tail + 16, kMagic, 8);
  std::fseek(f, 0, SEEK_END);
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size() &&
            std::fwrite(tail, 1, kTrailer, f) == kTrailer && std::fflush(f) == 0 && fsync(fileno(f)) == 0;
  int write_errno = errno;
  if (fault_at("full", write_number)) ok = false, write_errno = ENOSPC;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) return std::strerror(write_errno);
  fault_point("trailer", write_number);
  if (const std::string moved = keep_older(path, kept); !moved.empty()) return moved;
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    return std::string("renaming the temporary file failed (") + std::strerror(errno) + ")";
  fault_point("renamed", write_number);
  return "";
}

// Reads and checks the header of `path`. Rank 0 only; returns an error message, empty on success.
std::string unseal(const std::string& path, std::string* header_text) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return "-restart " + path + " is a folder; give its checkpoint file (" +
           (std::filesystem::path(path) / "checkpoint.bin").string() + ")";
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return "cannot read checkpoint " + path + "; check the -restart path";
  const std::string broken = "checkpoint " + path + " is damaged or incomplete";
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  unsigned char tail[kTrailer];
  std::string err;
  if (size < static_cast<long>(kTrailer) || std::fseek(f, size - static_cast<long>(kTrailer), SEEK_SET) != 0 ||
      std::fread(tail, 1, kTrailer, f) != kTrailer || std::memcmp(tail + 16, kMagic, 8) != 0) {
    std::fclose(f);
    return broken +
           " (no header at its end: truncated, or written by an older version); start a new run or "
           "restart from another checkpoint";
  }
  const std::uint64_t len = get_u64(tail);
  if (len > static_cast<std::uint64_t>(size) - kTrailer) {
    std::fclose(f);
    return broken + " (header length out of range)";
  }
  const std::uint64_t data_bytes = static_cast<std::uint64_t>(size) - kTrailer - len;
  header_text->assign(len, '\0');
  std::fseek(f, static_cast<long>(data_bytes), SEEK_SET);
  if (std::fread(header_text->data(), 1, len, f) != len) err = broken + " (header unreadable)";
  else if (fnv1a(*header_text) != get_u64(tail + 8))
    err = "checkpoint " + path +
          " fails its header checksum (the header was changed after it was written); "
          "restart from another checkpoint or start a new run";
  nlohmann::json header;
  if (err.empty()) {
    header = nlohmann::json::parse(*header_text, nullptr, false);
    if (header.is_discarded() || !header.is_object() || !header.contains("data_checksum"))
      err = broken + " (header is not valid)";
  }
  std::uint64_t hash = 0;
  if (err.empty() && (header.value("data_bytes", std::uint64_t(0)) != data_bytes || !checksum(f, data_bytes, &hash) ||
                      header["data_checksum"].get<std::uint64_t>() != hash))
    err = "checkpoint " + path +
          " fails its checksum (the data was changed or damaged after it was written); "
          "restart from another checkpoint or start a new run";
  std::fclose(f);
  return err;
}

}  // namespace

template <int D>
void write_checkpoint(const std::string& path, Particles<D>& P, const CheckpointState<D>& state, int kept) {
  static int writes = 0;
  ++writes;
  std::vector<double> kind(P.kind.begin(), P.kind.begin() + P.n_owned);
  std::vector<CheckpointField> fields = particle_fields(P, kind);
  const std::string tmp = path + ".tmp";
  const bool root = world_rank() == 0;
  if (root) note_output(path);
  nlohmann::json header{{"format", "sph checkpoint 1"}, {"t", state.t},         {"step", state.step},
                        {"n_global", P.n_global},       {"n_ids", id_count(P)}, {"dim", D},
                        {"scalars", state.scalars},     {"run", state.run},     {"fields", nlohmann::json::array()}};
  std::string error;
  try {
    PetscViewer viewer = open_viewer(tmp, FILE_MODE_WRITE);
    const PetscInt ids = header["n_ids"].get<PetscInt>();
    for (const CheckpointField& f : fields) {
      ::Vec vec;
      SPH_PETSC(VecCreateMPI(PETSC_COMM_WORLD, id_share(ids) * f.components, PETSC_DETERMINE, &vec));
      SPH_PETSC(VecSetBlockSize(vec, f.components));
      SPH_PETSC(VecSet(vec, f.name == "kind" ? double(kRemovedKind) : 0.0));
      transfer(vec, P, f.data, f.components, true);
      SPH_PETSC(VecView(vec, viewer));
      SPH_PETSC(VecDestroy(&vec));
      header["fields"].push_back({{"name", f.name}, {"components", f.components}});
    }
    SPH_PETSC(PetscViewerDestroy(&viewer));
  } catch (const Error& e) {
    error = e.what();
    if (const std::string full = root ? full_disk(tmp) : ""; !full.empty()) error = full;
  }
  if (root && error.empty()) error = seal(tmp, path, header, writes, kept);
  broadcast_from_root(error);
  if (!error.empty()) {
    if (root) std::remove(tmp.c_str());
    throw Error("writing checkpoint " + path + " failed: " + error +
                "; free disk space or choose another -output_dir (the previous checkpoint is kept)");
  }
}

nlohmann::json read_checkpoint_header(const std::string& path) {
  std::string text, error;
  if (world_rank() == 0) error = unseal(path, &text);
  throw_if_root_failed(error);
  broadcast_from_root(text);
  return nlohmann::json::parse(text);
}

template <int D> CheckpointState<D> read_checkpoint(const std::string& path, Particles<D>& P, bool grows) {
  const nlohmann::json header = read_checkpoint_header(path);
  // The case lays out every particle the run started with; those it took out since are removed after.
  const long ids = header.value("n_ids", header.value("n_global", -1L));
  if (grows && header.value("dim", 0) == D && ids > static_cast<long>(P.n_global)) add_slots(P, ids);
  if (header.value("dim", 0) != D || ids != static_cast<long>(P.n_global))
    throw Error("checkpoint " + path + " holds " + std::to_string(ids) + " particles in " +
                std::to_string(header.value("dim", 0)) + "D, this run has " + std::to_string(P.n_global) + " in " +
                std::to_string(D) + "D; restart with the options of the run that wrote it");
  std::vector<double> kind(P.n_owned);
  std::vector<CheckpointField> fields = particle_fields(P, kind);
  // A field a checkpoint may lack (kOptional) that this one lacks is zero.
  for (const ParticleField& f : P.fields.with(kOptional, P.n_owned)) {
    const nlohmann::json& saved = header["fields"];
    if (std::any_of(saved.begin(), saved.end(), [&](const nlohmann::json& s) { return s.value("name", "") == f.name; }))
      continue;
    std::fill(f.data, f.data + P.n_owned * f.components, 0.0);
    fields.erase(
        std::find_if(fields.begin(), fields.end(), [&](const CheckpointField& c) { return c.name == f.name; }));
  }
  if (header["fields"].size() != fields.size())
    throw Error("checkpoint " + path +
                " was written by another solver (field count differs); restart with the same -solver");
  PetscViewer viewer = open_viewer(path, FILE_MODE_READ);
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const CheckpointField& f = fields[k];
    if (header["fields"][k]["name"] != f.name)
      throw Error("checkpoint " + path + " field " + std::to_string(k) + " is '" +
                  header["fields"][k]["name"].get<std::string>() + "', expected '" + f.name + "'");
    ::Vec vec;
    SPH_PETSC(VecCreate(PETSC_COMM_WORLD, &vec));
    SPH_PETSC(VecSetSizes(vec, id_share(static_cast<PetscInt>(ids)) * f.components, PETSC_DETERMINE));
    SPH_PETSC(VecSetBlockSize(vec, f.components));
    SPH_PETSC(VecSetType(vec, VECMPI));
    SPH_PETSC(VecLoad(vec, viewer));
    transfer(vec, P, f.data, f.components, false);
    SPH_PETSC(VecDestroy(&vec));
  }
  SPH_PETSC(PetscViewerDestroy(&viewer));
  for (std::size_t i = 0; i < P.n_owned; ++i) P.kind[i] = static_cast<int>(kind[i]);
  CheckpointState<D> state;
  state.t = header["t"];
  state.step = header["step"];
  state.scalars = header["scalars"];
  state.run = header.value("run", nlohmann::json::object());
  return state;
}

std::size_t checkpoint_data_bytes(const std::string& path) {
  std::string text;
  if (!unseal(path, &text).empty()) return 0;
  return nlohmann::json::parse(text).value("data_bytes", std::size_t(0));
}

template void write_checkpoint<1>(const std::string&, Particles<1>&, const CheckpointState<1>&, int);
template void write_checkpoint<2>(const std::string&, Particles<2>&, const CheckpointState<2>&, int);
template void write_checkpoint<3>(const std::string&, Particles<3>&, const CheckpointState<3>&, int);
template CheckpointState<1> read_checkpoint<1>(const std::string&, Particles<1>&, bool);
template CheckpointState<2> read_checkpoint<2>(const std::string&, Particles<2>&, bool);
template CheckpointState<3> read_checkpoint<3>(const std::string&, Particles<3>&, bool);

}  // namespace sph
