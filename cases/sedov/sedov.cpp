#include "cases/sedov/sedov.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/io/csv_writer.hpp"
#include "src/kernels/kernel.hpp"

namespace sph {

namespace {
struct RawOptions {
  PetscInt nx;
  PetscReal gamma, rho0, energy, p_ambient, deposit_h;
};

PetscErrorCode read_options(RawOptions* o) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Sedov-Taylor blast wave, 2D (-case sedov)", "Case");
  PetscCall(
      option_int(PetscOptionsObject, "-nx", "Particles per side of the periodic unit box", o->nx, &o->nx, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-gamma", "Adiabatic index", o->gamma, &o->gamma, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-rho0", "Density of the gas at rest", o->rho0, &o->rho0, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-energy", "Blast energy E (per unit length of the cylinder)", o->energy,
                        &o->energy, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-p_ambient", "Pressure of the cold gas (the exact solution has 0)",
                        o->p_ambient, &o->p_ambient, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-deposit_h",
                        "Smoothing length of the cubic-spline weights that spread the energy over "
                        "the central particles, in particle spacings (support 2 deposit_h)",
                        o->deposit_h, &o->deposit_h, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

constexpr double box = 1.0;                     // side of the periodic box, centred on the blast
constexpr double ring_width = 0.5;              // of the radial profile, in particle spacings
constexpr double l1_extent = 1.2;               // l1 norms over r < 1.2 R
const double cone_cos = std::cos(M_PI / 16.0);  // half-angle of the axis / diagonal cones

double nan() { return std::numeric_limits<double>::quiet_NaN(); }
}  // namespace

void SedovBlast::set_from_options() {
  RawOptions o{nx_, gamma_, rho0_, energy_, p_ambient_, deposit_h_};
  SPH_PETSC(read_options(&o));
  require(o.nx >= 16, "-nx", "at least 16", o.nx);
  require(o.gamma > 1, "-gamma", "greater than 1", o.gamma);
  require(o.rho0 > 0, "-rho0", "positive", o.rho0);
  require(o.energy > 0, "-energy", "positive", o.energy);
  require(o.p_ambient > 0, "-p_ambient", "positive", o.p_ambient);
  require(o.deposit_h >= 0.5 && o.deposit_h <= 0.1 * o.nx, "-deposit_h", "in [0.5, nx/10] particle spacings",
          o.deposit_h);
  nx_ = o.nx, gamma_ = o.gamma, rho0_ = o.rho0, energy_ = o.energy, p_ambient_ = o.p_ambient;
  deposit_h_ = o.deposit_h;
  exact_ = std::make_shared<SedovSolution>(gamma_, 2, energy_, rho0_);
}

Physics<2> SedovBlast::physics() const {
  Physics<2> phys;
  phys.rho0 = rho0_;
  phys.gamma = gamma_;
  // The speed the gas would have with all of E as kinetic energy: bounds the kinetic-energy check.
  phys.U = std::sqrt(2.0 * energy_ / (rho0_ * box * box));
  return phys;
}

void SedovBlast::create(Particles<2>& P, Domain<2>& domain) const {
  domain.lo = Vector<2>::Constant(-0.5 * box);
  domain.hi = Vector<2>::Constant(0.5 * box);
  domain.periodic = {true, true};
  const double dx = spacing(), m = rho0_ * dx * dx;
  const long n = static_cast<long>(nx_) * nx_;
  auto position = [&](long k) {
    return Vector<2>(-0.5 * box + (k % nx_ + 0.5) * dx, -0.5 * box + (k / nx_ + 0.5) * dx);
  };
  // Energy weights over the whole lattice (every rank), so the shares sum to E whatever the rank count.
  const Kernel<2> deposit(KernelType::CubicSpline, deposit_h_ * dx);
  double weight_sum = 0.0;
  for (long k = 0; k < n; ++k) weight_sum += deposit.W(position(k).norm());

  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const long begin = n * rank / size, end = n * (rank + 1) / size;
  for (long k = begin; k < end; ++k) {
    const Vector<2> x = position(k);
    const double u = energy_ * deposit.W(x.norm()) / (weight_sum * m);  // thermal energy per unit mass
    P.add(x, Vector<2>::Zero(), m, rho0_, p_ambient_ + (gamma_ - 1.0) * rho0_ * u);
  }
}

SedovBlast::RadialProfile SedovBlast::radial_profile(const Particles<2>& P, double r_max, int cone) const {
  RadialProfile prof;
  prof.dr = ring_width * spacing();
  const std::size_t rings = static_cast<std::size_t>(std::ceil(r_max / prof.dr));
  // Sums per ring: count, rho, v_r, p (one buffer for one reduction).
  std::vector<double> s(4 * rings, 0.0);
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    const double r = P.x[i].norm();
    const std::size_t k = static_cast<std::size_t>(r / prof.dr);
    if (k >= rings) continue;
    const Vector<2> n = r > 0.0 ? Vector<2>(P.x[i] / r) : Vector<2>(1.0, 0.0);
    const double axis = std::max(std::abs(n[0]), std::abs(n[1])),
                 diagonal = (std::abs(n[0]) + std::abs(n[1])) / M_SQRT2;
    if ((cone == 1 && axis < cone_cos) || (cone == 2 && diagonal < cone_cos)) continue;
    s[4 * k] += 1.0, s[4 * k + 1] += P.rho[i], s[4 * k + 2] += P.v[i].dot(n), s[4 * k + 3] += P.p[i];
  }
  MPI_Allreduce(MPI_IN_PLACE, s.data(), static_cast<int>(s.size()), MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  prof.count.resize(rings), prof.rho.assign(rings, 0.0), prof.vr.assign(rings, 0.0), prof.p.assign(rings, 0.0);
  for (std::size_t k = 0; k < rings; ++k) {
    const double c = s[4 * k];
    prof.count[k] = c;
    if (c > 0) prof.rho[k] = s[4 * k + 1] / c, prof.vr[k] = s[4 * k + 2] / c, prof.p[k] = s[4 * k + 3] / c;
  }
  return prof;
}

SedovBlast::Shock SedovBlast::measure_shock(const RadialProfile& prof) const {
  std::size_t peak = 0;
  bool any = false;
  for (std::size_t k = 0; k < prof.rho.size(); ++k)
    if (prof.count[k] > 0 && (!any || prof.rho[k] > prof.rho[peak])) peak = k, any = true;
  if (!any) return {nan(), nan()};
  const double level = 0.5 * (prof.rho[peak] + rho0_);
  std::size_t inner = peak;  // the last non-empty ring at or above the level
  for (std::size_t k = peak + 1; k < prof.rho.size(); ++k) {
    if (prof.count[k] == 0) continue;
    if (prof.rho[k] < level) {
      const double f = (prof.rho[inner] - level) / (prof.rho[inner] - prof.rho[k]);
      return {prof.r(inner) + f * (prof.r(k) - prof.r(inner)), prof.rho[peak]};
    }
    inner = k;
  }
  return {nan(), prof.rho[peak]};
}

std::map<std::string, double> SedovBlast::errors(const Particles<2>& P, double t) const {
  const std::map<std::string, double> none = {{"shock_radius_rel", nan()}, {"peak_density_rel", nan()},
                                              {"l1_density", nan()},       {"l1_velocity", nan()},
                                              {"l1_pressure", nan()},      {"shock_anisotropy", nan()}};
  if (!(t > 0.0)) return none;
  const SedovSolution& ex = *exact_;
  const double R = ex.shock_radius(t), U = ex.shock_speed(t), rho2 = ex.post_shock_density();
  const double p2 = 2.0 * rho0_ * U * U / (gamma_ + 1.0);
  // sums over r < 1.2 R: V|drho|, V|dv|, V|dp|, V
  double s[4] = {0, 0, 0, 0};
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    const double r = P.x[i].norm();
    if (r >= l1_extent * R) continue;
    const SedovSolution::State e = ex.at(r, t);
    const Vector<2> v_exact = r > 0.0 ? Vector<2>(e.v / r * P.x[i]) : Vector<2>(Vector<2>::Zero());
    const double V = P.m[i] / P.rho[i];
    s[0] += V * std::abs(P.rho[i] - e.rho), s[1] += V * (P.v[i] - v_exact).norm(), s[2] += V * std::abs(P.p[i] - e.p);
    s[3] += V;
  }
  MPI_Allreduce(MPI_IN_PLACE, s, 4, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double r_max = std::min(1.5 * R, 0.5 * box);
  const Shock all = measure_shock(radial_profile(P, r_max, 0));
  const Shock axes = measure_shock(radial_profile(P, r_max, 1)), diagonals = measure_shock(radial_profile(P, r_max, 2));
  const double V = s[3] > 0 ? s[3] : nan();
  return {{"shock_radius_rel", std::abs(all.radius - R) / R},
          {"peak_density_rel", std::abs(all.peak - rho2) / rho2},
          {"l1_density", s[0] / (rho0_ * V)},
          {"l1_velocity", s[1] / (U * V)},
          {"l1_pressure", s[2] / (p2 * V)},
          {"shock_anisotropy", std::abs(axes.radius - diagonals.radius) / R}};
}

void SedovBlast::write_outputs(const Particles<2>& P, double t, const std::string& dir) const {
  if (!(t > 0.0)) return;
  const SedovSolution& ex = *exact_;
  const double R = ex.shock_radius(t);
  const RadialProfile prof = radial_profile(P, std::min(1.5 * R, 0.5 * box), 0);
  const Shock all = measure_shock(prof);
  const Shock axes = measure_shock(radial_profile(P, prof.dr * prof.rho.size(), 1));
  const Shock diagonals = measure_shock(radial_profile(P, prof.dr * prof.rho.size(), 2));
  // CsvWriter writes on rank 0 only; every rank took part in the reductions above.
  CsvWriter rings(dir + "/radial_profile.csv",
                  {"r", "particles", "rho", "v_r", "p", "rho_exact", "v_r_exact", "p_exact"});
  for (std::size_t k = 0; k < prof.rho.size(); ++k) {
    if (prof.count[k] == 0) continue;
    const SedovSolution::State e = ex.at(prof.r(k), t);
    rings.row({prof.r(k), prof.count[k], prof.rho[k], prof.vr[k], prof.p[k], e.rho, e.v, e.p});
  }
  CsvWriter shock(dir + "/shock.csv", {"t", "radius_exact", "radius", "radius_axes", "radius_diagonals", "peak_density",
                                       "post_shock_density_exact"});
  shock.row({t, R, all.radius, axes.radius, diagonals.radius, all.peak, ex.post_shock_density()});
}

nlohmann::json SedovBlast::parameters() const {
  return {{"nx", nx_},
          {"gamma", gamma_},
          {"rho0", rho0_},
          {"energy", energy_},
          {"p_ambient", p_ambient_},
          {"deposit_h", deposit_h_},
          {"box", box},
          {"exact", {{"xi0", exact_->xi0()}, {"post_shock_density", exact_->post_shock_density()}}}};
}

}  // namespace sph
