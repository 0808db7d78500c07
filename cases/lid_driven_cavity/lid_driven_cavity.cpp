#include "cases/lid_driven_cavity/lid_driven_cavity.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "cases/common/lattice.hpp"
#include "cases/common/reference_data.hpp"
#include "cases/common/wall_options.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/io/output_dir.hpp"

namespace sph {

namespace {
const char* const lid_corners_names[] = {"upstream", "symmetric"};

PetscErrorCode read_options(PetscInt* nx, PetscInt* layers, PetscReal* re, PetscReal* U, PetscReal* rho0,
                            PetscInt* interpolation, PetscInt* corners, PetscReal* average_from) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Lid-driven cavity (-case lid_driven_cavity)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Fluid particles per side of the unit cavity", *nx, nx, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-re", "Reynolds number U L / nu (references: 100, 400, 1000)", *re, re,
                        nullptr));
  PetscCall(option_real(PetscOptionsObject, "-U", "Lid speed", *U, U, nullptr));
  PetscCall(option_choice(PetscOptionsObject, "-lid_corners",
                          "Wall blocks where the lid meets the side walls: upstream (the upstream block moves "
                          "with the lid, the downstream one is fixed) or symmetric (both at U/2, the mean of the "
                          "two walls meeting there; 2D ISPH fails at Re 1000)",
                          lid_corners_names, 2, lid_corners_names[*corners], corners, nullptr));
  PetscCall(option_choice(PetscOptionsObject, "-profile_interpolation",
                          "How the centreline profiles are read off the particles: linear (moving least squares, "
                          "second order next to walls too) or shepard (kernel average, the metric before; O(h) "
                          "biased where the support is cut)",
                          probe_interpolation_names, 2, probe_interpolation_names[*interpolation], interpolation,
                          nullptr));
  PetscCall(option_real(PetscOptionsObject, "-profile_average_from",
                        "Average the centreline profiles over t >= this time and report their errors as "
                        "centreline_rms_u_averaged / _v_averaged (default -1: no average; use with "
                        "-steady_tol 0 and a -t_end past it)",
                        *average_from, average_from, nullptr));
  PetscCall(read_wall_scene_options(PetscOptionsObject, layers, rho0));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

// The references give values at the walls (imposed, not computed): they are left out of the norms,
// and so is Ghia's Re = 400 value at x = 0.9063, widely held to be a misprint.
bool compared(int dim, double coord, double re, double x_v_point) {
  if (coord <= 0.0 || coord >= 1.0) return false;
  return !(dim == 2 && re == 400.0 && std::abs(x_v_point - 0.9063) < 1e-6);
}
}  // namespace

template <int D> void LidDrivenCavity<D>::set_from_options() {
  PetscInt interpolation = static_cast<PetscInt>(interpolation_), corners = symmetric_corners_ ? 1 : 0;
  SPH_PETSC(read_options(&nx_, &wall_layers_, &re_, &U_, &rho0_, &interpolation, &corners, &average_from_));
  interpolation_ = static_cast<ProbeInterpolation>(interpolation);
  symmetric_corners_ = corners == 1;
  if (D == 3 && symmetric_corners_)
    throw Error("-lid_corners symmetric is 2D only (the cube's lid edges meet the end walls too); drop it with -dim 3");
  require(nx_ >= 8, "-nx", "at least 8", nx_);
  require(re_ > 0, "-re", "positive", re_);
  require(U_ > 0, "-U", "positive", U_);
  require(average_from_ >= 0 || average_from_ == -1, "-profile_average_from", "a time >= 0 (or -1: no average)",
          average_from_);
  if (averaging() && !has_reference())
    throw Error("-profile_average_from needs a reference to compare the averaged profiles with: -re 100, 400 or 1000");
  check_wall_scene_options(wall_layers_, rho0_);
}

template <int D> Physics<D> LidDrivenCavity<D>::physics() const {
  Physics<D> phys;
  phys.rho0 = rho0_;
  phys.nu = U_ / re_;
  phys.U = U_;
  return phys;
}

