#include "solvers/wcsph/wcsph_solver.hpp"

#include <cmath>
#include <sstream>

#include "src/boundary/adami_wall_model.hpp"
#include "src/core/log_events.hpp"
#include "src/core/options.hpp"
#include "src/sph/consistent_laplacian.hpp"
#include "src/sph/free_surface.hpp"
#include "src/sph/kernel_average.hpp"
#include "src/sph/leapfrog.hpp"
#include "src/sph/operators.hpp"
#include "src/sph/step_limits.hpp"

namespace sph {

template <int D> void WcsphSolver<D>::setup(Discretisation<D>& disc) {
  refuse_unmodelled(disc.physics, name(), false, false);
  refuse_unmodelled_open_boundaries(disc, name(), true);
  disc_ = &disc;
  Particles<D>& P = disc.particles;
  set_start_state(disc);
  walls_ = has_walls(P);
  extrapolated_ = walls_ || disc.open.any();
  disc.walls = make_wall_model<D>(wall_pressure_, disc.bodies);
  if (outlet_pressure_ == OutletPressure::Transmissive && disc.open.has_outlet())
    disc.open.use_transmissive_outlets(P, disc.physics.rho0 * eos_.c0);
  acc_ = P.fields.declare_vector("acceleration", kCarried, P.size());
  drho_ = P.fields.declare_scalar("density_rate", kCarried, P.size());
  free_surface_.setup(P, disc.physics.free_surface, BandScan::Walls);  // shifting only: a tank's corners
  // Under gravity Molteni's term diffuses the hydrostatic stratification: mass flows down, and still
  // water sank into its floor (t = 19 at 40 particles a unit). Fourtakas et al. (2019) diffuse the
  // density's difference from the hydrostatic one instead.
  if (!diffusion_chosen_ && diffusion_ == DensityDiffusion::Molteni && disc.physics.has_body_force())
    diffusion_ = DensityDiffusion::Fourtakas;
  declare_energy_budget(disc);
  resolve_choices(disc);
  disc.neighbourhood.update(P, true);
  compute_rates();  // the start's densities (by summation, if chosen), pressures and rates
}

// The sound speed, and the start's velocity (-prepared_start) and density from the case's pressure.
template <int D> void WcsphSolver<D>::set_start_state(Discretisation<D>& disc) {
  Particles<D>& P = disc.particles;
  eos_.rho0 = disc.physics.rho0;
  eos_.c0 = c0_ > 0 ? c0_ : c0_factor_ * speed_scale();
  // The Tait EOS cannot give a density for p <= -B: such a start would be NaN from t = 0.
  double p_min = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i) p_min = std::min(p_min, P.p[i]);
  MPI_Allreduce(MPI_IN_PLACE, &p_min, 1, MPI_DOUBLE, MPI_MIN, PETSC_COMM_WORLD);
  if (p_min <= -eos_.B()) {
    std::ostringstream msg;
    msg << "the sound speed c0 = " << eos_.c0 << " is too low for this scene: its initial pressure " << p_min
        << " is below -rho0 c0^2/gamma, where the Tait EOS has no density (the initial state would be NaN); raise "
        << (c0_ > 0 ? "-c0" : "-c0_factor") << " so that c0 > " << std::sqrt(-p_min * eos_.gamma / eos_.rho0);
    throw Error(msg.str());
  }
  // An incompressible start is not a weakly compressible flow: the particles carry their pressure,
  // which the incompressible field changes along their paths (Dp/Dt), so without the compressive
  // velocity that makes the continuity equation follow it the start rings with sound of pressure
  // O(Mach) times the flow's. Under c0 ~ 1/h that is an O(h) pressure error, which the prepared start
  // removes (docs/verification/taylor_green.md, "WCSPH with particle-scale delta-SPH").
  if (prepared_start_) {
    if (!disc.physics.slow_manifold_velocity)
      throw Error(
          "-prepared_start needs a case that gives its start's slow-manifold velocity (taylor_green "
          "does; this case does not): remove the option");
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kFluid) P.v[i] += disc.physics.slow_manifold_velocity(P.x[i], eos_.c0);
  }
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    // The case's initial pressure sets the density (inverse EOS); particle volumes stay as laid out.
    const double rho = eos_.density(P.p[i]);
    P.m[i] *= rho / P.rho[i];
    P.rho[i] = rho;
  }
}

