#include "cases/taylor_green/taylor_green.hpp"

#include <cmath>
#include <random>

#include "cases/common/exact_flow_errors.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* nx, PetscReal* re, PetscReal* U, PetscReal* rho0, PetscReal* perturbation) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Taylor-Green vortex (-case taylor_green)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Particles per side of the unit square", *nx, nx, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-re", "Reynolds number U L / nu", *re, re, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-U", "Initial velocity amplitude", *U, U, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-rho0", "Density", *rho0, rho0, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-perturbation",
                        "Disordered start: lattice positions moved by up to this fraction of dx", *perturbation,
                        perturbation, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

// grad phi with lap phi = -(Dp/Dt) / (rho0 c0^2) at t = 0, in closed form. With a = U, k = 2 pi and
// lambda the velocity's decay rate, p = -(rho0 a^2 / 4)(cos 2kx + cos 2ky), so dp/dt = 2 lambda p and
// u . grad p = (rho0 k a^3 / 4)(sin kx sin 3ky - sin 3kx sin ky): the sound the start would excite is in
// the modes (2, 0), (0, 2) and (1, 3), (3, 1).
Vector<2> slow_manifold_velocity(const Vector<2>& x, double U, double decay_rate, double c0) {
  const double a = U, k = 2.0 * M_PI, c2 = c0 * c0;
  const Vector<2> decay_part =
      (decay_rate * a * a / (4.0 * k * c2)) * Vector<2>(std::sin(2.0 * k * x[0]), std::sin(2.0 * k * x[1]));
  const Vector<2> advection_part =
      (a * a * a / (40.0 * c2)) *
      Vector<2>(std::cos(k * x[0]) * std::sin(3.0 * k * x[1]) - 3.0 * std::cos(3.0 * k * x[0]) * std::sin(k * x[1]),
                3.0 * std::sin(k * x[0]) * std::cos(3.0 * k * x[1]) - std::sin(3.0 * k * x[0]) * std::cos(k * x[1]));
  return decay_part + advection_part;
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
  phys.slow_manifold_velocity = [U = U_, rate = decay_rate()](const Vector<2>& x, double c0) {
    return slow_manifold_velocity(x, U, rate, c0);
  };
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
  // velocity() and pressure() per particle, with their decay factors taken once and the pressure's
  // cos 2kx = 1 - 2 sin^2 kx from the velocity's sines: two sine-cosine pairs a particle instead of
  // four trigonometric calls and two exponentials, which makes the per-step diagnostics cheaper
  // (docs/performance.md, "Design measurements"). The same fields to round-off.
  const double a = U_ * std::exp(decay_rate() * t), k = 2.0 * M_PI, p_amp = -0.25 * rho0_ * a * a;
  struct Shape {
    double s0, c0, s1, c1;
  };
  auto shape = [k](const Vector<2>& x) {
    return Shape{std::sin(k * x[0]), std::cos(k * x[0]), std::sin(k * x[1]), std::cos(k * x[1])};
  };
  return exact_flow_errors(
      P, a, rho0_,
      [&](const Vector<2>& x) {
        const Shape f = shape(x);
        return Vector<2>(-a * f.c0 * f.s1, a * f.s0 * f.c1);
      },
      [&](const Vector<2>& x) {
        const Shape f = shape(x);
        return p_amp * (2.0 - 2.0 * (f.s0 * f.s0 + f.s1 * f.s1));
      });
}

nlohmann::json TaylorGreen::parameters() const {
  return {{"nx", nx_}, {"re", re_}, {"U", U_}, {"rho0", rho0_}, {"perturbation", perturbation_}};
}

}  // namespace sph
