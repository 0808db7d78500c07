#pragma once
// Pressure probes: the pressure at fixed points, each a column probe_<name>_p of timeseries.csv. A
// probe reads the kernel-weighted (Shepard) mean of the pressure of the particles within the kernel's
// reach: the fluid's, and the walls' and inlets', which is the fluid's pressure carried into them, so
// a probe on a wall's face reads what a pressure transducer set flush in the wall reads. A probe no
// particle reaches reads 0, the pressure of the air above a free surface (a dry transducer).
#include <petscsys.h>

#include <cmath>
#include <string>
#include <vector>

#include "src/core/domain.hpp"
#include "src/kernels/kernel.hpp"
#include "src/particles/particles.hpp"

namespace sph {

template <int D> struct Probe {
  std::string name;
  Vector<D> at = Vector<D>::Zero();
};

// The column names, in the probes' order.
template <int D> std::vector<std::string> probe_columns(const std::vector<Probe<D>>& probes) {
  std::vector<std::string> columns;
  for (const Probe<D>& p : probes) columns.push_back("probe_" + p.name + "_p");
  return columns;
}

// Each probe's pressure, over all ranks. Brute force over the owned particles: a few probes cost a
// few distance evaluations per particle per step, far below a step's pair loops.
template <int D> std::vector<double> probe_pressures(const Particles<D>& P, const Domain<D>& domain, const Kernel<D>& K,
                                                     const std::vector<Probe<D>>& probes) {
  std::vector<double> sums(2 * probes.size(), 0.0);  // per probe: sum W p, sum W
  const double reach = K.support_radius();
  for (std::size_t k = 0; k < probes.size(); ++k)
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid && !extrapolates_pressure(P.kind[i])) continue;
      Vector<D> r = P.x[i] - probes[k].at;
      for (int a = 0; a < D; ++a)  // the nearest periodic image
        if (domain.periodic[a]) {
          const double L = domain.hi[a] - domain.lo[a];
          r[a] -= L * std::round(r[a] / L);
        }
      const double d = r.norm();
      if (d >= reach) continue;
      const double w = K.W(d);
      sums[2 * k] += w * P.p[i], sums[2 * k + 1] += w;
    }
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  std::vector<double> p(probes.size());
  for (std::size_t k = 0; k < probes.size(); ++k) p[k] = sums[2 * k + 1] > 0 ? sums[2 * k] / sums[2 * k + 1] : 0.0;
  return p;
}

}  // namespace sph