template <int D> void LidDrivenCavity<D>::create(Particles<D>& P, Domain<D>& domain) const {
  const double dx = spacing(), pad = wall_layers_ * dx;
  double mass = rho0_;
  for (int d = 0; d < D; ++d) mass *= dx;
  domain.lo = Vector<D>::Constant(-pad);
  domain.hi = Vector<D>::Constant(1.0 + pad);
  domain.periodic.fill(false);
  Particles<D> all;
  const int L = static_cast<int>(wall_layers_), n = static_cast<int>(nx_);
  const int depth_lo = D == 3 ? -L : 0, depth_hi = D == 3 ? n + L : 1;
  for (int k = depth_lo; k < depth_hi; ++k)
    for (int j = -L; j < n + L; ++j)
      for (int i = -L; i < n + L; ++i) {
        Vector<D> x;
        x[0] = (i + 0.5) * dx, x[1] = (j + 0.5) * dx;
        if constexpr (D == 3) x[2] = (k + 0.5) * dx;
        const bool inside_depth = D == 2 || (k >= 0 && k < n);
        const bool fluid = i >= 0 && i < n && j >= 0 && j < n && inside_depth;
        // Where the lid meets a side wall, the wall velocity jumps from U to 0 inside the kernel support
        // of the corner fluid, and a discrete divergence (the ISPH pressure source) reads the jump as a
        // line of wall divergence +-U/dx. With both corner blocks fixed that is an expansion at the
        // upstream corner (x = 0), a mass sink that draws fluid particles through the gap between lid and
        // corner block at high Re. So the upstream corner block moves with the lid (the jump there lies
        // across y = 1, a shear, as in the continuum problem) and the downstream one stays fixed (a
        // compression, which raises the stagnation pressure in that corner); a moving downstream block
        // drags particles out along y = 1 (docs/verification/lid_driven_cavity.md, "The lid's corners"
        // and "Design measurements"). In 3D the lid stops at the end walls z = 0, 1: the jump there lies
        // across z, a shear that has no divergence. WCSPH's continuity equation sees walls at rest (see
        // solvers/wcsph), so none of this changes its density; ISPH's source sees them at rest too by
        // default (-ppe_wall_velocity zero), and the blocks then enter only the viscous term. The choices
        // here were made with the source seeing the walls' velocities (prescribed).
        const bool lid = j >= n && i < n && inside_depth;
        Vector<D> v = Vector<D>::Zero();
        if (lid) v[0] = U_;
        // -lid_corners symmetric: each wall particle takes the boundary value of the nearest point of the
        // fluid's boundary; for the corner blocks that point is the corner itself, where the lid's value
        // and the side wall's meet, so they take the mean of the two. Not the default: with the prescribed
        // source the jump U -> U/2 inside the lid's wall layer draws a particle out at Re 1000, and with the
        // walls at rest in the source its gain is gone (docs/verification/lid_driven_cavity.md, "The lid's
        // corners").
        if (symmetric_corners_ && j >= n && (i < 0 || i >= n)) v[0] = 0.5 * U_;
        all.add(x, v, mass, rho0_, 0.0, fluid ? kFluid : kWall);
      }
  P = rank_share(all);
}

template <int D> bool LidDrivenCavity<D>::has_reference() const {
  return re_ == 100.0 || re_ == 400.0 || re_ == 1000.0;
}

template <int D> typename LidDrivenCavity<D>::Reference LidDrivenCavity<D>::reference() const {
  const std::string re = std::to_string(static_cast<int>(re_));
  if constexpr (D == 2)
    return {"ghia1982_u_vertical_centreline.csv",
            "ghia1982_v_horizontal_centreline.csv",
            "u_Re" + re,
            "v_Re" + re,
            "ghia",
            "ghia1982"};
  if (re_ == 1000.0)
    return {"albensoeder2005_u_vertical_centreline.csv",
            "albensoeder2005_v_horizontal_centreline.csv",
            "u_Re" + re,
            "v_Re" + re,
            "albensoeder",
            "albensoeder2005"};
  return {"cavity3d_fd_u_vertical_centreline.csv",
          "cavity3d_fd_v_horizontal_centreline.csv",
          "u_Re" + re,
          "v_Re" + re,
          "reference",
          "finite_difference"};
}

template <int D> Vector<D> LidDrivenCavity<D>::centreline_point(double along, int axis) const {
  Vector<D> x = Vector<D>::Constant(0.5);
  x[axis] = along;
  return x;
}

