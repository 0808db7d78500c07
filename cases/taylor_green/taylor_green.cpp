#include "cases/taylor_green/taylor_green.hpp"

#include <cmath>
#include <random>

#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* nx, PetscReal* re, PetscReal* U, PetscReal* rho0, PetscReal* perturbation) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Taylor-Green vortex (-case taylor_green)", "Case");
  PetscCall(PetscOptionsInt("-nx", "Particles per side of the unit square", "", *nx, nx, nullptr));
  PetscCall(PetscOptionsReal("-re", "Reynolds number U L / nu", "", *re, re, nullptr));
  PetscCall(PetscOptionsReal("-U", "Initial velocity amplitude", "", *U, U, nullptr));
  PetscCall(PetscOptionsReal("-rho0", "Density", "", *rho0, rho0, nullptr));
  PetscCall(PetscOptionsReal("-perturbation", "Disordered start: lattice positions moved by up to this fraction of dx",
                             "", *perturbation, perturbation, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

void TaylorGreen::set_from_options() {
  SPH_PETSC(read_options(&nx_, &re_, &U_, &rho0_, &perturbation_));
  require(perturbation_ >= 0 && perturbation_ < 0.5, "-perturbation", "in [0, 0.5)", perturbation_);
  require(nx_ >= 4, "-nx", "at least 4", nx_);
  require(re_ > 0, "-re", "positive", re_);
  require(U_ > 0, "-U", "positive", U_);
  require(rho0_ > 0, "-rho0", "positive", rho0_);
}

double TaylorGreen::decay_rate() const { return -8.0 * M_PI * M_PI / re_; }

Vector<2> TaylorGreen::velocity(const Vector<2>& x, double t) const {
  const double a = U_ * std::exp(decay_rate() * t), k = 2.0 * M_PI;
  return {-a * std::cos(k * x[0]) * std::sin(k * x[1]), a * std::sin(k * x[0]) * std::cos(k * x[1])};
}

double TaylorGreen::pressure(const Vector<2>& x, double t) const {
  const double k = 4.0 * M_PI;
  return -0.25 * rho0_ * U_ * U_ * std::exp(2.0 * decay_rate() * t) * (std::cos(k * x[0]) + std::cos(k * x[1]));
}

Physics<2> TaylorGreen::physics() const {
  Physics<2> phys;
  phys.rho0 = rho0_;
  phys.nu = U_ * 1.0 / re_;
  phys.U = U_;
  return phys;
}

void TaylorGreen::create(Particles<2>& P, Domain<2>& domain) const {
  domain.lo = Vector<2>::Zero();
  domain.hi = Vector<2>::Ones();
  domain.periodic = {true, true};
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  // Each rank creates an equal contiguous share of the lattice.
  const long n = static_cast<long>(nx_) * nx_;
  const long begin = n * rank / size, end = n * (rank + 1) / size;
  const double dx = spacing(), mass = rho0_ * dx * dx;
  for (long k = begin; k < end; ++k) {
    Vector<2> x((k % nx_ + 0.5) * dx, (k / nx_ + 0.5) * dx);
    if (perturbation_ > 0) {
      // Reproducible on any rank count: the offset depends on the particle's lattice index only.
      std::mt19937_64 rng(static_cast<unsigned long>(k) * 0x9E3779B97F4A7C15ull + 12345u);
      std::uniform_real_distribution<double> u(-perturbation_ * dx, perturbation_ * dx);
      x += Vector<2>(u(rng), u(rng));
    }
    P.add(x, velocity(x, 0.0), mass, rho0_, pressure(x, 0.0));
  }
}

std::map<std::string, double> TaylorGreen::errors(const Particles<2>& P, double t) const {
  const double amp = U_ * std::exp(decay_rate() * t);
  // sums: |du|, count, p, p_exact, u . u_exact, |u_exact|^2 ; maxima: |du|, |u|
  double sum[6] = {0, 0, 0, 0, 0, 0}, mx[2] = {0, 0};
  std::vector<double> p_exact(P.n_owned);
  std::vector<Vector<2>> u_exact(P.n_owned);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    u_exact[i] = velocity(P.x[i], t);
    const double du = (P.v[i] - u_exact[i]).norm();
    p_exact[i] = pressure(P.x[i], t);
    sum[0] += du, sum[1] += 1.0, sum[2] += P.p[i], sum[3] += p_exact[i];
    sum[4] += P.v[i].dot(u_exact[i]), sum[5] += u_exact[i].squaredNorm();
    mx[0] = std::max(mx[0], du), mx[1] = std::max(mx[1], P.v[i].norm());
  }
  MPI_Allreduce(MPI_IN_PLACE, sum, 6, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, mx, 2, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  const double mean_p = sum[2] / sum[1], mean_pe = sum[3] / sum[1];
  // The vortex's amplitude relative to the exact one (least squares), and what is left of the error
  // once the exact field is scaled by it: a decay rate that is off shows in the first, a distorted
  // vortex in the second.
  const double a = sum[5] > 0 ? sum[4] / sum[5] : 1.0;
  double local[2] = {0, 0};  // |p - p_exact| after the means, |u - a u_exact|
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    local[0] += std::abs((P.p[i] - mean_p) - (p_exact[i] - mean_pe));
    local[1] += (P.v[i] - a * u_exact[i]).norm();
  }
  MPI_Allreduce(MPI_IN_PLACE, local, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double p_scale = 0.5 * rho0_ * amp * amp;
  return {{"l1_velocity", sum[0] / sum[1] / amp},
          {"linf_velocity", mx[0] / amp},
          {"decay_rel", std::abs(mx[1] - amp) / amp},
          {"amplitude_rel", a - 1.0},
          {"l1_velocity_shape", local[1] / sum[1] / amp},
          {"l1_pressure", local[0] / sum[1] / p_scale}};
}

nlohmann::json TaylorGreen::parameters() const {
  return {{"nx", nx_}, {"re", re_}, {"U", U_}, {"rho0", rho0_}, {"perturbation", perturbation_}};
}

}  // namespace sph
