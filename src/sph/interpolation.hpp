#pragma once
// Field values at arbitrary points from fluid particles: Shepard-normalised kernel sums,
//   f(x) = sum_f f_f W(x - x_f) / sum_f W(x - x_f),
// reduced over all ranks. Brute force over particles: meant for a few hundred probe points.
#include <vector>

#include "src/kernels/kernel.hpp"
#include "src/particles/particles.hpp"

namespace sph {

template <int D>
std::vector<Vector<D>> shepard_velocity(const Particles<D>& P, const Kernel<D>& K, const std::vector<Vector<D>>& points) {
  const std::size_t n = points.size();
  std::vector<double> buf(n * (D + 1), 0.0);  // per point: sum W u (D values), sum W
  const double rc2 = K.support_radius() * K.support_radius();
  for (std::size_t k = 0; k < n; ++k) {
    double* b = &buf[k * (D + 1)];
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid) continue;
      const double r2 = (points[k] - P.x[i]).squaredNorm();
      if (r2 >= rc2) continue;
      const double w = K.W(std::sqrt(r2));
      for (int a = 0; a < D; ++a) b[a] += w * P.v[i][a];
      b[D] += w;
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  std::vector<Vector<D>> u(n, Vector<D>::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    const double* b = &buf[k * (D + 1)];
    if (b[D] > 0.0)
      for (int a = 0; a < D; ++a) u[k][a] = b[a] / b[D];
  }
  return u;
}

}  // namespace sph
