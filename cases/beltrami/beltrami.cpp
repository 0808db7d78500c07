#include "cases/beltrami/beltrami.hpp"

#include <cmath>

#include "cases/common/exact_flow_errors.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
constexpr double kL = 2.0 * M_PI;  // side of the cube

PetscErrorCode read_options(PetscInt* nx, PetscReal* re, PetscReal* A, PetscReal* B, PetscReal* C, PetscReal* rho0) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Beltrami (ABC) flow (-case beltrami, 3D)", "Case");
  PetscCall(
      option_int(PetscOptionsObject, "-nx", "Particles per side of the periodic cube [0, 2 pi)^3", *nx, nx, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-re", "Reynolds number U L / nu, U = max |u(x, 0)|, L = 2 pi", *re, re,
                        nullptr));
  PetscCall(option_real(PetscOptionsObject, "-A", "ABC coefficient A (u = A sin z + C cos y, ...)", *A, A, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-B", "ABC coefficient B", *B, B, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-C", "ABC coefficient C", *C, C, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-rho0", "Density", *rho0, rho0, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

Vector<3> abc(double A, double B, double C, const Vector<3>& x) {
  return {A * std::sin(x[2]) + C * std::cos(x[1]), B * std::sin(x[0]) + A * std::cos(x[2]),
          C * std::sin(x[1]) + B * std::cos(x[0])};
}
}  // namespace

double beltrami_max_speed(double A, double B, double C) {
  // |u|^2 is smooth and 2 pi-periodic: a 32^3 grid finds the basin of the maximum, and grids of 9^3
  // points, each spanning two spacings of the one before, close in on it (to ~1e-12 in |u|).
  Vector<3> best = Vector<3>::Zero();
  double best_u2 = abc(A, B, C, best).squaredNorm(), spacing = kL / 32;
  for (int i = 0; i < 32; ++i)
    for (int j = 0; j < 32; ++j)
      for (int k = 0; k < 32; ++k) {
        const Vector<3> x(i * spacing, j * spacing, k * spacing);
        const double u2 = abc(A, B, C, x).squaredNorm();
        if (u2 > best_u2) best_u2 = u2, best = x;
      }
  for (int level = 0; level < 12; ++level) {
    const Vector<3> centre = best;
    spacing /= 4;
    for (int i = -4; i <= 4; ++i)
      for (int j = -4; j <= 4; ++j)
        for (int k = -4; k <= 4; ++k) {
          const Vector<3> x = centre + spacing * Vector<3>(i, j, k);
          const double u2 = abc(A, B, C, x).squaredNorm();
          if (u2 > best_u2) best_u2 = u2, best = x;
        }
  }
  return std::sqrt(best_u2);
}

void Beltrami::set_from_options() {
  SPH_PETSC(read_options(&nx_, &re_, &A_, &B_, &C_, &rho0_));
  require(nx_ >= 4, "-nx", "at least 4", nx_);
  require(re_ > 0, "-re", "positive", re_);
  require(rho0_ > 0, "-rho0", "positive", rho0_);
  U_ = beltrami_max_speed(A_, B_, C_);
  if (!(U_ > 0)) throw OptionError("-A, -B and -C are all zero: the flow is at rest; give at least one a value");
}

double Beltrami::spacing() const { return kL / nx_; }

double Beltrami::viscosity() const { return U_ * kL / re_; }

Vector<3> Beltrami::velocity(const Vector<3>& x, double t) const {
  return std::exp(-viscosity() * t) * abc(A_, B_, C_, x);
}

double Beltrami::pressure(const Vector<3>& x, double t) const { return -0.5 * rho0_ * velocity(x, t).squaredNorm(); }

Physics<3> Beltrami::physics() const {
  Physics<3> phys;
  phys.rho0 = rho0_;
  phys.nu = viscosity();
  phys.U = U_;
  return phys;
}

void Beltrami::create(Particles<3>& P, Domain<3>& domain) const {
  domain.lo = Vector<3>::Zero();
  domain.hi = Vector<3>::Constant(kL);
  domain.periodic = {true, true, true};
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  // Each rank creates an equal contiguous share of the lattice.
  const long nx = nx_, n = nx * nx * nx;
  const long begin = n * rank / size, end = n * (rank + 1) / size;
  const double dx = spacing(), mass = rho0_ * dx * dx * dx;
  for (long k = begin; k < end; ++k) {
    const Vector<3> x((k % nx + 0.5) * dx, ((k / nx) % nx + 0.5) * dx, (k / (nx * nx) + 0.5) * dx);
    P.add(x, velocity(x, 0.0), mass, rho0_, pressure(x, 0.0));
  }
}

std::map<std::string, double> Beltrami::errors(const Particles<3>& P, double t) const {
  return exact_flow_errors(
      P, U_ * std::exp(-viscosity() * t), rho0_, [&](const Vector<3>& x) { return velocity(x, t); },
      [&](const Vector<3>& x) { return pressure(x, t); });
}

nlohmann::json Beltrami::parameters() const {
  return {{"nx", nx_}, {"re", re_}, {"A", A_}, {"B", B_}, {"C", C_}, {"rho0", rho0_}, {"U", U_}};
}

}  // namespace sph
