#include "src/io/checkpoint.hpp"

#include <petscis.h>
#include <petscvec.h>
#include <petscviewer.h>

#include <cstdio>
#include <fstream>

#include "src/core/error.hpp"
#include "src/io/json_file.hpp"

namespace sph {

namespace {

// The Particles fields themselves, as checkpoint fields (kind stored as doubles).
template <int D> std::vector<CheckpointField> particle_fields(Particles<D>& P, std::vector<double>& kind) {
  double* x = P.x.empty() ? nullptr : P.x[0].data();
  double* v = P.v.empty() ? nullptr : P.v[0].data();
  return {{"x", x, D}, {"v", v, D}, {"m", P.m.data(), 1}, {"rho", P.rho.data(), 1}, {"p", P.p.data(), 1},
          {"kind", kind.data(), 1}};
}

// This rank's share of the id range in the file's vectors (whole particles, so blocks stay whole).
template <int D> PetscInt id_share(const Particles<D>& P) {
  PetscInt local = PETSC_DECIDE, total = static_cast<PetscInt>(P.n_global);
  SPH_PETSC(PetscSplitOwnership(PETSC_COMM_WORLD, &local, &total));
  return local;
}

// Moves a field between this rank's particles and a global vector ordered by permanent particle id
// (entry id * components + c), whichever rank holds the particle: what makes a checkpoint readable on
// another rank count and independent of how the particles were partitioned.
template <int D>
void transfer(::Vec global, const Particles<D>& P, double* data, int components, bool to_global) {
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

}  // namespace

template <int D>
void write_checkpoint(const std::string& path, Particles<D>& P, const std::vector<CheckpointField>& extra,
                      const CheckpointState<D>& state) {
  std::vector<double> kind(P.kind.begin(), P.kind.begin() + P.n_owned);
  std::vector<CheckpointField> fields = particle_fields(P, kind);
  fields.insert(fields.end(), extra.begin(), extra.end());
  const std::string tmp = path + ".tmp";
  PetscViewer viewer = open_viewer(tmp, FILE_MODE_WRITE);
  nlohmann::json header{{"t", state.t}, {"step", state.step}, {"n_global", P.n_global}, {"dim", D},
                        {"scalars", state.scalars}, {"fields", nlohmann::json::array()}};
  for (const CheckpointField& f : fields) {
    ::Vec vec;
    SPH_PETSC(VecCreateMPI(PETSC_COMM_WORLD, id_share(P) * f.components, PETSC_DETERMINE, &vec));
    SPH_PETSC(VecSetBlockSize(vec, f.components));
    transfer(vec, P, f.data, f.components, true);
    SPH_PETSC(VecView(vec, viewer));
    SPH_PETSC(VecDestroy(&vec));
    header["fields"].push_back({{"name", f.name}, {"components", f.components}});
  }
  SPH_PETSC(PetscViewerDestroy(&viewer));
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) {
    if (std::rename(tmp.c_str(), path.c_str()) != 0) throw Error("cannot write checkpoint " + path);
  }
  write_json_file(path + ".json", header);
}

template <int D>
CheckpointState<D> read_checkpoint(const std::string& path, Particles<D>& P, const std::vector<CheckpointField>& extra) {
  nlohmann::json header;
  {
    std::ifstream in(path + ".json");
    if (!in) throw Error("cannot read checkpoint header " + path + ".json; check the -restart path");
    try {
      in >> header;
    } catch (const std::exception&) {
      throw Error("checkpoint header " + path + ".json is not valid JSON");
    }
  }
  if (header.value("dim", 0) != D || header.value("n_global", -1L) != static_cast<long>(P.n_global))
    throw Error("checkpoint " + path + " holds " + std::to_string(header.value("n_global", -1L)) + " particles in " +
                std::to_string(header.value("dim", 0)) + "D, this run has " + std::to_string(P.n_global) + " in " +
                std::to_string(D) + "D; restart with the options of the run that wrote it");
  std::vector<double> kind(P.n_owned);
  std::vector<CheckpointField> fields = particle_fields(P, kind);
  fields.insert(fields.end(), extra.begin(), extra.end());
  if (header["fields"].size() != fields.size())
    throw Error("checkpoint " + path + " was written by another solver (field count differs); restart with the same -solver");
  PetscViewer viewer = open_viewer(path, FILE_MODE_READ);
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const CheckpointField& f = fields[k];
    if (header["fields"][k]["name"] != f.name)
      throw Error("checkpoint " + path + " field " + std::to_string(k) + " is '" +
                  header["fields"][k]["name"].get<std::string>() + "', expected '" + f.name + "'");
    ::Vec vec;
    SPH_PETSC(VecCreate(PETSC_COMM_WORLD, &vec));
    SPH_PETSC(VecSetSizes(vec, id_share(P) * f.components, PETSC_DETERMINE));
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
  return state;
}

template void write_checkpoint<1>(const std::string&, Particles<1>&, const std::vector<CheckpointField>&,
                                  const CheckpointState<1>&);
template void write_checkpoint<2>(const std::string&, Particles<2>&, const std::vector<CheckpointField>&,
                                  const CheckpointState<2>&);
template void write_checkpoint<3>(const std::string&, Particles<3>&, const std::vector<CheckpointField>&,
                                  const CheckpointState<3>&);
template CheckpointState<1> read_checkpoint<1>(const std::string&, Particles<1>&, const std::vector<CheckpointField>&);
template CheckpointState<2> read_checkpoint<2>(const std::string&, Particles<2>&, const std::vector<CheckpointField>&);
template CheckpointState<3> read_checkpoint<3>(const std::string&, Particles<3>&, const std::vector<CheckpointField>&);

}  // namespace sph