// The choices that depend on the scene (diffusion, closed volume, wall bounding, pressure gradient),
// and the refusal of those it cannot take.
template <int D> void WcsphSolver<D>::resolve_choices(const Discretisation<D>& disc) {
  // Where a wall or a free surface cuts the kernel support, the kernel average of rho is not its
  // resolved part, and rho minus it would not be particle-scale noise.
  if (diffusion_ == DensityDiffusion::Particle && (walls_ || disc.physics.free_surface))
    throw Error(
        "-density_diffusion particle needs a scene without walls or a free surface (the kernel average that "
        "separates the particle scale is cut there); use -density_diffusion molteni");
  // A closed or periodic box fixes the fluid's volume; a free surface lets the weakly compressible
  // fluid change it (hydrostatic compression), so there the constraint would be wrong.
  if (closed_volume_option_ > 0 && disc.physics.free_surface)
    throw Error(
        "-closed_volume 1 needs a scene without a free surface (a free surface lets the fluid's volume "
        "change); remove the option");
  if (closed_volume_option_ > 0 && disc.open.any())
    throw Error(
        "-closed_volume 1 needs a scene without inlets or outlets (they let the fluid's volume change); "
        "remove the option");
  closed_volume_ =
      closed_volume_option_ < 0 ? !disc.physics.free_surface && !disc.open.any() : closed_volume_option_ > 0;
  // The free surface's default kernel sums nearly flat over a wall's particles, which then let fluid
  // through: the bounding holds the walls there (free_surface.md, "A wall that holds without the ripple").
  bound_to_walls_ = wall_bounding_option_ < 0 ? disc.physics.free_surface : wall_bounding_option_ > 0;
  // The corrected gradient sees no pressure beyond a free surface, and WCSPH has no surface condition
  // that gives it one (docs/verification/free_surface.md, "What moves WCSPH's lattice").
  if (gradient_ == WcsphGradient::Corrected && disc.physics.free_surface)
    throw Error(
        "-wcsph_pressure_gradient corrected needs a scene without a free surface (WCSPH imposes the surface's zero "
        "pressure through the symmetric form; with the corrected one still water blows up at once): use "
        "-wcsph_pressure_gradient auto or symmetric");
  // The kernel sum is cut off at a free surface: its particles' density falls by up to half, and the
  // pressure that follows pulls the surface in: still water blows up at once.
  if (density_ == DensityMethod::Summation && disc.physics.free_surface)
    throw Error(
        "-density summation needs a scene without a free surface (the kernel sum is cut off at the surface, "
        "where the density it gives falls by up to half and still water blows up at once): use -density "
        "continuity");
  if (gradient_ == WcsphGradient::Auto)
    gradient_ = disc.physics.free_surface ? WcsphGradient::Symmetric : WcsphGradient::Corrected;
}

// The sound speed keeps density variations near 1/c0_factor^2 only if c0 exceeds every speed whose
// square sets a pressure scale (Morris, Fox & Zhu 1997, eq. 4.1): the flow speed U (dynamic pressure
// rho U^2), the body-force head sqrt(|g| H) with H the fluid's extent along g (rho g H), and the
// viscous sqrt(nu U / L) with L its smallest extent (mu U / L, which dominates at low Reynolds
// number). With U alone a Stokes flow driven by a body force is compressed and its drag too low
// (docs/user-guide.md, "Drag of a periodic array of cylinders").
// The energy budget, with the Tait fluid's elastic energy, and the rates' parts by cause that it
// credits the kicks with (carried: the next step's opening kick applies them), where the cause is on.
template <int D> void WcsphSolver<D>::declare_energy_budget(const Discretisation<D>& disc) {
  Particles<D>& P = disc.particles;
  const wcsph::TaitEos eos = eos_;
  energy_ = EnergyBudget(disc.physics.gravity, disc.neighbourhood.domain().periodic,
                         {[eos](double rho) { return eos.elastic_energy(rho); },
                          [eos](double rho) { return eos.pressure(rho) / (rho * rho); }});
  if (disc.physics.viscous()) viscous_acc_ = P.fields.declare_vector("viscous_acceleration", kCarried, P.size());
  if (av_.active()) av_acc_ = P.fields.declare_vector("artificial_viscosity_acceleration", kCarried, P.size());
  if (diffusion_ != DensityDiffusion::None && density_ == DensityMethod::Continuity)
    diffusion_rate_ = P.fields.declare_scalar("diffusion_density_rate", kCarried, P.size());
}