template <int D> typename LidDrivenCavity<D>::Profiles LidDrivenCavity<D>::reference_profiles() const {
  Profiles pr;
  const Reference ref = reference();
  const Table tu = reference_table(ref.u_file), tv = reference_table(ref.v_file);
  pr.y_u = tu.column("y"), pr.u_ref = tu.column(ref.u_column);
  pr.x_v = tv.column("x"), pr.v_ref = tv.column(ref.v_column);
  return pr;
}

template <int D>
typename LidDrivenCavity<D>::Profiles LidDrivenCavity<D>::centreline_profiles(const Particles<D>& P) const {
  Profiles pr = reference_profiles();
  std::vector<Vector<D>> pts;
  for (double y : pr.y_u) pts.push_back(centreline_point(y, 1));
  for (double x : pr.x_v) pts.push_back(centreline_point(x, 0));
  // The interpolation is part of the metric: Wendland C2 weights with h = 1.5 dx, fit by -profile_interpolation.
  const Kernel<D> K(KernelType::WendlandC2, 1.5 * spacing());
  const std::vector<Vector<D>> u = probe_velocity(P, K, pts, interpolation_);
  for (std::size_t k = 0; k < pr.y_u.size(); ++k) pr.u_sph.push_back(u[k][0] / U_);
  for (std::size_t k = 0; k < pr.x_v.size(); ++k) pr.v_sph.push_back(u[pr.y_u.size() + k][1] / U_);
  return pr;
}

template <int D> std::pair<double, double> LidDrivenCavity<D>::rms_errors(const Profiles& pr) const {
  auto rms = [&](const std::vector<double>& c, const std::vector<double>& ref, const std::vector<double>& sph,
                 bool horizontal) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (!compared(D, c[k], re_, horizontal ? c[k] : -1.0)) continue;
      sum += (sph[k] - ref[k]) * (sph[k] - ref[k]);
      ++count;
    }
    return std::sqrt(sum / count);
  };
  return {rms(pr.y_u, pr.u_ref, pr.u_sph, false), rms(pr.x_v, pr.v_ref, pr.v_sph, true)};
}

template <int D> const typename LidDrivenCavity<D>::Profiles& LidDrivenCavity<D>::profiles_at(const Particles<D>& P,
                                                                                              double t,
                                                                                              Profiles& scratch) const {
  if (t == last_t_ && !last_.y_u.empty()) return last_;  // accumulate() read them at this step already
  scratch = centreline_profiles(P);
  return scratch;
}

template <int D> void LidDrivenCavity<D>::accumulate(const Particles<D>& P, double t, double dt) {
  if (!has_reference()) return;
  last_ = centreline_profiles(P);
  last_t_ = t;
  if (!averaging() || t - dt < average_from_ - 1e-12 * std::max(1.0, average_from_)) return;
  if (average_.weight == 0.0) {
    average_.u.assign(last_.u_sph.size(), 0.0);
    average_.v.assign(last_.v_sph.size(), 0.0);
  }
  average_.weight += dt;
  for (std::size_t k = 0; k < average_.u.size(); ++k) average_.u[k] += dt * last_.u_sph[k];
  for (std::size_t k = 0; k < average_.v.size(); ++k) average_.v[k] += dt * last_.v_sph[k];
}

template <int D> typename LidDrivenCavity<D>::Profiles LidDrivenCavity<D>::averaged_profiles() const {
  Profiles pr = reference_profiles();
  for (double s : average_.u) pr.u_sph.push_back(s / average_.weight);
  for (double s : average_.v) pr.v_sph.push_back(s / average_.weight);
  return pr;
}

template <int D> std::map<std::string, double> LidDrivenCavity<D>::errors(const Particles<D>& P, double t) const {
  if (!has_reference()) return {};
  Profiles scratch;
  const auto [u, v] = rms_errors(profiles_at(P, t, scratch));
  std::map<std::string, double> e{{"centreline_rms_u", u}, {"centreline_rms_v", v}};
  if (!averaging()) return e;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto [ua, va] = average_.weight > 0.0 ? rms_errors(averaged_profiles()) : std::make_pair(nan, nan);
  e["centreline_rms_u_averaged"] = ua, e["centreline_rms_v_averaged"] = va;
  return e;
}

