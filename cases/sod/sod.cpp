#include "cases/sod/sod.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
struct RawOptions {
  PetscInt nx, ny;
  PetscReal gamma, rho_l, p_l, rho_r, p_r, margin;
};

PetscErrorCode read_options(RawOptions* o, int dim) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Sod shock tube (-case sod)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx",
                       "Particles per unit length of the left (dense) state; the 1D tube [-1,1) holds "
                       "nx (1 + rho_right/rho_left) particles",
                       o->nx, &o->nx, nullptr));
  if (dim > 1)
    PetscCall(option_int(PetscOptionsObject, "-ny", "Particle layers across the tube in the left state (2D/3D)", o->ny,
                         &o->ny, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-gamma", "Adiabatic index", o->gamma, &o->gamma, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-rho_left", "Density for x < 0", o->rho_l, &o->rho_l, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-p_left", "Pressure for x < 0", o->p_l, &o->p_l, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-rho_right", "Density for x > 0", o->rho_r, &o->rho_r, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-p_right", "Pressure for x > 0", o->p_r, &o->p_r, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-plateau_margin",
                        "Particle spacings next to the contact and the shock left out of the "
                        "plateau errors",
                        o->margin, &o->margin, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

template <int D> void SodShockTube<D>::set_from_options() {
  RawOptions o{nx_, ny_, gamma_, rho_l_, p_l_, rho_r_, p_r_, plateau_margin_};
  SPH_PETSC(read_options(&o, D));
  require(o.nx >= 8, "-nx", "at least 8", o.nx);
  require(o.ny >= 1, "-ny", "at least 1", o.ny);
  require(o.gamma > 1, "-gamma", "greater than 1", o.gamma);
  require(o.rho_l > 0, "-rho_left", "positive", o.rho_l);
  require(o.rho_r > 0, "-rho_right", "positive", o.rho_r);
  require(o.p_l > 0, "-p_left", "positive", o.p_l);
  require(o.p_r > 0, "-p_right", "positive", o.p_r);
  require(o.margin >= 0, "-plateau_margin", "non-negative", o.margin);
  nx_ = o.nx, ny_ = o.ny, gamma_ = o.gamma, rho_l_ = o.rho_l, p_l_ = o.p_l, rho_r_ = o.rho_r, p_r_ = o.p_r;
  plateau_margin_ = o.margin;
  exact_ = std::make_shared<ExactRiemann>(GasState{rho_l_, 0.0, p_l_}, GasState{rho_r_, 0.0, p_r_}, gamma_);
  if (D == 1) {
    // Equal masses need a whole number of right-state particles on [0, 1).
    const double n_right = nx_ * rho_r_ / rho_l_;
    if (std::abs(n_right - std::round(n_right)) > 1e-9 * n_right)
      throw Error("-nx must make nx * rho_right / rho_left a whole number for equal-mass particles (got nx = " +
                  std::to_string(nx_) + "; use a multiple of 8 for Sod's densities)");
  }
}

template <int D> typename SodShockTube<D>::Lattice SodShockTube<D>::left_lattice() const {
  const double dx = 1.0 / nx_;
  return {static_cast<long>(nx_), D == 1 ? 1L : static_cast<long>(ny_), dx, dx, -1.0};
}

// The left state's particles (the right state's are fewer).
template <int D> double SodShockTube<D>::minimum_particles() const {
  const Lattice L = left_lattice();
  return double(L.nx) * std::pow(double(L.ny), D - 1);
}

template <int D> typename SodShockTube<D>::Lattice SodShockTube<D>::right_lattice() const {
  const Lattice L = left_lattice();
  // Volume per particle rho_L/rho_R times the left one (equal masses); across the tube the nearest whole
  // number of layers to an isotropic spacing, along it the spacing that keeps the volume.
  const double volume = std::pow(L.dx, D) * rho_l_ / rho_r_;
  const double width = L.ny * L.dy;
  long ny = 1;
  double dy = L.dy;
  if (D > 1) {
    ny = std::max(1L, std::lround(width / std::pow(volume, 1.0 / D)));
    dy = width / ny;
  }
  const long nx = std::max(1L, std::lround(1.0 / (volume / std::pow(dy, D - 1))));
  return {nx, ny, 1.0 / nx, dy, 0.0};
}

template <int D> Physics<D> SodShockTube<D>::physics() const {
  Physics<D> phys;
  phys.rho0 = rho_l_;
  phys.U = std::sqrt(gamma_ * p_l_ / rho_l_);  // left sound speed
  phys.gamma = gamma_;
  return phys;
}

template <int D> void SodShockTube<D>::create(Particles<D>& P, Domain<D>& domain) const {
  const Lattice L = left_lattice(), R = right_lattice();
  domain.lo = Vector<D>::Zero();
  domain.hi = Vector<D>::Constant(L.ny * L.dy);
  domain.lo[0] = -1.0, domain.hi[0] = 1.0;
  for (int a = 0; a < D; ++a) domain.periodic[a] = true;

  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  long layers = 1;
  for (int a = 1; a < D; ++a) layers *= L.ny;
  long layers_r = 1;
  for (int a = 1; a < D; ++a) layers_r *= R.ny;
  const long n_left = L.nx * layers, n = n_left + R.nx * layers_r;
  const long begin = n * rank / size, end = n * (rank + 1) / size;
  for (long k = begin; k < end; ++k) {
    const bool left = k < n_left;
    const Lattice& G = left ? L : R;
    long c = left ? k : k - n_left;
    Vector<D> x;
    x[0] = G.x0 + (c % G.nx + 0.5) * G.dx;
    c /= G.nx;
    for (int a = 1; a < D; ++a, c /= G.ny) x[a] = (c % G.ny + 0.5) * G.dy;
    const double rho = left ? rho_l_ : rho_r_, p = left ? p_l_ : p_r_;
    const double volume = G.dx * std::pow(G.dy, D - 1);
    P.add(x, Vector<D>::Zero(), rho * volume, rho, p);
  }
}

template <int D> std::map<std::string, double> SodShockTube<D>::errors(const Particles<D>& P, double t) const {
  const ExactRiemann& ex = *exact_;
  const double x_contact = ex.u_star() * t, x_shock = ex.right_head_speed() * t;
  // Plateau window: a few particle spacings of the post-shock state away from the contact and the shock.
  const Lattice R = right_lattice();
  const double m_right = rho_r_ * R.dx * std::pow(R.dy, D - 1);
  const double margin = plateau_margin_ * std::pow(m_right / ex.rho_star_right(), 1.0 / D);
  const double lo = x_contact + margin, hi = x_shock - margin;

  // sums: V|drho|, V|du|, V|dp|, V ; plateau: rho, p, count
  double s[7] = {0, 0, 0, 0, 0, 0, 0};
  std::vector<double> front;  // (x, rho) pairs between the contact and the tube's end
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    const double x = P.x[i][0];
    if (std::abs(x) > 0.5) continue;
    const GasState e = ex.at(x, t);
    const double V = P.m[i] / P.rho[i];
    Vector<D> du = P.v[i];
    du[0] -= e.u;
    s[0] += V * std::abs(P.rho[i] - e.rho), s[1] += V * du.norm(), s[2] += V * std::abs(P.p[i] - e.p), s[3] += V;
    if (x > lo && x < hi) s[4] += P.rho[i], s[5] += P.p[i], s[6] += 1.0;
    if (x > x_contact) front.push_back(x), front.push_back(P.rho[i]);
  }
  MPI_Allreduce(MPI_IN_PLACE, s, 7, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);

  // The shock front needs the particles in x order across ranks.
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  int count = static_cast<int>(front.size());
  std::vector<int> counts(size), displs(size, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, PETSC_COMM_WORLD);
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<double> all(displs[size - 1] + counts[size - 1]);
  MPI_Allgatherv(front.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
                 PETSC_COMM_WORLD);
  std::vector<std::pair<double, double>> xr;
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) xr.emplace_back(all[k], all[k + 1]);
  std::sort(xr.begin(), xr.end());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double mid = 0.5 * (ex.rho_star_right() + rho_r_);
  double x_measured = nan;
  for (std::size_t k = xr.size(); k-- > 1;) {
    if (xr[k - 1].second >= mid && xr[k].second < mid) {
      const double f = (xr[k - 1].second - mid) / (xr[k - 1].second - xr[k].second);
      x_measured = xr[k - 1].first + f * (xr[k].first - xr[k - 1].first);
      break;
    }
  }

  const double plateau_rho = s[6] > 0 ? s[4] / s[6] : nan, plateau_p = s[6] > 0 ? s[5] / s[6] : nan;
  return {{"l1_density", s[0] / s[3]},
          {"l1_velocity", s[1] / s[3]},
          {"l1_pressure", s[2] / s[3]},
          {"plateau_density_rel", std::abs(plateau_rho - ex.rho_star_right()) / ex.rho_star_right()},
          {"plateau_pressure_rel", std::abs(plateau_p - ex.p_star()) / ex.p_star()},
          {"shock_position", t > 0 ? std::abs(x_measured - x_shock) : nan}};
}

template <int D> nlohmann::json SodShockTube<D>::parameters() const {
  const Lattice L = left_lattice(), R = right_lattice();
  nlohmann::json j{{"nx", nx_},
                   {"gamma", gamma_},
                   {"left", {{"rho", rho_l_}, {"p", p_l_}}},
                   {"right", {{"rho", rho_r_}, {"p", p_r_}}},
                   {"dx_left", L.dx},
                   {"dx_right", R.dx},
                   {"plateau_margin", plateau_margin_},
                   {"exact",
                    {{"p_star", exact_->p_star()},
                     {"u_star", exact_->u_star()},
                     {"rho_star_left", exact_->rho_star_left()},
                     {"rho_star_right", exact_->rho_star_right()},
                     {"shock_speed", exact_->right_head_speed()}}}};
  if (D > 1) j["ny"] = ny_, j["dy_right"] = R.dy, j["layers_right"] = R.ny;
  return j;
}

template class SodShockTube<1>;
template class SodShockTube<2>;
template class SodShockTube<3>;

}  // namespace sph
