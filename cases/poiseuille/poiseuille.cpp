#include "cases/poiseuille/poiseuille.hpp"

#include <cmath>

#include "cases/common/lattice.hpp"
#include "cases/common/wall_options.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* ny, PetscInt* layers, PetscReal* re, PetscReal* U, PetscReal* rho0) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Poiseuille channel flow (-case poiseuille)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Fluid particles across the channel", *ny, ny, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-re", "Reynolds number U L / nu of the steady flow", *re, re, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-U", "Steady centreline speed (sets the body force)", *U, U, nullptr));
  PetscCall(read_wall_scene_options(PetscOptionsObject, layers, rho0));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

void Poiseuille::set_from_options() {
  SPH_PETSC(read_options(&ny_, &wall_layers_, &re_, &U_, &rho0_));
  require(ny_ >= 8, "-nx", "at least 8", ny_);
  require(re_ > 0, "-re", "positive", re_);
  require(U_ > 0, "-U", "positive", U_);
  check_wall_scene_options(wall_layers_, rho0_);
}

Physics<2> Poiseuille::physics() const {
  Physics<2> phys;
  phys.rho0 = rho0_;
  phys.nu = nu();
  phys.U = U_;
  phys.gravity = Vector<2>(force(), 0.0);
  return phys;
}

double Poiseuille::velocity(double y, double t) const {
  const double F = force(), v = nu();
  double u = F / (2.0 * v) * y * (1.0 - y);
  for (int n = 0; n < 200; ++n) {
    const double k = 2 * n + 1;
    const double term =
        4.0 * F / (v * std::pow(M_PI * k, 3)) * std::sin(k * M_PI * y) * std::exp(-k * k * M_PI * M_PI * v * t);
    u -= term;
    if (std::abs(term) < 1e-16 * U_) break;
  }
  return u;
}

void Poiseuille::create(Particles<2>& P, Domain<2>& domain) const {
  const double dx = spacing(), mass = rho0_ * dx * dx, pad = wall_layers_ * dx;
  // The periodic length must exceed twice the neighbour-search radius: 12 dx covers support 3 dx.
  const int columns = 12;
  domain.lo = Vector<2>(0.0, -pad);
  domain.hi = Vector<2>(columns * dx, 1.0 + pad);
  domain.periodic = {true, false};
  Particles<2> all;
  const int L = static_cast<int>(wall_layers_), n = static_cast<int>(ny_);
  for (int j = -L; j < n + L; ++j)
    for (int i = 0; i < columns; ++i) {
      const bool fluid = j >= 0 && j < n;
      all.add(Vector<2>((i + 0.5) * dx, (j + 0.5) * dx), Vector<2>::Zero(), mass, rho0_, 0.0, fluid ? kFluid : kWall);
    }
  P = rank_share(all);
}

std::map<std::string, double> Poiseuille::errors(const Particles<2>& P, double t) const {
  // Mean |u - u_exact| over fluid particles, relative to the reference centreline speed at t.
  double sum[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] != kFluid) continue;
    const double y = P.x[i][1];
    sum[0] += (P.v[i] - Vector<2>(velocity(y, t), 0.0)).norm();
    sum[1] += 1.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, sum, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double centre = velocity(0.5, t);
  if (centre <= 0.0) return {{"l1_velocity", 0.0}};
  return {{"l1_velocity", sum[0] / sum[1] / centre}};
}

nlohmann::json Poiseuille::parameters() const {
  return {{"nx", ny_}, {"re", re_}, {"U", U_}, {"rho0", rho0_}, {"wall_layers", wall_layers_}, {"body_force", force()}};
}

}  // namespace sph