template <int D> double WcsphSolver<D>::speed_scale() {
  const Particles<D>& P = disc_->particles;
  const Physics<D>& phys = disc_->physics;
  Vector<D> lo = Vector<D>::Constant(1e300), hi = Vector<D>::Constant(-1e300);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) lo = lo.cwiseMin(P.x[i]), hi = hi.cwiseMax(P.x[i]);
  MPI_Allreduce(MPI_IN_PLACE, lo.data(), D, MPI_DOUBLE, MPI_MIN, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, hi.data(), D, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  const Vector<D> extent = (hi - lo).cwiseMax(0.0) + Vector<D>::Constant(disc_->dx);  // particle centres: + dx
  const double g = phys.gravity.norm();
  const double H = g > 0 ? (phys.gravity.cwiseAbs() / g).dot(extent) : 0.0;
  const double speeds[3] = {phys.U, std::sqrt(g * H), std::sqrt(phys.nu * phys.U / extent.minCoeff())};
  const char* names[3] = {"flow speed U_ref", "body-force head sqrt(|g| H)", "viscous sqrt(nu U_ref / L)"};
  const int k = static_cast<int>(std::max_element(speeds, speeds + 3) - speeds);
  speed_scale_name_ = names[k];
  return speeds[k];
}

template <int D> void WcsphSolver<D>::update_pressure() {
  Particles<D>& P = disc_->particles;
  // A transmissive outlet's particles carry their pressure (src/boundary/open_boundaries.hpp), their
  // density follows it.
  const bool transmissive = disc_->open.outlet_pressure() == OutletPressure::Transmissive;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (!transmissive || P.kind[i] != kOutlet) P.p[i] = eos_.pressure(P.rho[i]);
  P.written(P.p);
  disc_->open.hold_outlet_pressure(P, [this](double p) { return eos_.density(p); });
  if (!extrapolated_) return;
  // Adami et al. (2012): wall (and inlet) pressure extrapolated from the fluid, their density from the EOS.
  const Neighbourhood<D>& nh = disc_->neighbourhood;
  disc_->walls->extrapolate_pressure(P, nh, disc_->kernel, disc_->physics.gravity);
  P.written(P.p);
  const bool outlets = disc_->open.transmit_outlet_pressure(P, nh.list(), disc_->kernel);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (extrapolates_pressure(P.kind[i]) || (outlets && P.kind[i] == kOutlet))
      P.rho[i] = eos_.density(std::max(P.p[i], -0.9 * eos_.B()));
  P.written(P.p), P.written(P.rho);
}

// Densities by summation (-density summation), their change of elastic energy credited to pressure.
template <int D> void WcsphSolver<D>::sum_densities() {
  Particles<D>& P = disc_->particles;
  const std::vector<double> rho = density_summation(P, disc_->neighbourhood.list(), disc_->kernel);
  const double before = energy_.internal_energy(P);
  std::copy(rho.begin(), rho.end(), P.rho.begin());
  if (energy_.started())
    energy_.add_change(EnergyCause::Pressure, EnergyForm::Internal, before, energy_.internal_energy(P));
  P.written(P.rho);
}

