#pragma once
// Where the kinetic energy E = sum_i 1/2 m_i |u_i|^2 of the owned fluid particles goes, by cause,
// summed over a run's steps. A velocity update u -> u + d, d = sum_k d_k, changes E by exactly
// sum_i m_i (u_i + d_i / 2) . d_i, and each cause k is credited with its share, sum_i m_i
// (u_i + d_i / 2) . d_k,i; the shares add up to the change. A solver reports the budget in
// summary.json (conservation.energy_budget), the tool that split ISPH's decay-rate error into the
// viscous term's and shifting's parts (docs/verification/taylor_green.md, "What limits ISPH's order").
#include <petscsys.h>

#include <array>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <tuple>
#include <utility>
#include <vector>

#include "src/particles/particles.hpp"

namespace sph {

enum class EnergyCause { Viscous, Pressure, BodyForce, Shifting };

class EnergyBudget {
 public:
  static constexpr int kCauses = 4;

  // The kinetic energy of the owned fluid particles with velocities u (this rank's part).
  template <int D> static double kinetic_energy(const Particles<D>& P, const std::vector<Vector<D>>& u) {
    double e = 0.0;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kFluid) e += 0.5 * P.m[i] * u[i].squaredNorm();
    return e;
  }

  // The energy at the start of the budget (the first call counts).
  template <int D> void start(const Particles<D>& P) {
    if (!started_) start_ = kinetic_energy(P, P.v), started_ = true;
  }

  // Credits the update u -> u + sum_k scale_k a_k to the causes of the parts (cause, scale, a).
  template <int D>
  void add_update(const Particles<D>& P, const std::vector<Vector<D>>& u,
                  std::initializer_list<std::tuple<EnergyCause, double, const std::vector<Vector<D>>*>> parts) {
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid) continue;
      Vector<D> d = Vector<D>::Zero();
      for (const auto& [cause, scale, a] : parts) d += scale * (*a)[i];
      const Vector<D> mid = u[i] + 0.5 * d;
      for (const auto& [cause, scale, a] : parts) change_[static_cast<int>(cause)] += P.m[i] * mid.dot(scale * (*a)[i]);
    }
  }

  // Credits a change measured as the difference of two energies (this rank's parts) to one cause.
  void add_change(EnergyCause cause, double before, double after) {
    change_[static_cast<int>(cause)] += after - before;
  }

  // Reduced over the ranks (collective), with the energies at the start and now.
  template <int D> nlohmann::json describe(const Particles<D>& P) const {
    std::array<double, kCauses + 2> sum{};
    for (int k = 0; k < kCauses; ++k) sum[k] = change_[k];
    sum[kCauses] = start_, sum[kCauses + 1] = kinetic_energy(P, P.v);
    MPI_Allreduce(MPI_IN_PLACE, sum.data(), kCauses + 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    return {{"kinetic_energy_start", sum[kCauses]},
            {"kinetic_energy_end", sum[kCauses + 1]},
            {"viscous", sum[0]},
            {"pressure", sum[1]},
            {"body_force", sum[2]},
            {"shifting", sum[3]}};
  }

 private:
  std::array<double, kCauses> change_{};
  double start_ = 0.0;
  bool started_ = false;
};

}  // namespace sph
