#include "cases/still_water/still_water.hpp"

#include <algorithm>
#include <cmath>

#include "cases/common/lattice.hpp"
#include "cases/common/wall_options.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* nx, PetscInt* layers, PetscReal* width, PetscReal* depth, PetscReal* g,
                            PetscReal* re, PetscReal* rho0) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Still water (-case still_water)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Particles per unit length", *nx, nx, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, "-tank_width", "Tank width L (its depth too, in 3D)", *width, width, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-depth", "Water depth H", *depth, depth, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-g", "Gravity", *g, g, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-re", "Reynolds number sqrt(g H) H / nu", *re, re, nullptr));
  PetscCall(read_wall_scene_options(PetscOptionsObject, layers, rho0));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

template <int D> void StillWater<D>::set_from_options() {
  SPH_PETSC(read_options(&nx_, &wall_layers_, &width_, &depth_, &g_, &re_, &rho0_));
  require(nx_ >= 4, "-nx", "at least 4", nx_);
  require(width_ > 0, "-tank_width", "positive", width_);
  require(depth_ > 0, "-depth", "positive", depth_);
  require(g_ > 0, "-g", "positive", g_);
  require(re_ > 0, "-re", "positive", re_);
  check_wall_scene_options(wall_layers_, rho0_);
  require(std::lround(width_ * nx_) >= 4 && std::lround(depth_ * nx_) >= 4, "-nx",
          "at least 4 particles across the tank and the depth", nx_);
}

template <int D> Physics<D> StillWater<D>::physics() const {
  Physics<D> phys;
  phys.rho0 = rho0_;
  phys.nu = std::sqrt(g_ * depth_) * depth_ / re_;
  phys.U = std::sqrt(2.0 * g_ * depth_);  // free fall over the depth: the scale of any motion
  phys.gravity = Vector<D>::Zero();
  phys.gravity[1] = -g_;
  phys.free_surface = true;
  return phys;
}

template <int D> Particles<D> StillWater<D>::lattice() const {
  const double dx = spacing();
  double mass = rho0_;
  for (int d = 0; d < D; ++d) mass *= dx;
  const int L = static_cast<int>(wall_layers_), n = static_cast<int>(std::lround(width_ * nx_));
  const int rows = static_cast<int>(std::lround(depth_ * nx_)), height = rows + rows / 2 + 1;  // walls above the water
  Particles<D> all;
  const int depth_lo = D == 3 ? -L : 0, depth_hi = D == 3 ? n + L : 1;
  for (int k = depth_lo; k < depth_hi; ++k)
    for (int j = -L; j < height; ++j)
      for (int i = -L; i < n + L; ++i) {
        Vector<D> x;
        x[0] = (i + 0.5) * dx, x[1] = (j + 0.5) * dx;
        if constexpr (D == 3) x[2] = (k + 0.5) * dx;
        const bool wall = j < 0 || i < 0 || i >= n || k < 0 || (D == 3 && k >= n);
        const bool fluid = !wall && j < rows;
        if (!wall && !fluid) continue;
        const double p = fluid ? rho0_ * g_ * (depth_ - x[1]) : 0.0;
        all.add(x, Vector<D>::Zero(), mass, rho0_, p, wall ? kWall : kFluid);
      }
  return all;
}

template <int D> void StillWater<D>::create(Particles<D>& P, Domain<D>& domain) const {
  const double dx = spacing();
  const int L = static_cast<int>(wall_layers_);
  domain.lo = Vector<D>::Constant(-L * dx);
  domain.hi = Vector<D>::Constant(width_ + L * dx);
  domain.hi[1] = 20.0 * depth_;  // open top
  domain.periodic.fill(false);
  P = rank_share(lattice());
}

template <int D> std::map<std::string, double> StillWater<D>::errors(const Particles<D>& P, double) const {
  if (start_.empty()) {
    const Particles<D> all = lattice();
    start_ = all.x;
    double top = -1e300;
    for (std::size_t i = 0; i < all.n_owned; ++i)
      if (all.kind[i] == kFluid) top = std::max(top, all.x[i][1]);
    top_.assign(all.n_owned, 0);
    for (std::size_t i = 0; i < all.n_owned; ++i)
      top_[i] = all.kind[i] == kFluid && all.x[i][1] > top - 0.5 * spacing();
  }
  const double dx = spacing(), scale = rho0_ * g_ * depth_;
  double sums[4] = {0.0, 0.0, 0.0, 0.0};  // |p error|, fluid count, top heights, top count
  double drift = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] != kFluid) continue;
    const std::size_t label = static_cast<std::size_t>(P.id[i]);
    sums[0] += std::abs(P.p[i] - rho0_ * g_ * (depth_ - P.x[i][1])), sums[1] += 1.0;
    if (top_[label]) sums[2] += P.x[i][1] + 0.5 * dx, sums[3] += 1.0;
    drift = std::max(drift, (P.x[i] - start_[label]).norm());
  }
  MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &drift, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return {{"hydrostatic_l1_rel", sums[0] / sums[1] / scale},
          {"max_drift_dx", drift / dx},
          {"level_rel", sums[2] / sums[3] / depth_ - 1.0}};
}

template <int D> nlohmann::json StillWater<D>::parameters() const {
  return {{"nx", nx_},     {"tank_width", width_},       {"depth", depth_}, {"g", g_}, {"re", re_},
          {"rho0", rho0_}, {"wall_layers", wall_layers_}};
}

template class StillWater<2>;
template class StillWater<3>;

}  // namespace sph