template <int D> void WcsphSolver<D>::compute_rates() {
  Particles<D>& P = disc_->particles;
  const Neighbourhood<D>& nh = disc_->neighbourhood;
  const NeighbourList<D>& nl = nh.list();
  const Kernel<D>& K = disc_->kernel;
  const Physics<D>& phys = disc_->physics;

  LogEventScope log_density(LogEvent::Density);
  const DiffusionFields diffusion = densities_and_pressures();
  log_density.end();
  const LogEventScope log_forces(LogEvent::Forces);
  // No-slip walls: the viscous term sees the mirrored wall velocity (Adami et al. 2012).
  std::vector<Vector<D>> u_visc;
  if (walls_ && phys.viscous()) u_visc = disc_->walls->viscous_velocity(P, nh, K, P.v);
  const std::vector<Vector<D>>& uv = u_visc.empty() ? P.v : u_visc;
  const std::vector<double>& diffused = diffusion.rho_fine.empty() ? P.rho : diffusion.rho_fine;
  wcsph::RatesInputs<D> in(P, uv, diffusion.grad_rho, diffused, eos_, av_);
  in.forms = rate_forms();
  in.h = K.h(), in.inv_R = 1.0 / K.support_radius(), in.nu = phys.nu;
  in.delta_h_c0 = delta_ * K.h() * eos_.c0;
  // Moving bodies push the fluid: the continuity equation sees their velocity (sliding walls at rest).
  std::vector<Vector<D>> wall_velocity;
  if (disc_->walls->moving()) {
    wall_velocity = disc_->walls->continuity_velocities(P);
    in.wall_velocity = &wall_velocity;
  }
  if (phys.free_surface) {
    // Remembered: the flags' hysteresis, and the shift at the end of the step reuses them.
    surface_ = free_surface_.detect(P, nl, K, true);
    if (in.forms.diffuse && !diffusion_at_surface_) {
      surface_flags_ = surface_flags_with_ghosts(surface_, P, nh);
      in.surface = &surface_flags_;
    }
  }
  if (diffusion_ == DensityDiffusion::Fourtakas)
    in.hydrostatic_density_gradient = eos_.rho0 * phys.gravity / (eos_.c0 * eos_.c0);
  check_ghosts(nl, uv, "the viscous term's velocity");
  check_ghosts(nl, diffused, "the diffused density");
  if (!in.grad_rho.empty()) check_ghosts(nl, in.grad_rho, "the density gradient");
  if (in.surface) check_ghosts(nl, *in.surface, "the surface flags");
  if (in.wall_velocity) check_ghosts(nl, *in.wall_velocity, "the walls' velocity");
  sum_rates(in);
  add_body_force_and_limit();
}

// The forms this run's options and physics choose.
template <int D> wcsph::RateForms WcsphSolver<D>::rate_forms() const {
  wcsph::RateForms f;
  f.viscous = disc_->physics.viscous();
  f.consistent_viscous = operators_ == OperatorSet::Consistent && f.viscous;
  f.corrected_gradient = gradient_ == WcsphGradient::Corrected;
  f.continuity = density_ == DensityMethod::Continuity;
  // The corrected divergence goes with the corrected pressure gradient. The symmetric gradient's
  // discrete adjoint is nearly the plain divergence: together they exchange energy between pressure
  // work and compression but for the factor rho_i / rho_j in each continuity pair
  // (docs/verification/free_surface.md, "Energy budgets"). Mixed with the corrected divergence (a free surface, where
  // auto picks the symmetric gradient) the dam-break front runs far ahead of the experiment
  // (docs/verification/dam_break.md, "Design measurements").
  f.corrected_continuity = operators_ == OperatorSet::Consistent && f.corrected_gradient && f.continuity;
  f.diffuse = diffusion_ != DensityDiffusion::None && f.continuity;
  return f;
}

