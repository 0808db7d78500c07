#include "cases/toy_star/toy_star.hpp"

#include <cmath>
#include <vector>

#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* n, PetscReal* gamma, PetscReal* K, PetscReal* omega, PetscReal* A0) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "1D toy star (-case toy_star)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Number of (equal-mass) particles", *n, n, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-gamma", "Polytropic exponent", *gamma, gamma, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, "-polytropic_k", "Polytropic constant K in P = K rho^gamma", *K, K, nullptr));
  PetscCall(
      option_real(PetscOptionsObject, "-omega", "Frequency of the external force -Omega^2 x", *omega, omega, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-a0", "Initial velocity gradient A0 (v = A0 x)", *A0, A0, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
constexpr double radius = 1.0;  // of the initial static star
}  // namespace

void ToyStar::set_from_options() {
  SPH_PETSC(read_options(&n_, &gamma_, &K_, &omega_, &A0_));
  require(n_ >= 10, "-nx", "at least 10", n_);
  require(gamma_ > 1, "-gamma", "greater than 1", gamma_);
  require(K_ > 0, "-polytropic_k", "positive", K_);
  require(omega_ > 0, "-omega", "positive", omega_);
  require(std::abs(A0_) < omega_, "-a0", "smaller in magnitude than -omega", A0_);
  const double C = (gamma_ - 1.0) * omega_ * omega_ / (2.0 * K_ * gamma_);
  y_cache_ = {A0_, C * radius * radius, C};
  k_cache_ = 0;
}

double ToyStar::period() const { return 2.0 * M_PI / (omega_ * std::sqrt(gamma_ + 1.0)); }

std::array<double, 3> ToyStar::rates(const std::array<double, 3>& y) const {
  const double A = y[0], H = y[1], C = y[2];
  return {2.0 * K_ * gamma_ * C / (gamma_ - 1.0) - omega_ * omega_ - A * A, -(gamma_ - 1.0) * A * H,
          -(gamma_ + 1.0) * A * C};
}

std::array<double, 3> ToyStar::rk4_step(const std::array<double, 3>& y, double h) const {
  auto axpy = [](const std::array<double, 3>& y, double a, const std::array<double, 3>& k) {
    return std::array<double, 3>{y[0] + a * k[0], y[1] + a * k[1], y[2] + a * k[2]};
  };
  const auto k1 = rates(y), k2 = rates(axpy(y, 0.5 * h, k1)), k3 = rates(axpy(y, 0.5 * h, k2)),
             k4 = rates(axpy(y, h, k3));
  std::array<double, 3> out = y;
  for (int c = 0; c < 3; ++c) out[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
  return out;
}

// RK4 on the fixed grid t_k = k dt (dt = period / 1000; error ~1e-13), cached at the last grid point
// reached, then one partial step to t: the same answer whatever the order of the calls (restarts).
std::array<double, 3> ToyStar::coefficients(double t) const {
  const double dt = 1e-3 * period();
  const long k = static_cast<long>(std::floor(t / dt));
  if (k < k_cache_) {
    const double C = (gamma_ - 1.0) * omega_ * omega_ / (2.0 * K_ * gamma_);
    y_cache_ = {A0_, C * radius * radius, C};
    k_cache_ = 0;
  }
  for (; k_cache_ < k; ++k_cache_) y_cache_ = rk4_step(y_cache_, dt);
  const double rest = t - k * dt;
  return rest > 0.0 ? rk4_step(y_cache_, rest) : y_cache_;
}

double ToyStar::density(double x, double t) const {
  const auto y = coefficients(t);
  const double base = y[1] - y[2] * x * x;
  return base > 0.0 ? std::pow(base, 1.0 / (gamma_ - 1.0)) : 0.0;
}

double ToyStar::velocity(double x, double t) const { return coefficients(t)[0] * x; }

double ToyStar::mass() const {
  // Simpson's rule on the initial profile (smooth enough away from the edges; 20000 intervals).
  const int n = 20000;
  const double C = (gamma_ - 1.0) * omega_ * omega_ / (2.0 * K_ * gamma_), H = C * radius * radius;
  auto rho = [&](double x) {
    const double b = H - C * x * x;
    return b > 0.0 ? std::pow(b, 1.0 / (gamma_ - 1.0)) : 0.0;
  };
  const double dx = 2.0 * radius / n;
  double s = rho(-radius) + rho(radius);
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * rho(-radius + k * dx);
  return s * dx / 3.0;
}

double ToyStar::spacing() const {
  const double C = (gamma_ - 1.0) * omega_ * omega_ / (2.0 * K_ * gamma_);
  const double rho_c = std::pow(C * radius * radius, 1.0 / (gamma_ - 1.0));
  return mass() / n_ / rho_c;
}

Physics<1> ToyStar::physics() const {
  Physics<1> phys;
  const double C = (gamma_ - 1.0) * omega_ * omega_ / (2.0 * K_ * gamma_);
  phys.rho0 = std::pow(C * radius * radius, 1.0 / (gamma_ - 1.0));
  phys.U = omega_ * radius;
  phys.gamma = gamma_;
  phys.isentropic = true;
  const double w2 = omega_ * omega_;
  phys.external_acceleration = [w2](const Vector<1>& x) { return Vector<1>(-w2 * x); };
  phys.external_potential = [w2](const Vector<1>& x) { return 0.5 * w2 * x.squaredNorm(); };
  phys.external_label = "harmonic -Omega^2 x, Omega = " + std::to_string(omega_);
  return phys;
}

void ToyStar::create(Particles<1>& P, Domain<1>& domain) const {
  domain.lo = Vector<1>(-2.0 * radius);
  domain.hi = Vector<1>(2.0 * radius);
  domain.periodic = {false};
  // Equal masses placed where the cumulative mass of the exact profile reaches (k + 1/2) M / N
  // (trapezoidal cumulative mass on a fine grid, inverted by linear interpolation).
  const int grid = 200000;
  std::vector<double> xs(grid + 1), cum(grid + 1, 0.0);
  for (int k = 0; k <= grid; ++k) xs[k] = -radius + 2.0 * radius * k / grid;
  for (int k = 1; k <= grid; ++k)
    cum[k] = cum[k - 1] + 0.5 * (density(xs[k - 1], 0.0) + density(xs[k], 0.0)) * (xs[k] - xs[k - 1]);
  const double M = cum[grid], m = M / n_;
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const long begin = long(n_) * rank / size, end = long(n_) * (rank + 1) / size;
  int k = 0;
  for (long p = 0; p < end; ++p) {
    const double target = (p + 0.5) * m;
    while (k < grid && cum[k + 1] < target) ++k;
    if (p < begin) continue;
    const double f = (target - cum[k]) / (cum[k + 1] - cum[k]);
    const Vector<1> x(xs[k] + f * (xs[k + 1] - xs[k]));
    const double rho = density(x[0], 0.0);
    P.add(x, Vector<1>(A0_ * x[0]), m, rho, K_ * std::pow(rho, gamma_));
  }
}

std::map<std::string, double> ToyStar::errors(const Particles<1>& P, double t) const {
  const auto y = coefficients(t);
  double s[3] = {0, 0, 0};
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    const double x = P.x[i][0], base = y[1] - y[2] * x * x;
    const double rho = base > 0.0 ? std::pow(base, 1.0 / (gamma_ - 1.0)) : 0.0;
    s[0] += std::abs(P.rho[i] - rho), s[1] += std::abs(P.v[i][0] - y[0] * x), s[2] += 1.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, s, 3, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return {{"l1_density", s[0] / s[2]}, {"l1_velocity", s[1] / s[2]}};
}

nlohmann::json ToyStar::parameters() const {
  const auto y = coefficients(0.0);
  return {{"nx", n_},         {"gamma", gamma_}, {"K", K_},    {"Omega", omega_}, {"A0", A0_},
          {"radius", radius}, {"H0", y[1]},      {"C0", y[2]}, {"mass", mass()},  {"period", period()}};
}

}  // namespace sph
