#include "src/run/memory_budget.hpp"

#include <mpi.h>
#include <petscsys.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "src/particles/particle_budget.hpp"

namespace sph {

namespace {

// A control group's memory limit (cgroup v2, then v1), or 0 when there is none.
double cgroup_limit_bytes() {
  for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    double bytes = 0;
    if (in >> bytes && bytes > 0) return bytes;  // "max" (no limit) fails to parse
  }
  return 0;
}

std::string gigabytes(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g GB", bytes / 1e9);
  return buf;
}

std::string per_particle(double bytes, const std::string& scheme) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.2g kB a particle (-solver %s, measured)", bytes / 1e3, scheme.c_str());
  return buf;
}

double ranks_on_node_share() {
  MPI_Comm node;
  MPI_Comm_split_type(PETSC_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int on_node = 1, all = 1;
  MPI_Comm_size(node, &on_node);
  MPI_Comm_free(&node);
  MPI_Comm_size(PETSC_COMM_WORLD, &all);
  return double(on_node) / double(all);
}

}  // namespace

double node_memory_bytes() {
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  const double group = cgroup_limit_bytes();
  return group > 0 ? std::min(physical, group) : physical;
}

MemoryBudgetScope::MemoryBudgetScope(double bytes_per_particle, const std::string& scheme, double planned_particles)
    : bytes_per_particle_(bytes_per_particle), memory_(node_memory_bytes()), scheme_(scheme) {
  // The scene is shared evenly among the ranks, so this node holds its ranks' share of it.
  const double planned_here = planned_particles * ranks_on_node_share(), need = planned_here * bytes_per_particle_;
  if (need > memory_) {
    char count[32];
    std::snprintf(count, sizeof count, "%.3g", planned_here);
    throw Error(std::string("the scene has at least ") + count + " particles on a node; at about " +
                per_particle(bytes_per_particle_, scheme_) + " they need " + gigabytes(need) + ", more than its " +
                gigabytes(memory_) + "; lower -nx, or spread the run over more nodes");
  }
  ParticleBudget& b = particle_budget();
  b.limit = static_cast<std::size_t>(memory_ / bytes_per_particle_);
  b.refusal = "the scene needs more than " + std::to_string(b.limit) + " particles; at about " +
              per_particle(bytes_per_particle_, scheme_) + " that is more than this machine's " + gigabytes(memory_) +
              "; lower -nx";
}

MemoryBudgetScope::~MemoryBudgetScope() { particle_budget() = ParticleBudget{}; }

void MemoryBudgetScope::check_scene(std::size_t n_owned) const {
  MPI_Comm node;
  MPI_Comm_split_type(PETSC_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  unsigned long long mine = n_owned, on_node = 0;
  MPI_Allreduce(&mine, &on_node, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, node);
  MPI_Comm_free(&node);
  // The fullest node decides, on every rank alike (nodes are taken to have the same memory).
  unsigned long long fullest = 0;
  MPI_Allreduce(&on_node, &fullest, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, PETSC_COMM_WORLD);
  const double need = double(fullest) * bytes_per_particle_;
  if (need > memory_)
    throw Error("the scene's " + std::to_string(fullest) + " particles on a node need about " + gigabytes(need) + " (" +
                per_particle(bytes_per_particle_, scheme_) + "), more than its " + gigabytes(memory_) +
                "; lower -nx, or spread the run over more nodes");
}

}  // namespace sph