// The densities (by summation, if chosen) and pressures at the current positions, and the fields the
// density diffusion reads beside them.
template <int D> typename WcsphSolver<D>::DiffusionFields WcsphSolver<D>::densities_and_pressures() {
  Particles<D>& P = disc_->particles;
  Neighbourhood<D>& nh = disc_->neighbourhood;
  const std::size_t n = P.n_owned;
  if (density_ == DensityMethod::Summation) sum_densities();
  update_pressure();
  DiffusionFields f;
  // Antuono's correction needs the renormalised density gradient on both sides of each pair.
  if (diffusion_ == DensityDiffusion::Antuono) {
    f.grad_rho = gradient_corrected(P, nh.list(), disc_->kernel, P.rho);
    nh.halo().update(f.grad_rho);  // step-local: refreshed by hand
  }
  // -density_diffusion particle: the diffusion acts on rho minus its kernel average (every support is
  // all fluid: setup refuses walls and free surfaces).
  if (diffusion_ == DensityDiffusion::Particle && density_ == DensityMethod::Continuity) {
    f.rho_fine.assign(P.rho.begin(), P.rho.begin() + n);
    const KernelAverage<double> average = kernel_average_in_fluid(P, nh, disc_->kernel, f.rho_fine, nullptr);
    for (std::size_t i = 0; i < n; ++i) f.rho_fine[i] = P.rho[i] - average.average[i];
    nh.halo().update(f.rho_fine);  // step-local: refreshed by hand
  }
  return f;
}

// The pair loop: each fluid particle's acceleration and density rate (and their parts by cause), the
// corrected forms and the viscous Laplacian's smoothing error finished after it.
template <int D> void WcsphSolver<D>::sum_rates(const wcsph::RatesInputs<D>& in) {
  Particles<D>& P = disc_->particles;
  std::vector<Vector<D>>& acc = P.fields[acc_];
  std::vector<double>& drho = P.fields[drho_];
  const std::size_t n = P.n_owned;
  const wcsph::RateForms& forms = in.forms;
  // Sums finished after the pair loop: the moment matrix of the kernel-gradient correction, the
  // velocity gradient of the corrected continuity equation and the pressure-difference sum.
  std::vector<Tensor<D>> M(forms.corrected_gradient ? n : 0, Tensor<D>::Zero()),
      grad_u(forms.corrected_continuity ? n : 0, Tensor<D>::Zero());
  std::vector<Vector<D>> grad_p(forms.corrected_gradient ? n : 0, Vector<D>::Zero());
  acc.assign(n, Vector<D>::Zero());
  drho.assign(n, 0.0);
  // The rates' parts by cause, for the energy budget (the pressure's is the rest of acc).
  const Vector<D> zero = Vector<D>::Zero();
  std::vector<Vector<D>>* viscous_part = zeroed(viscous_acc_, zero);
  std::vector<Vector<D>>* av_part = zeroed(av_acc_, zero);
  std::vector<double>* diffusion_part = zeroed(diffusion_rate_, 0.0);
  // Each particle's sums live in locals while its pairs are visited, and are stored once. The
  // consistent viscous Laplacian is gathered in the same loop as the rest, which saves a pass over the
  // pairs (docs/performance.md, "Design measurements").
  // The viscous Laplacian's smoothing error removed (src/sph/laplacian_smoothing.hpp) needs its
  // factors and values after the loop; the free surface cuts the supports, where it is left off.
  const bool smoothing =
      forms.consistent_viscous && viscous_laplacian_ == ViscousLaplacian::Fourth && !disc_->physics.free_surface;
  std::vector<LaplacianCorrection<D>> lap_factors(smoothing ? n : 0);
  std::vector<Vector<D>> lap_u(smoothing ? n : 0, Vector<D>::Zero());
  const double nu = disc_->physics.nu;
  for_each_particle_pairs(P, disc_->neighbourhood.list(), disc_->kernel, [&](std::size_t i, auto&& visit_pairs) {
    if (P.kind[i] != kFluid) return;  // walls move as prescribed
    wcsph::RateSums<D> sums(laplacian_pair_buffer<D>());
    visit_pairs([&](int, int j, const PairGeometry<D>& g) { wcsph::add_rates_pair(in, sums, i, j, g); });
    if (forms.consistent_viscous) {
      const Vector<D> lap = sums.viscous.finish(in.inv_R, smoothing ? &lap_factors[i] : nullptr);
      sums.acc_viscous += nu * lap;
      if (smoothing) lap_u[i] = lap;
    }
    acc[i] = sums.acc + sums.acc_av + sums.acc_viscous, drho[i] = sums.drho + sums.drho_diffusion;
    if (viscous_part) (*viscous_part)[i] = sums.acc_viscous;
    if (av_part) (*av_part)[i] = sums.acc_av;
    if (diffusion_part) (*diffusion_part)[i] = sums.drho_diffusion;
    if (forms.corrected_gradient) M[i] = sums.M, grad_p[i] = sums.grad_p;
    if (forms.corrected_continuity) grad_u[i] = sums.grad_u;
  });
  if (smoothing) remove_viscous_smoothing_error(lap_factors, lap_u, viscous_part);
  if (forms.corrected_gradient) apply_corrected_forms(M, grad_p, grad_u);
}

