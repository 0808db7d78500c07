#include "cases/square_patch/square_patch.hpp"

#include <cmath>

#include "cases/common/lattice.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* nx, PetscReal* L, PetscReal* omega, PetscReal* nu, PetscReal* rho0) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Rotating square patch (-case square_patch)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Particles along a side of the square", *nx, nx, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-side", "Side length L", *L, L, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-omega", "Initial angular velocity", *omega, omega, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-nu", "Kinematic viscosity (0: inviscid)", *nu, nu, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-rho0", "Density", *rho0, rho0, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

void SquarePatch::set_from_options() {
  SPH_PETSC(read_options(&nx_, &L_, &omega_, &nu_, &rho0_));
  require(nx_ >= 8, "-nx", "at least 8", nx_);
  require(L_ > 0, "-side", "positive", L_);
  require(omega_ > 0, "-omega", "positive", omega_);
  require(nu_ >= 0, "-nu", "non-negative", nu_);
  require(rho0_ > 0, "-rho0", "positive", rho0_);
}

Physics<2> SquarePatch::physics() const {
  Physics<2> phys;
  phys.rho0 = rho0_;
  phys.nu = nu_;
  phys.U = omega_ * L_ / std::sqrt(2.0);  // corner speed
  phys.free_surface = true;
  return phys;
}

void SquarePatch::create(Particles<2>& P, Domain<2>& domain) const {
  const double dx = spacing(), mass = rho0_ * dx * dx;
  // Vacuum all round: a box far larger than the patch can reach in the run.
  domain.lo = Vector<2>(-10.0 * L_, -10.0 * L_);
  domain.hi = Vector<2>(10.0 * L_, 10.0 * L_);
  domain.periodic = {false, false};
  Particles<2> all;
  const int n = static_cast<int>(nx_);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vector<2> x((i + 0.5) * dx - 0.5 * L_, (j + 0.5) * dx - 0.5 * L_);  // centred at the origin
      all.add(x, Vector<2>(omega_ * x[1], -omega_ * x[0]), mass, rho0_, 0.0, kFluid);
    }
  P = rank_share(all);
}

std::pair<double, double> SquarePatch::invariants(const Particles<2>& P) const {
  double buf[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] != kFluid) continue;
    buf[0] += P.m[i] * (P.x[i][0] * P.v[i][1] - P.x[i][1] * P.v[i][0]);
    buf[1] += 0.5 * P.m[i] * P.v[i].squaredNorm();
  }
  MPI_Allreduce(MPI_IN_PLACE, buf, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return {buf[0], buf[1]};
}

std::map<std::string, double> SquarePatch::errors(const Particles<2>& P, double t) const {
  const auto [Lz, E] = invariants(P);
  if (t == 0.0 || L0_ == 0.0) L0_ = Lz, E0_ = E;
  return {{"angular_momentum_drift_rel", std::abs(Lz - L0_) / std::abs(L0_)},
          {"kinetic_energy_change_rel", (E - E0_) / E0_}};
}

nlohmann::json SquarePatch::parameters() const {
  return {{"nx", nx_}, {"side", L_}, {"omega", omega_}, {"nu", nu_}, {"rho0", rho0_}};
}

}  // namespace sph
