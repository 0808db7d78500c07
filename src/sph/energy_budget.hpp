#pragma once
// Where the energy of the owned fluid particles goes, by cause, summed over a run's steps: the kinetic
// energy E_k = sum_i 1/2 m_i |u_i|^2, the potential energy of gravity E_p = -sum_i m_i g . x_i, and a
// weakly compressible fluid's elastic (internal) energy E_e = sum_i m_i e(rho_i), e' = p / rho^2.
//
// Every change of a particle's velocity, place or density is credited to the cause that made it, each
// from the change it made, so the budget closes (the energies' change minus the causes' sum, the
// `closure`, is round-off) and any scene tells where its energy went
// (docs/verification/free_surface.md, "Energy budgets"):
// - a velocity update u -> u + d, d = sum_k d_k, changes E_k by exactly sum_i m_i (u_i + d_i / 2) . d_i,
//   and cause k is credited with its share sum_i m_i (u_i + d_i / 2) . d_k,i;
// - a density update rho -> rho + sum_k r_k changes e by the secant slope times the sum, and cause k is
//   credited with the slope times r_k;
// - other changes (a projection, a shift, a particle put back on a wall) are measured as the
//   difference of the energies before and after.
// Gravity is conservative: its kicks' share of E_k and the drift's change of E_p cancel but for the
// time integration's error, which its total is. A body force along a periodic direction has no
// potential: its work is the external forcing `body_force`.
#include <petscsys.h>

#include <array>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "src/particles/particles.hpp"

namespace sph {

// The causes, in the order of summary.json and timeseries.csv. Pressure includes the compression its
// work stores in a weakly compressible fluid (the continuity equation's change of E_e).
enum class EnergyCause {
  Gravity,
  BodyForce,
  Pressure,
  Viscous,
  ArtificialViscosity,
  DensityDiffusion,
  Shifting,
  WallBounding,
  RemovedFluid,
  OpenBoundaries  // what fluid brings in through inlets and takes out through outlets
};
enum class EnergyForm { Kinetic, Potential, Internal };

class EnergyBudget {
 public:
  static constexpr int kCauses = 10, kForms = 3;
  static constexpr const char* kCauseNames[kCauses] = {
      "gravity",           "body_force", "pressure",      "viscous",       "artificial_viscosity",
      "density_diffusion", "shifting",   "wall_bounding", "removed_fluid", "open_boundaries"};
  static constexpr const char* kFormNames[kForms] = {"kinetic", "potential", "internal"};
  // A weakly compressible fluid's specific elastic energy e(rho), zero at the rest density, and its
  // slope e'(rho) = p / rho^2.
  struct SpecificEnergy {
    std::function<double(double)> energy, slope;
    explicit operator bool() const { return static_cast<bool>(energy); }
  };

  EnergyBudget() = default;
  // g: the gravity; periodic[a]: whether axis a is periodic (there g has no potential). e: the specific
  // elastic energy of a weakly compressible fluid (none: incompressible).
  template <int D, std::size_t N>
  EnergyBudget(const Vector<D>& g, const std::array<bool, N>& periodic, SpecificEnergy e = {})
      : elastic_(std::move(e)) {
    for (int a = 0; a < D; ++a) (periodic[a] ? forcing_ : potential_g_)[a] = g[a];
  }

  bool has_internal() const { return static_cast<bool>(elastic_); }
  bool started() const { return started_; }
  const SpecificEnergy& specific_energy() const { return elastic_; }

  // The gravity split into its potential part and its forcing part (along periodic axes).
  template <int D> Vector<D> potential_gravity() const { return Eigen::Map<const Vector<D>>(potential_g_.data()); }
  template <int D> Vector<D> forcing_gravity() const { return Eigen::Map<const Vector<D>>(forcing_.data()); }