// The viscous Laplacian's smoothing error removed after the pair loop (src/sph/laplacian_smoothing.hpp),
// from its factors and values lap_u; the change goes to the viscous part too.
template <int D> void WcsphSolver<D>::remove_viscous_smoothing_error(const std::vector<LaplacianCorrection<D>>& factors,
                                                                     const std::vector<Vector<D>>& lap_u,
                                                                     std::vector<Vector<D>>* viscous_part) {
  Particles<D>& P = disc_->particles;
  std::vector<Vector<D>>& acc = P.fields[acc_];
  std::vector<Vector<D>> corrected = lap_u;
  remove_laplacian_smoothing_error(P, disc_->neighbourhood, disc_->kernel, factors, corrected);
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) {
      const Vector<D> removed = disc_->physics.nu * (corrected[i] - lap_u[i]);
      acc[i] += removed;
      if (viscous_part) (*viscous_part)[i] += removed;
    }
}

// The corrected forms: d rho_i/dt = -rho_i tr(L_i grad u_i) and a_i = -L_i grad p_i / rho_i, both
// exact for linear fields on any particle distribution (the plain forms are O(1) wrong in the
// disorder; Negi & Ramachandran 2022 found them the obstacle to second order). grad_u empty: the
// plain continuity equation.
template <int D> void WcsphSolver<D>::apply_corrected_forms(const std::vector<Tensor<D>>& M,
                                                            const std::vector<Vector<D>>& grad_p,
                                                            const std::vector<Tensor<D>>& grad_u) {
  Particles<D>& P = disc_->particles;
  std::vector<Vector<D>>& acc = P.fields[acc_];
  std::vector<double>& drho = P.fields[drho_];
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    if (P.kind[i] != kFluid) continue;
    const Tensor<D> L = correction_from_moments(M[i]);
    acc[i] -= (L * grad_p[i]) / P.rho[i];
    if (!grad_u.empty()) drho[i] -= P.rho[i] * (L * grad_u[i]).trace();
  }
}

// Gravity, the closed box's volume constraint, and the largest acceleration (the force step limit).
template <int D> void WcsphSolver<D>::add_body_force_and_limit() {
  Particles<D>& P = disc_->particles;
  std::vector<Vector<D>>& acc = P.fields[acc_];
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) acc[i] += disc_->physics.gravity;
  if (density_ == DensityMethod::Continuity && closed_volume_) remove_net_volume_rate();
  double a2 = 0.0;
  for (const auto& a : acc) a2 = std::max(a2, a.squaredNorm());
  MPI_Allreduce(MPI_IN_PLACE, &a2, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  max_acc_ = std::sqrt(a2);
}

