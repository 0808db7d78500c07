#include "cases/standing_wave/standing_wave.hpp"

#include <cmath>

#include "cases/common/lattice.hpp"
#include "cases/common/wall_options.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* nx, PetscInt* layers, PetscReal* width, PetscReal* depth, PetscReal* amplitude,
                            PetscReal* g, PetscReal* re, PetscReal* rho0, PetscBool* side_walls,
                            PetscBool* free_slip_side_walls) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Standing wave (-case standing_wave)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Particles per unit length", *nx, nx, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-tank_width", "Tank width L (the mode's half wavelength)", *width, width,
                        nullptr));
  PetscCall(option_real(PetscOptionsObject, "-depth", "Mean water depth h", *depth, depth, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-amplitude", "The surface's initial amplitude a", *amplitude, amplitude,
                        nullptr));
  PetscCall(option_real(PetscOptionsObject, "-g", "Gravity", *g, g, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-re", "Reynolds number sqrt(g h) h / nu", *re, re, nullptr));
  PetscCall(option_bool(PetscOptionsObject, "-side_walls",
                        "Walls at both ends (a tank); 0: one whole wavelength 2L, periodic, a floor only (no "
                        "contact lines, whose no-slip dissipation the linear theory leaves out)",
                        *side_walls, side_walls, nullptr));
  PetscCall(option_bool(PetscOptionsObject, "-free_slip_side_walls",
                        "Side walls without shear: no Stokes layers on them and no no-slip contact lines, whose "
                        "dissipation the linear theory leaves out (its rate is then the bulk's and the floor's)",
                        *free_slip_side_walls, free_slip_side_walls, nullptr));
  PetscCall(read_wall_scene_options(PetscOptionsObject, layers, rho0));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

void StandingWave::set_from_options() {
  PetscBool side_walls = side_walls_ ? PETSC_TRUE : PETSC_FALSE,
            free_slip = free_slip_side_walls_ ? PETSC_TRUE : PETSC_FALSE;
  SPH_PETSC(
      read_options(&nx_, &wall_layers_, &width_, &depth_, &amplitude_, &g_, &re_, &rho0_, &side_walls, &free_slip));
  side_walls_ = side_walls == PETSC_TRUE;
  free_slip_side_walls_ = free_slip == PETSC_TRUE;
  if (free_slip_side_walls_ && !side_walls_)
    throw Error("-free_slip_side_walls needs side walls; remove it or drop -side_walls 0");
  require(nx_ >= 4, "-nx", "at least 4", nx_);
  require(width_ > 0, "-tank_width", "positive", width_);
  require(depth_ > 0, "-depth", "positive", depth_);
  require(amplitude_ > 0 && amplitude_ < 0.5 * depth_, "-amplitude", "positive and below half the depth", amplitude_);
  require(g_ > 0, "-g", "positive", g_);
  require(re_ > 0, "-re", "positive", re_);
  check_wall_scene_options(wall_layers_, rho0_);
}

double StandingWave::linear_period() const {
  const double k = M_PI / width_;
  return 2.0 * M_PI / std::sqrt(g_ * k * std::tanh(k * depth_));
}

// Linear theory's viscous decay rate of the mode's amplitude: the bulk, 2 nu k^2, and the Stokes layers
// on the floor and, in a tank, on both side walls (Mei et al. 2005, sec. 9; Keulegan 1959), of
// thickness sqrt(2 nu / omega): sqrt(nu omega / 2) omega^2 / (g sinh^2 kh) (1/2 + sinh(2kh) / (2kL) -
// h/L), whose floor part is sqrt(nu omega / 2) k / sinh(2kh).
double StandingWave::damping_rate_theory() const {
  const double k = M_PI / width_, nu = physics().nu, omega = 2.0 * M_PI / linear_period();
  const double layers = std::sqrt(0.5 * nu * omega) * omega * omega / (g_ * std::pow(std::sinh(k * depth_), 2));
  const double walls =
      side_walls_ && !free_slip_side_walls_ ? std::sinh(2.0 * k * depth_) / (2.0 * k * width_) - depth_ / width_ : 0.0;
  return 2.0 * nu * k * k + layers * (0.5 + walls);
}

Physics<2> StandingWave::physics() const {
  Physics<2> phys;
  phys.rho0 = rho0_;
  phys.nu = std::sqrt(g_ * depth_) * depth_ / re_;
  phys.U = std::sqrt(g_ * depth_);  // the long-wave speed: the flow's speeds are a fraction a / h of it
  phys.gravity = Vector<2>(0.0, -g_);
  phys.free_surface = true;
  return phys;
}

// Calls f(i, j, site) for each particle's lattice site (i, j), in the order create() adds them.
template <class F> void StandingWave::for_each_site(F&& f) const {
  const int L = static_cast<int>(wall_layers_), n = static_cast<int>(std::lround(width_ * nx_));
  const int rows = static_cast<int>(std::lround(depth_ * nx_)), height = 2 * rows;
  // Without side walls: one whole wavelength, periodic in x.
  const int side = side_walls_ ? L : 0, columns = side_walls_ ? n : 2 * n;
  for (int j = -L; j < height; ++j)
    for (int i = -side; i < columns + side; ++i) {
      if (j < 0) f(i, j, Site::Floor);
      else if (i < 0 || i >= columns) f(i, j, Site::SideWall);
      else if (j < rows) f(i, j, Site::Fluid);
    }
}

void StandingWave::create(Particles<2>& P, Domain<2>& domain) const {
  const double dx = spacing(), k = M_PI / width_;
  const int L = static_cast<int>(wall_layers_), n = static_cast<int>(std::lround(width_ * nx_));
  const int side = side_walls_ ? L : 0, columns = side_walls_ ? n : 2 * n;
  domain.lo = Vector<2>(-side * dx, -L * dx);
  domain.hi = Vector<2>((columns + side) * dx, 20.0 * depth_);
  domain.periodic = {!side_walls_, false};
  Particles<2> all;
  for_each_site([&](int i, int j, Site site) {
    const Vector<2> lattice((i + 0.5) * dx, (j + 0.5) * dx);
    if (site != Site::Fluid) {
      all.add(lattice, Vector<2>::Zero(), rho0_ * dx * dx, rho0_, 0.0, kWall);
    } else {
      // The column stretched to the surface h + eta(x): its particles' volume grows with it.
      const double stretch = 1.0 + amplitude_ * std::cos(k * lattice[0]) / depth_;
      const Vector<2> x(lattice[0], lattice[1] * stretch);
      const double surface = depth_ * stretch;
      all.add(x, Vector<2>::Zero(), rho0_ * dx * dx * stretch, rho0_, rho0_ * g_ * (surface - x[1]), kFluid);
    }
  });
  P = rank_share(all);
}

std::vector<char> StandingWave::free_slip_of_particles() const {
  if (!free_slip_side_walls_) return {};
  std::vector<char> free_slip;
  for_each_site([&](int, int, Site site) { free_slip.push_back(site == Site::SideWall); });
  return free_slip;
}

double StandingWave::horizontal_momentum(const Particles<2>& P) const {
  // Without side walls the whole wavelength's momentum is zero: that of its first half, [0, L).
  double sum = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid && (side_walls_ || std::fmod(P.x[i][0] + 2.0 * width_, 2.0 * width_) < width_))
      sum += P.m[i] * P.v[i][0];
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return sum;
}

// A swing's extreme is its largest |momentum| between two crossings (the particles' noise makes
// small wiggles that a turning-point test would count).
void StandingWave::accumulate(const Particles<2>& P, double t, double) {
  const double c = horizontal_momentum(P);
  if (samples_ > 0 && (c > 0.0) != (last_ > 0.0)) {
    crossings_.push_back(last_t_ + (t - last_t_) * last_ / (last_ - c));  // linear in time between the samples
    if (crossings_.size() >= 2) extremes_.push_back(swing_max_), extreme_times_.push_back(swing_max_t_);
    swing_max_ = 0.0;
  }
  if (std::abs(c) > swing_max_) swing_max_ = std::abs(c), swing_max_t_ = t;
  last_ = c, last_t_ = t;
  ++samples_;
}

nlohmann::json StandingWave::accumulated_state() const {
  return {{"crossings", crossings_},     {"extremes", extremes_}, {"extreme_times", extreme_times_},
          {"last_t", last_t_},           {"last", last_},         {"swing_max", swing_max_},
          {"swing_max_t", swing_max_t_}, {"samples", samples_}};
}

void StandingWave::restore_accumulated_state(const nlohmann::json& s) {
  if (s.is_null()) return;
  crossings_ = s.at("crossings").get<std::vector<double>>();
  extremes_ = s.at("extremes").get<std::vector<double>>();
  extreme_times_ = s.at("extreme_times").get<std::vector<double>>();
  last_t_ = s.at("last_t"), last_ = s.at("last"), samples_ = s.at("samples");
  swing_max_ = s.at("swing_max"), swing_max_t_ = s.at("swing_max_t");
}

std::map<std::string, double> StandingWave::errors(const Particles<2>&, double) const {
  // Whole periods only: crossing 0 to crossing 2m.
  const std::size_t periods = crossings_.size() >= 3 ? (crossings_.size() - 1) / 2 : 0;
  const double T = periods > 0 ? (crossings_[2 * periods] - crossings_.front()) / periods : std::nan("");
  // Least squares of log(extreme) against time: every swing counts, none decides alone.
  double rate = std::nan("");
  const std::size_t n = extremes_.size();
  if (n >= 2 && extreme_times_.back() > extreme_times_.front()) {
    double st = 0.0, sy = 0.0, stt = 0.0, sty = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const double t = extreme_times_[k], y = std::log(extremes_[k]);
      st += t, sy += y, stt += t * t, sty += t * y;
    }
    rate = -(n * sty - st * sy) / (n * stt - st * st);
  }
  const double T0 = linear_period();
  return {{"period", T}, {"period_rel", std::abs(T - T0) / T0}, {"damping_rate", rate}};
}

std::string StandingWave::unmeasured_reason(const std::string& name) const {
  if (name == "period" || name == "period_rel")
    return "the horizontal momentum changed sign " + std::to_string(crossings_.size()) +
           " times, fewer than the 3 a period needs; raise -t_end";
  if (name == "damping_rate") return "fewer than two whole swings of the horizontal momentum; raise -t_end";
  return "";
}

nlohmann::json StandingWave::parameters() const {
  const double k = M_PI / width_;
  return {{"nx", nx_},
          {"tank_width", width_},
          {"depth", depth_},
          {"amplitude", amplitude_},
          {"g", g_},
          {"re", re_},
          {"rho0", rho0_},
          {"wall_layers", wall_layers_},
          {"side_walls", side_walls_},
          {"free_slip_side_walls", free_slip_side_walls_},
          {"linear_period", linear_period()},
          {"bulk_damping_rate", 2.0 * physics().nu * k * k},
          {"damping_rate_theory", damping_rate_theory()}};
}

}  // namespace sph
