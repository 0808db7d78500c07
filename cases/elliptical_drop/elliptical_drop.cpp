#include "cases/elliptical_drop/elliptical_drop.hpp"

#include <array>
#include <cmath>

#include "cases/common/lattice.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* nx, PetscReal* R, PetscReal* A0, PetscReal* rho0) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Elliptical drop (-case elliptical_drop)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Particles across the drop's radius", *nx, nx, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-radius", "The drop's initial radius R", *R, R, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, "-strain_rate", "The initial strain rate A0: u = A0 (x, -y)", *A0, A0, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-rho0", "Density", *rho0, rho0, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

void EllipticalDrop::set_from_options() {
  SPH_PETSC(read_options(&nx_, &R_, &A0_, &rho0_));
  require(nx_ >= 4, "-nx", "at least 4", nx_);
  require(R_ > 0, "-radius", "positive", R_);
  require(A0_ > 0, "-strain_rate", "positive", A0_);
  require(rho0_ > 0, "-rho0", "positive", rho0_);
}

Physics<2> EllipticalDrop::physics() const {
  Physics<2> phys;
  phys.rho0 = rho0_;
  phys.nu = 0.0;
  phys.U = A0_ * R_;
  phys.gravity = Vector<2>::Zero();
  phys.free_surface = true;
  return phys;
}

void EllipticalDrop::create(Particles<2>& P, Domain<2>& domain) const {
  const double dx = spacing(), mass = rho0_ * dx * dx;
  const int n = static_cast<int>(nx_);
  domain.lo = Vector<2>::Constant(-6.0 * R_);  // the drop stretches to a ~ 2.5 R by A0 t = 1
  domain.hi = Vector<2>::Constant(6.0 * R_);
  domain.periodic.fill(false);
  Particles<2> all;
  for (int j = -n; j < n; ++j)
    for (int i = -n; i < n; ++i) {
      const Vector<2> x((i + 0.5) * dx, (j + 0.5) * dx);
      if (x.norm() >= R_) continue;
      const Vector<2> u(A0_ * x[0], -A0_ * x[1]);
      all.add(x, u, mass, rho0_, 0.5 * rho0_ * A0_ * A0_ * (R_ * R_ - x.squaredNorm()), kFluid);
    }
  P = rank_share(all);
}

std::pair<double, double> EllipticalDrop::semi_axes(double t) const {
  // State (a, b, A); RK4 at a step far below the flow's time 1 / A0 (round-off limited).
  using State = std::array<double, 3>;
  auto rate = [](const State& s) {
    const double a2 = s[0] * s[0], b2 = s[1] * s[1];
    return State{s[2] * s[0], -s[2] * s[1], s[2] * s[2] * (b2 - a2) / (a2 + b2)};
  };
  State s{R_, R_, A0_};
  const int steps = std::max(1, static_cast<int>(std::ceil(t * A0_ * 2000.0)));
  const double h = t / steps;
  for (int k = 0; k < steps; ++k) {
    const State k1 = rate(s);
    State tmp;
    for (int c = 0; c < 3; ++c) tmp[c] = s[c] + 0.5 * h * k1[c];
    const State k2 = rate(tmp);
    for (int c = 0; c < 3; ++c) tmp[c] = s[c] + 0.5 * h * k2[c];
    const State k3 = rate(tmp);
    for (int c = 0; c < 3; ++c) tmp[c] = s[c] + h * k3[c];
    const State k4 = rate(tmp);
    for (int c = 0; c < 3; ++c) s[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
  }
  return {s[0], s[1]};
}

std::map<std::string, double> EllipticalDrop::errors(const Particles<2>& P, double t) const {
  double sums[3] = {0.0, 0.0, 0.0};  // sum m x^2, sum m y^2, sum m (the drop's centre stays at the origin)
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid)
      sums[0] += P.m[i] * P.x[i][0] * P.x[i][0], sums[1] += P.m[i] * P.x[i][1] * P.x[i][1], sums[2] += P.m[i];
  MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double x2 = sums[0] / sums[2], y2 = sums[1] / sums[2];
  if (x2_0_ < 0.0) x2_0_ = x2, y2_0_ = y2;  // the first call is at t = 0
  const double a = R_ * std::sqrt(x2 / x2_0_), b = R_ * std::sqrt(y2 / y2_0_);
  const auto [a_ref, b_ref] = semi_axes(t);
  return {{"semi_axis_a", a},
          {"semi_axis_b", b},
          {"semi_axis_rel", std::abs(a - a_ref) / a_ref},
          {"semi_axis_b_rel", std::abs(b - b_ref) / b_ref}};
}

nlohmann::json EllipticalDrop::parameters() const {
  return {{"nx", nx_}, {"radius", R_}, {"strain_rate", A0_}, {"rho0", rho0_}};
}

}  // namespace sph