// A closed or periodic box holds a fixed mass in a fixed volume, so the fluid's mean density cannot
// change, however compressible the fluid. The discrete continuity equation does not know that: its
// divergence (corrected or plain) is not the time derivative of any volume of the particle set, and on
// disordered particles its volume integral has a bias of the size of the truncation error, the same
// sign for as long as the flow lasts, mostly from the interior and independent of dt
// (docs/verification/lid_driven_cavity.md, "WCSPH in a closed box keeps its volume"). The net rate,
// which no flow in the box can have, is taken out as a uniform compression rate, as ISPH spreads a
// closed domain's net PPE source evenly over its rows.
template <int D> void WcsphSolver<D>::remove_net_volume_rate() {
  Particles<D>& P = disc_->particles;
  std::vector<double>& drho = P.fields[drho_];
  // Volume rate of the fluid, sum_i dV_i/dt = -sum_i V_i (d rho_i/dt) / rho_i, and its volume.
  double sums[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) {
      const double V = P.m[i] / P.rho[i];
      sums[0] += V * drho[i] / P.rho[i];
      sums[1] += V;
    }
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  if (sums[1] <= 0.0) return;
  const double mean_rate = sums[0] / sums[1];
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) drho[i] -= P.rho[i] * mean_rate;
}

template <int D> double WcsphSolver<D>::stable_dt() const {
  const Particles<D>& P = disc_->particles;
  const Physics<D>& phys = disc_->physics;
  const double h = disc_->kernel.h();
  double buf[2] = {0.0, 0.0};  // max |u|^2, max c
  for (std::size_t i = 0; i < P.n_owned; ++i) {
    buf[0] = std::max(buf[0], P.v[i].squaredNorm());
    buf[1] = std::max(buf[1], eos_.sound_speed(P.rho[i]));
  }
  MPI_Allreduce(MPI_IN_PLACE, buf, 2, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  double dt = cfl_ * h / (buf[1] + std::sqrt(buf[0]));
  if (phys.viscous()) dt = std::min(dt, kViscousStepFactor * h * h / phys.nu);
  if (max_acc_ > 0.0) dt = std::min(dt, kForceStepFactor * std::sqrt(h / max_acc_));
  return dt;
}

// A step as its phases: kick, drift, the rates at the new positions and kick (leapfrog), the shift,
// the wall bounding (-wall_bounding), and the pressures of the new densities.
template <int D> StepReport WcsphSolver<D>::step(double dt) {
  const Particles<D>& P = disc_->particles;
  energy_.start(P);
  kick_drift_rates_kick(dt);
  if (shifting_model_.enabled) {
    const auto before = energy_.energies(P);
    shift(dt);
    energy_.add_change(EnergyCause::Shifting, before, energy_.energies(P));
  }
  if (bound_to_walls_ && walls_) {
    disc_->neighbourhood.update(disc_->particles);
    const auto before = energy_.energies(P);
    bounded_ += wall_bounding_.apply(disc_->particles, disc_->neighbourhood, disc_->kernel, disc_->dx, eos_.rho0,
                                     disc_->walls->moving());
    energy_.add_change(EnergyCause::WallBounding, before, energy_.energies(P));
  }
  const LogEventScope log_density(LogEvent::Density);
  disc_->open.relax_outlet_pressure(disc_->particles, dt, outlet_relaxation_ * eos_.c0,
                                    disc_->neighbourhood.domain().length());
  update_pressure();
  return {};
}

template <int D> void WcsphSolver<D>::kick_drift_rates_kick(double dt) {
  Particles<D>& P = disc_->particles;
  std::vector<Vector<D>>& acc = P.fields[acc_];
  std::vector<double>& drho = P.fields[drho_];
  Neighbourhood<D>& nh = disc_->neighbourhood;
  const std::size_t n = P.n_owned;
  const bool continuity = density_ == DensityMethod::Continuity;

  // Wall particles have zero rates: they keep their prescribed velocity and place. So do the open
  // boundaries' buffers, which may hold the rates they had as fluid.
  for (std::size_t i = 0; i < n; ++i)
    if (P.kind[i] != kFluid) acc[i].setZero(), drho[i] = 0.0;
  std::vector<LeapfrogScalar> scalars;
  if (continuity) scalars.push_back({&P.rho, &drho});
  const double t_start = disc_->bodies.time(), t_end = t_start + dt;
  const double potential_before_drift = energy_.potential_energy(P);
  leapfrog_step<D>(
      dt, n, P.x, P.v, acc, scalars, [&](std::size_t i) { return P.kind[i] == kFluid; },
      [&] {
        disc_->open.drift(P, t_start, dt);
        disc_->bodies.move_to(P, t_end);      // with the fluid's drift
        if (!nh.update(P)) P.written(P.rho);  // a rebuild refreshed every particle column, an update x and v
        compute_rates();
      },
      [&](const std::vector<Vector<D>>& u, const std::vector<const std::vector<double>*>& f) {
        credit_kick(0.5 * dt, u, continuity ? *f[0] : P.rho);
      });
  energy_.add_change(EnergyCause::Gravity, EnergyForm::Potential, potential_before_drift, energy_.potential_energy(P));
  disc_->bodies.move_to(P, t_end);  // the closing kick left the walls' velocity of the step's start
  disc_->open.prescribe(P, t_end);  // and the inlets'
  P.written(P.rho);                 // the closing kick's densities, for the shift and the pressures
}

template <int D>
void WcsphSolver<D>::credit_kick(double half_dt, const std::vector<Vector<D>>& u, const std::vector<double>& rho) {
  const Particles<D>& P = disc_->particles;
  const std::size_t n = P.n_owned;
  const std::vector<Vector<D>>& acc = P.fields[acc_];
  const std::vector<double>& drho = P.fields[drho_];
  const std::vector<Vector<D>> none(viscous_acc_.valid() && av_acc_.valid() ? 0 : n, Vector<D>::Zero());
  const std::vector<Vector<D>>& viscous = viscous_acc_.valid() ? P.fields[viscous_acc_] : none;
  const std::vector<Vector<D>>& av = av_acc_.valid() ? P.fields[av_acc_] : none;
  const std::vector<Vector<D>> gravity(n, energy_.template potential_gravity<D>()),
      forcing(n, energy_.template forcing_gravity<D>());
  // The pressure's part is what the others leave of the acceleration; compression what diffusion leaves
  // of the density rate.
  std::vector<Vector<D>> pressure(n);
  for (std::size_t i = 0; i < n; ++i) pressure[i] = acc[i] - gravity[i] - forcing[i] - viscous[i] - av[i];
  energy_.add_update(P, u,
                     {{EnergyCause::Gravity, half_dt, &gravity},
                      {EnergyCause::BodyForce, half_dt, &forcing},
                      {EnergyCause::Pressure, half_dt, &pressure},
                      {EnergyCause::Viscous, half_dt, &viscous},
                      {EnergyCause::ArtificialViscosity, half_dt, &av}});
  if (density_ != DensityMethod::Continuity) return;
  const std::vector<double> zero(diffusion_rate_.valid() ? 0 : n, 0.0);
  const std::vector<double>& diffusion = diffusion_rate_.valid() ? P.fields[diffusion_rate_] : zero;
  std::vector<double> compression(n);
  for (std::size_t i = 0; i < n; ++i) compression[i] = drho[i] - diffusion[i];
  energy_.add_density_update(
      P, rho, {{EnergyCause::Pressure, half_dt, &compression}, {EnergyCause::DensityDiffusion, half_dt, &diffusion}});
}

template <int D> void WcsphSolver<D>::shift(double dt) {
  Particles<D>& P = disc_->particles;
  Neighbourhood<D>& nh = disc_->neighbourhood;
  nh.update(P);
  // Free-surface particles stay put, beside them shifts are never outwards (src/sph/shifting.hpp). The
  // surface is the rates' one: the particles have not moved since.
  ShiftBoundary<D> boundary;
  if (disc_->physics.free_surface) boundary = free_surface_.shift_boundary(P, nh, disc_->kernel, surface_);
  shift_particles(P, nh, disc_->kernel, shifting_model_, disc_->dx, largest_speed(P), dt, {&P.rho},
                  disc_->physics.free_surface ? &boundary : nullptr);
}

template class WcsphSolver<1>;
template class WcsphSolver<2>;
template class WcsphSolver<3>;

}  // namespace sph