template <int D> std::string LidDrivenCavity<D>::unmeasured_reason(const std::string& name) const {
  if (name.find("_averaged") == std::string::npos || average_.weight > 0.0) return "";
  std::ostringstream msg;
  msg << "the run ended before the profile average began (-profile_average_from " << average_from_
      << "): set -steady_tol 0 and a -t_end past it";
  return msg.str();
}

template <int D> nlohmann::json LidDrivenCavity<D>::accumulated_state() const {
  if (!averaging()) return nullptr;
  return {{"weight", average_.weight}, {"u", average_.u}, {"v", average_.v}};
}

template <int D> void LidDrivenCavity<D>::restore_accumulated_state(const nlohmann::json& state) {
  // The run identity has already checked that the checkpoint was written with the same window.
  if (!averaging() || !state.is_object()) return;
  average_.weight = state.at("weight").get<double>();
  average_.u = state.at("u").get<std::vector<double>>();
  average_.v = state.at("v").get<std::vector<double>>();
}

template <int D> void LidDrivenCavity<D>::write_outputs(const Particles<D>& P, double t, const std::string& dir) const {
  // Fine profiles for plots, and the comparison at the reference's points.
  std::vector<Vector<D>> pts;
  const int m = 101;
  for (int k = 0; k < m; ++k) pts.push_back(centreline_point(k / double(m - 1), 1));
  for (int k = 0; k < m; ++k) pts.push_back(centreline_point(k / double(m - 1), 0));
  const Kernel<D> K(KernelType::WendlandC2, 1.5 * spacing());
  const std::vector<Vector<D>> u = probe_velocity(P, K, pts, interpolation_);
  const Profiles pr = has_reference() ? centreline_profiles(P) : Profiles{};  // collective: every rank
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  for (const char* name : {"/centreline_u.csv", "/centreline_v.csv"}) note_output(dir + name);
  std::ofstream cu(dir + "/centreline_u.csv"), cv(dir + "/centreline_v.csv");
  cu.precision(10), cv.precision(10);
  cu << "y,u\n";
  cv << "x,v\n";
  for (int k = 0; k < m; ++k) cu << pts[k][1] << "," << u[k][0] / U_ << "\n";
  for (int k = 0; k < m; ++k) cv << pts[m + k][0] << "," << u[m + k][1] / U_ << "\n";
  if (!has_reference()) return;
  const Reference ref = reference();
  note_output(dir + "/centreline_" + ref.file_tag + ".csv");
  std::ofstream cr(dir + "/centreline_" + ref.file_tag + ".csv");
  cr.precision(10);
  // With -profile_average_from, the time-averaged profile beside the last one (empty before the window).
  const bool averaged = averaging() && average_.weight > 0.0;
  const Profiles avg = averaged ? averaged_profiles() : Profiles{};
  cr << "profile,coordinate,sph," << ref.source << (averaging() ? ",sph_averaged" : "") << "\n";
  auto row = [&](const char* name, double c, double sph, double ref, const std::vector<double>& avg_sph,
                 std::size_t k) {
    cr << name << "," << c << "," << sph << "," << ref;
    if (averaging()) cr << ",";
    if (averaged) cr << avg_sph[k];
    cr << "\n";
  };
  for (std::size_t k = 0; k < pr.y_u.size(); ++k) row("u", pr.y_u[k], pr.u_sph[k], pr.u_ref[k], avg.u_sph, k);
  for (std::size_t k = 0; k < pr.x_v.size(); ++k) row("v", pr.x_v[k], pr.v_sph[k], pr.v_ref[k], avg.v_sph, k);
}

template <int D> nlohmann::json LidDrivenCavity<D>::parameters() const {
  return {{"nx", nx_},
          {"re", re_},
          {"U", U_},
          {"rho0", rho0_},
          {"wall_layers", wall_layers_},
          {"profile_interpolation", probe_interpolation_names[static_cast<int>(interpolation_)]},
          {"lid_corners", lid_corners_names[symmetric_corners_ ? 1 : 0]},
          {"profile_average_from", average_from_}};
}

template class LidDrivenCavity<2>;
template class LidDrivenCavity<3>;

}  // namespace sph