  // This rank's part of each energy of the owned fluid particles, with velocities u.
  template <int D> double kinetic_energy(const Particles<D>& P, const std::vector<Vector<D>>& u) const {
    double e = 0.0;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kFluid) e += 0.5 * P.m[i] * u[i].squaredNorm();
    return e;
  }
  template <int D> double kinetic_energy(const Particles<D>& P) const { return kinetic_energy(P, P.v); }
  template <int D> double potential_energy(const Particles<D>& P) const {
    const Vector<D> g = potential_gravity<D>();
    double e = 0.0;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kFluid) e -= P.m[i] * g.dot(P.x[i]);
    return e;
  }
  template <int D> double internal_energy(const Particles<D>& P) const {
    if (!elastic_) return 0.0;
    double e = 0.0;
    for (std::size_t i = 0; i < P.n_owned; ++i)
      if (P.kind[i] == kFluid) e += P.m[i] * elastic_.energy(P.rho[i]);
    return e;
  }
  // The three, this rank's part.
  template <int D> std::array<double, kForms> energies(const Particles<D>& P) const {
    return {kinetic_energy(P), potential_energy(P), internal_energy(P)};
  }

  // The energies at the start of the budget (the first call counts).
  template <int D> void start(const Particles<D>& P) {
    if (!started_) start_ = energies(P), started_ = true;
  }

  // Credits the update u -> u + sum_k scale_k a_k to the causes of the parts (cause, scale, a).
  template <int D>
  void add_update(const Particles<D>& P, const std::vector<Vector<D>>& u,
                  std::initializer_list<std::tuple<EnergyCause, double, const std::vector<Vector<D>>*>> parts) {
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid) continue;
      Vector<D> d = Vector<D>::Zero();
      for (const auto& [cause, scale, a] : parts) d += scale * (*a)[i];
      const Vector<D> mid = u[i] + 0.5 * d;
      for (const auto& [cause, scale, a] : parts) at(cause, EnergyForm::Kinetic) += P.m[i] * mid.dot(scale * (*a)[i]);
    }
  }

  // Credits the density update rho -> rho + sum_k scale_k r_k to the causes of the parts.
  template <int D>
  void add_density_update(const Particles<D>& P, const std::vector<double>& rho,
                          std::initializer_list<std::tuple<EnergyCause, double, const std::vector<double>*>> parts) {
    if (!elastic_) return;
    for (std::size_t i = 0; i < P.n_owned; ++i) {
      if (P.kind[i] != kFluid) continue;
      double d = 0.0;
      for (const auto& [cause, scale, r] : parts) d += scale * (*r)[i];
      const double slope = secant_slope(rho[i], rho[i] + d);
      for (const auto& [cause, scale, r] : parts) at(cause, EnergyForm::Internal) += P.m[i] * slope * scale * (*r)[i];
    }
  }

  // Credits a change measured as the difference of two energies of one form (this rank's parts).
  void add_change(EnergyCause cause, EnergyForm form, double before, double after) {
    at(cause, form) += after - before;
  }
  // The same for all three forms.
  void add_change(EnergyCause cause, const std::array<double, kForms>& before,
                  const std::array<double, kForms>& after) {
    for (int f = 0; f < kForms; ++f) change_[idx(cause)][f] += after[f] - before[f];
  }

  // The budget reduced over the ranks (collective): the energies at the start and now, and what each
  // cause changed of each form.
  struct Totals {
    std::array<double, kForms> start{}, now{};
    std::array<std::array<double, kForms>, kCauses> change{};
    double cause_total(int c) const { return change[c][0] + change[c][1] + change[c][2]; }
    double energy_change() const {
      double d = 0.0;
      for (int f = 0; f < kForms; ++f) d += now[f] - start[f];
      return d;
    }
    double closure() const {
      double d = energy_change();
      for (int c = 0; c < kCauses; ++c) d -= cause_total(c);
      return d;
    }
  };
  template <int D> Totals totals(const Particles<D>& P) const {
    constexpr int n = kForms * (2 + kCauses);
    std::array<double, n> buf{};
    const std::array<double, kForms> now = energies(P);
    for (int f = 0; f < kForms; ++f) buf[f] = start_[f], buf[kForms + f] = now[f];
    for (int c = 0; c < kCauses; ++c)
      for (int f = 0; f < kForms; ++f) buf[kForms * (2 + c) + f] = change_[c][f];
    MPI_Allreduce(MPI_IN_PLACE, buf.data(), n, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    Totals t;
    for (int f = 0; f < kForms; ++f) t.start[f] = buf[f], t.now[f] = buf[kForms + f];
    for (int c = 0; c < kCauses; ++c)
      for (int f = 0; f < kForms; ++f) t.change[c][f] = buf[kForms * (2 + c) + f];
    return t;
  }

  // summary.json's conservation.energy_budget (collective).
  template <int D> nlohmann::json describe(const Particles<D>& P) const { return describe(totals(P)); }
  nlohmann::json describe(const Totals& t) const {
    nlohmann::json j;
    for (int f = 0; f < kForms; ++f) {
      if (f == 2 && !elastic_) continue;
      j[std::string(kFormNames[f]) + "_energy_start"] = t.start[f];
      j[std::string(kFormNames[f]) + "_energy_end"] = t.now[f];
    }
    // Each cause's change of the total energy, and of each form.
    nlohmann::json work = nlohmann::json::object(), parts = nlohmann::json::object();
    for (int c = 0; c < kCauses; ++c) {
      work[kCauseNames[c]] = t.cause_total(c);
      nlohmann::json by_form = nlohmann::json::object();
      for (int f = 0; f < kForms; ++f)
        if (f < 2 || elastic_) by_form[kFormNames[f]] = t.change[c][f];
      parts[kCauseNames[c]] = by_form;
    }
    j["work"] = work;
    j["work_by_form"] = parts;
    // What gravity released: the kinetic energy its kicks gave (the scale for the other terms).
    j["gravity_released"] = t.change[idx(EnergyCause::Gravity)][0];
    j["energy_change"] = t.energy_change();
    j["closure"] = t.closure();
    return j;
  }

  // timeseries.csv's columns: the potential and internal energies (the kinetic one is there already)
  // and each cause's running total.
  std::vector<std::string> columns() const {
    std::vector<std::string> c = {"potential_energy"};
    if (elastic_) c.push_back("internal_energy");
    for (const char* name : kCauseNames) c.push_back(std::string("work_") + name);
    return c;
  }
  std::vector<double> row(const Totals& t) const {
    std::vector<double> r = {t.now[1]};
    if (elastic_) r.push_back(t.now[2]);
    for (int c = 0; c < kCauses; ++c) r.push_back(t.cause_total(c));
    return r;
  }

  // A checkpoint keeps the budget, so that a restarted run's budget is its whole run's: each rank's
  // partial sums (collective). A restart on as many ranks, which puts each particle back on its rank
  // (src/run/time_loop.cpp), takes each rank's own, so that the sums go on bitwise as the writing run's;
  // on another rank count rank 0 takes their total and the others start from zero.
  nlohmann::json to_json() const {
    std::array<double, kForms*(1 + kCauses)> mine{};
    for (int f = 0; f < kForms; ++f) mine[f] = start_[f];
    for (int c = 0; c < kCauses; ++c)
      for (int f = 0; f < kForms; ++f) mine[kForms * (1 + c) + f] = change_[c][f];
    int ranks = 1;
    MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
    std::vector<double> all(mine.size() * static_cast<std::size_t>(ranks));
    MPI_Allgather(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), static_cast<int>(mine.size()),
                  MPI_DOUBLE, PETSC_COMM_WORLD);
    nlohmann::json per_rank = nlohmann::json::array();
    for (int r = 0; r < ranks; ++r)
      per_rank.push_back(std::vector<double>(all.begin() + r * mine.size(), all.begin() + (r + 1) * mine.size()));
    return {{"per_rank", per_rank}, {"started", started_}};
  }
  void from_json(const nlohmann::json& j) {
    if (!j.is_object() || !j.value("started", false)) return;
    int rank = 0, ranks = 1;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
    const auto per_rank = j.at("per_rank").get<std::vector<std::array<double, kForms*(1 + kCauses)>>>();
    std::array<double, kForms*(1 + kCauses)> mine{};
    if (static_cast<int>(per_rank.size()) == ranks) {
      mine = per_rank[rank];
    } else if (rank == 0) {
      for (const auto& r : per_rank)
        for (std::size_t k = 0; k < mine.size(); ++k) mine[k] += r[k];
    }
    started_ = true;
    for (int f = 0; f < kForms; ++f) start_[f] = mine[f];
    for (int c = 0; c < kCauses; ++c)
      for (int f = 0; f < kForms; ++f) change_[c][f] = mine[kForms * (1 + c) + f];
  }

 private:
  static int idx(EnergyCause c) { return static_cast<int>(c); }
  double& at(EnergyCause c, EnergyForm f) { return change_[idx(c)][static_cast<int>(f)]; }
  // (e(b) - e(a)) / (b - a), or e' at the midpoint where the two are too close for the difference.
  double secant_slope(double a, double b) const {
    if (std::abs(b - a) > 1e-6 * std::abs(a)) return (elastic_.energy(b) - elastic_.energy(a)) / (b - a);
    return elastic_.slope(0.5 * (a + b));
  }

  std::array<double, 3> potential_g_{}, forcing_{};
  SpecificEnergy elastic_;
  std::array<std::array<double, kForms>, kCauses> change_{};
  std::array<double, kForms> start_{};
  bool started_ = false;
};

}  // namespace sph
