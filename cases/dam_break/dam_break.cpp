#include "cases/dam_break/dam_break.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cases/common/lattice.hpp"
#include "cases/common/reference_data.hpp"
#include "cases/common/wall_options.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"
#include "src/io/output_dir.hpp"

namespace sph {

namespace {
PetscErrorCode read_options(PetscInt* nx, PetscInt* layers, PetscReal* a, PetscReal* g, PetscReal* re,
                            PetscReal* rho0) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Dam break (-case dam_break)", "Case");
  PetscCall(option_int(PetscOptionsObject, "-nx", "Particles across the column width a", *nx, nx, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-column_width", "Column width a (height 2a, tank 4a)", *a, a, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-g", "Gravity", *g, g, nullptr));
  PetscCall(option_real(PetscOptionsObject, "-re", "Reynolds number sqrt(g a^3) / nu", *re, re, nullptr));
  PetscCall(read_wall_scene_options(PetscOptionsObject, layers, rho0));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

template <int D> void DamBreak<D>::set_from_options() {
  SPH_PETSC(read_options(&nx_, &wall_layers_, &a_, &g_, &re_, &rho0_));
  require(nx_ >= 4, "-nx", "at least 4", nx_);
  require(a_ > 0, "-column_width", "positive", a_);
  require(g_ > 0, "-g", "positive", g_);
  require(re_ > 0, "-re", "positive", re_);
  check_wall_scene_options(wall_layers_, rho0_);
}

template <int D> double DamBreak<D>::time_scale() const { return std::sqrt(a_ / (2.0 * g_)); }
template <int D> double DamBreak<D>::default_t_end() const { return 3.0 * time_scale(); }

template <int D> Physics<D> DamBreak<D>::physics() const {
  Physics<D> phys;
  phys.rho0 = rho0_;
  phys.nu = std::sqrt(g_ * a_ * a_ * a_) / re_;
  phys.U = std::sqrt(2.0 * g_ * 2.0 * a_);  // free fall from the column height
  phys.gravity = Vector<D>::Zero();
  phys.gravity[1] = -g_;
  phys.free_surface = true;
  return phys;
}

template <int D> void DamBreak<D>::create(Particles<D>& P, Domain<D>& domain) const {
  const double dx = spacing();
  double mass = rho0_;
  for (int d = 0; d < D; ++d) mass *= dx;
  const int L = static_cast<int>(wall_layers_), n = static_cast<int>(nx_);
  const int tank = 4 * n, height = 3 * n;  // tank 4a long (and a deep in 3D); side walls 3a high
  domain.lo = Vector<D>::Constant(-L * dx);
  domain.hi = Vector<D>::Constant((n + L) * dx);
  domain.hi[0] = (tank + L) * dx;
  // Open top: room above, and beside and below the tank for the run-up that flies over a side wall
  // (after T = 4); a tree search costs nothing for the room.
  domain.hi[1] = 20.0 * a_;
  domain.lo[0] -= 20.0 * a_, domain.hi[0] += 20.0 * a_, domain.lo[1] -= 100.0 * a_;
  domain.periodic.fill(false);
  Particles<D> all;
  const int depth_lo = D == 3 ? -L : 0, depth_hi = D == 3 ? n + L : 1;
  for (int k = depth_lo; k < depth_hi; ++k)
    for (int j = -L; j < height; ++j)
      for (int i = -L; i < tank + L; ++i) {
        Vector<D> x;
        x[0] = (i + 0.5) * dx, x[1] = (j + 0.5) * dx;
        if constexpr (D == 3) x[2] = (k + 0.5) * dx;
        const bool wall = j < 0 || i < 0 || i >= tank || k < 0 || (D == 3 && k >= n);
        const bool fluid = !wall && i < n && j < 2 * n;
        if (!wall && !fluid) continue;
        // Hydrostatic start (ISPH recomputes it; WCSPH takes its density from it).
        const double p = fluid ? rho0_ * g_ * (2.0 * a_ - x[1]) : 0.0;
        all.add(x, Vector<D>::Zero(), mass, rho0_, p, wall ? kWall : kFluid);
      }
  P = rank_share(all);
}

template <int D> double DamBreak<D>::front(const Particles<D>& P) const {
  double xmax = -1e300;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid) xmax = std::max(xmax, P.x[i][0]);
  MPI_Allreduce(MPI_IN_PLACE, &xmax, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return xmax + 0.5 * spacing();  // particle centres sit half a spacing inside the fluid's edge
}

// Mean fluid pressure in the square of side a/8 at the foot of the left wall (x0 = 0) or of the far
// wall (x0 = 4a, where the surge hits at T ~ 3): a fixed region, so runs at any resolution measure the
// same thing (the walls' extrapolated pressure is left out); NaN while no fluid is there.
template <int D> double DamBreak<D>::foot_pressure(const Particles<D>& P, double x0) const {
  const double side = 0.125 * a_;
  double sums[2] = {0.0, 0.0};
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid && std::abs(P.x[i][0] - x0) < side && P.x[i][1] < side) sums[0] += P.p[i], sums[1] += 1.0;
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return sums[1] > 0 ? sums[0] / sums[1] : std::nan("");
}

// The column's height at the left wall (the residual column of Martin & Moyce's second measurement):
// the highest fluid particle within a/8 of the wall, plus half a spacing.
template <int D> double DamBreak<D>::column_height(const Particles<D>& P) const {
  double ymax = 0.0;
  for (std::size_t i = 0; i < P.n_owned; ++i)
    if (P.kind[i] == kFluid && P.x[i][0] < 0.125 * a_) ymax = std::max(ymax, P.x[i][1]);
  MPI_Allreduce(MPI_IN_PLACE, &ymax, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return ymax + 0.5 * spacing();
}

template <int D> std::map<std::string, double> DamBreak<D>::errors(const Particles<D>& P, double t) const {
  const double T = t / time_scale(), Z = front(P) / a_;
  const double scale = rho0_ * g_ * a_;
  if (history_.empty() || T > history_.back().T)
    history_.push_back(
        {T, Z, foot_pressure(P, 0.0) / scale, foot_pressure(P, 4.0 * a_) / scale, column_height(P) / a_});
  // Mean relative error at the experimental points reached so far (linear interpolation in time).
  const Table exp = reference_table("martin_moyce_1952.csv");
  const std::vector<double> Te = exp.column("T"), Ze = exp.column("Z");
  double sum = 0.0;
  int count = 0;
  for (std::size_t k = 0; k < Te.size(); ++k) {
    if (Te[k] > T || Ze[k] >= 4.0 || history_.size() < 2 || Te[k] < history_.front().T) continue;
    for (std::size_t h = 1; h < history_.size(); ++h) {
      if (history_[h].T < Te[k]) continue;
      const Record &a = history_[h - 1], &b = history_[h];
      const double Zs = a.Z + (b.Z - a.Z) * (Te[k] - a.T) / (b.T - a.T);
      sum += std::abs(Zs - Ze[k]) / Ze[k];
      ++count;
      break;
    }
  }
  // No experimental point reached yet: no error to report (NaN, null in summary.json), not 0.
  first_measured_T_ = *std::min_element(Te.begin(), Te.end());
  return {{"front_position", Z}, {"front_position_rel", count ? sum / count : std::nan("")}};
}

template <int D> std::string DamBreak<D>::unmeasured_reason(const std::string& name) const {
  if (name != "front_position_rel") return "";
  std::ostringstream why;
  why << "the run ended at T = " << (history_.empty() ? 0.0 : history_.back().T)
      << ", before the front reached the first measured point of Martin & Moyce (T = " << first_measured_T_
      << "); raise -t_end";
  return why.str();
}

template <int D> void DamBreak<D>::write_outputs(const Particles<D>& P, double t, const std::string& dir) const {
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  note_output(dir + "/front_position.csv");
  std::ofstream out(dir + "/front_position.csv");
  out.precision(10);
  out << "T,Z,P_foot,P_far,H\n";
  for (const auto& [T, Z, P_foot, P_far, H] : history_)
    out << T << "," << Z << "," << P_foot << "," << P_far << "," << H << "\n";
}

template <int D> nlohmann::json DamBreak<D>::parameters() const {
  return {{"nx", nx_}, {"column_width", a_}, {"g", g_}, {"re", re_}, {"rho0", rho0_}, {"wall_layers", wall_layers_}};
}

template class DamBreak<2>;
template class DamBreak<3>;

}  // namespace sph
