#include "solvers/isph/isph_solver.hpp"

#include <cmath>

#include "src/boundary/adami_wall.hpp"
#include "src/core/options.hpp"
#include "src/run/log_events.hpp"
#include "src/sph/free_surface.hpp"
#include "src/sph/operators.hpp"

namespace sph {

namespace {
const char* const gradient_names[] = {"corrected", "difference", "symmetric"};

PetscErrorCode read_options(PetscReal* cfl, PetscBool* shifting, PetscReal* shift_A, PetscInt* gradient,
                            PetscReal* fs_threshold) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "ISPH projection solver (-solver isph)", "Solver");
  PetscCall(PetscOptionsReal("-cfl", "Advective Courant number: dt <= cfl h / U", "", *cfl, cfl, nullptr));
  PetscCall(PetscOptionsBool("-shifting", "Particle shifting (Lind et al. 2012)", "", *shifting, shifting, nullptr));
  PetscCall(PetscOptionsReal("-shift_coefficient", "Shifting coefficient A in D = A h^2 per step (stable up to ~0.5)", "", *shift_A,
                             shift_A, nullptr));
  PetscCall(PetscOptionsEList("-pressure_gradient",
                              "Pressure gradient: corrected (Bonet & Lok), difference, symmetric (Monaghan)", "",
                              gradient_names, 3, gradient_names[*gradient], gradient, nullptr));
  PetscCall(PetscOptionsReal("-free_surface_threshold",
                             "Free-surface particles: div r below this (0: 1.5 in 2D, 2.4 in 3D; Lind et al. 2012)", "",
                             *fs_threshold, fs_threshold, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

template <int D> void IsphSolver<D>::set_from_options() {
  PetscReal cfl = cfl_, A = shifting_model_.A;
  PetscInt gradient = static_cast<PetscInt>(gradient_);
  SPH_PETSC(read_options(&cfl, &shifting_, &A, &gradient, &free_surface_threshold_));
  require(free_surface_threshold_ >= 0 && free_surface_threshold_ < D, "-free_surface_threshold",
          "in [0, dimension)", free_surface_threshold_);
  require(cfl > 0 && cfl <= 1.0, "-cfl", "in (0, 1]", cfl);
  require(A >= 0 && A <= 1, "-shift_coefficient", "in [0, 1]", A);
  cfl_ = cfl, shifting_model_.A = A, gradient_ = static_cast<PressureGradient>(gradient);
  ppe_.set_from_options();
}

template <int D> void IsphSolver<D>::setup(Scene<D>& scene) {
  refuse_unmodelled(scene.physics, name(), false, false);
  scene_ = &scene;
  Particles<D>& P = scene.particles;
  // Divergence-free ISPH: density stays at its reference value (walls included).
  for (std::size_t i = 0; i < P.n_owned; ++i) P.rho[i] = scene.physics.rho0;
  walls_ = has_walls(P);
  ppe_.use_nonsymmetric(walls_ || scene.physics.free_surface);
  if (free_surface_threshold_ <= 0) free_surface_threshold_ = default_free_surface_threshold<D>();
  scene.neighbourhood.update(P, true);
}

template <int D> double IsphSolver<D>::max_speed() const {
  const Particles<D>& P = scene_->particles;
  double u2 = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) u2 = std::max(u2, P.v[i].squaredNorm());
  MPI_Allreduce(MPI_IN_PLACE, &u2, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return std::sqrt(u2);
}

template <int D> double IsphSolver<D>::stable_dt() const {
  const double h = scene_->kernel.h();
  const Physics<D>& phys = scene_->physics;
  // The reference speed bounds the step too, so a fluid at rest does not take an unbounded step.
  double dt = cfl_ * h / std::max(max_speed(), phys.U);
  if (phys.viscous()) dt = std::min(dt, viscous_dt_factor_ * h * h / phys.nu);  // Morris et al. (1997)
  return dt;
}

template <int D> std::vector<Vector<D>> IsphSolver<D>::pressure_gradient() const {
  const Particles<D>& P = scene_->particles;
  const NeighbourList<D>& nl = scene_->neighbourhood.list();
  const Kernel<D>& K = scene_->kernel;
  switch (gradient_) {
    case PressureGradient::Corrected:
      return gradient_corrected(P, nl, K, P.p);
    case PressureGradient::Difference: return gradient_difference(P, nl, K, P.p);
    case PressureGradient::Symmetric: return gradient_symmetric(P, nl, K, P.p);
  }
  return {};
}

template <int D> StepReport IsphSolver<D>::step(double dt) {
  Particles<D>& P = scene_->particles;
  Neighbourhood<D>& nh = scene_->neighbourhood;
  const Kernel<D>& K = scene_->kernel;
  const Physics<D>& phys = scene_->physics;
  const std::size_t n = P.n_owned;
  nh.update(P);

  auto fluid = [&](std::size_t i) { return P.kind[i] == kFluid; };  // walls keep their prescribed motion

  // Prediction with the non-pressure forces at x^n.
  LogEventScope log_forces(LogEvent::Forces);
  const std::vector<Vector<D>> u_old(P.v.begin(), P.v.begin() + n);
  std::vector<Vector<D>> u_star = P.v;
  if (phys.viscous()) {
    // No-slip walls: the viscous term sees the mirrored wall velocity (Adami et al. 2012).
    std::vector<Vector<D>> u_visc =
        walls_ ? AdamiWall<D>::viscous_velocity(AdamiWall<D>::stencil(P, nh.list(), K), P) : P.v;
    if (walls_) nh.halo().update(u_visc);
    const std::vector<Vector<D>> lap = laplacian_morris(P, nh.list(), K, u_visc);
    for (std::size_t i = 0; i < n; ++i)
      if (fluid(i)) u_star[i] += dt * phys.nu * lap[i];
  }
  if (phys.has_body_force())
    for (std::size_t i = 0; i < n; ++i)
      if (fluid(i)) u_star[i] += dt * phys.gravity;
  log_forces.end();

  // Advect to x* = x^n + dt u^n, where the projection is made: the pressure then balances this
  // step's motion (Cummins & Rudman 1999; Lind et al. 2012) instead of lagging a step behind.
  for (std::size_t i = 0; i < n; ++i)
    if (fluid(i)) P.x[i] += dt * u_old[i];
  nh.update(P);
  nh.halo().update(u_star);

  // Projection: div(grad p / rho) = div(u*) / dt.
  LogEventScope log_assembly(LogEvent::PpeAssembly);
  std::vector<double> source = divergence(P, nh.list(), K, u_star);
  for (double& s : source) s /= dt;
  // Free surface (Lind et al. 2012): surface particles at x* get p = 0.
  std::vector<char> surface;
  if (phys.free_surface) surface = free_surface_particles(P, nh.list(), K, free_surface_threshold_);
  ppe_.assemble(P, nh, K, phys.gravity, phys.free_surface ? &surface : nullptr);
  log_assembly.end();
  LogEventScope log_solve(LogEvent::PpeSolve);
  // The first solve starts from zero: the case's initial pressure is not the projection's.
  const StepReport report = ppe_.solve(source, P.m, P.p, solves_ > 0);
  ++solves_;
  log_solve.end();
  nh.halo().update(P.p);

  // Correction, and the trapezoidal position update x^{n+1} = x^n + dt (u^n + u^{n+1}) / 2.
  LogEventScope log_correction(LogEvent::Forces);
  const std::vector<Vector<D>> grad_p = pressure_gradient();
  for (std::size_t i = 0; i < n; ++i) {
    if (!fluid(i)) continue;
    P.v[i] = u_star[i] - (dt / P.rho[i]) * grad_p[i];
    P.x[i] += (0.5 * dt) * (P.v[i] - u_old[i]);
  }
  log_correction.end();
  if (shifting_) shift();
  return report;
}

template <int D> void IsphSolver<D>::shift() {
  Particles<D>& P = scene_->particles;
  Neighbourhood<D>& nh = scene_->neighbourhood;
  nh.update(P);  // shifting works on the new positions
  std::vector<char> surface;
  if (scene_->physics.free_surface) surface = free_surface_particles(P, nh.list(), scene_->kernel, free_surface_threshold_);
  shift_particles(P, nh, scene_->kernel, shifting_model_, scene_->dx, {}, surface.empty() ? nullptr : &surface);
}

template <int D> nlohmann::json IsphSolver<D>::describe() const {
  const Physics<D>& phys = scene_->physics;
  nlohmann::json models = nlohmann::json::object();
  models["pressure_laplacian"] = "CumminsRudman";
  if (walls_)
    models["walls"] = {{"model", "AdamiWall"},
                       {"ppe", phys.free_surface ? "extrapolation rows" : "extrapolation rows, one fluid pressure pinned"}};
  if (phys.free_surface)
    models["free_surface"] = {{"model", "LindFreeSurface"}, {"threshold_div_r", free_surface_threshold_}};
  models["pressure_gradient"] = gradient_names[static_cast<int>(gradient_)];
  if (phys.viscous()) models["viscosity"] = {{"model", "MorrisViscosity"}, {"nu", phys.nu}};
  if (phys.has_body_force()) models["body_force"] = phys.describe()["gravity"];
  if (shifting_) models["shifting"] = shifting_model_.describe();
  return {{"models", models}, {"cfl", cfl_}, {"ksp", ppe_.describe()}};
}

template class IsphSolver<1>;
template class IsphSolver<2>;
template class IsphSolver<3>;

}  // namespace sph
