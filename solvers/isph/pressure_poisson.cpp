#include "solvers/isph/pressure_poisson.hpp"

#include <algorithm>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "solvers/isph/ppe_matrix.hpp"
#include "src/core/error.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {

// The owned fluid particle nearest the centre of the fluid's bounding box (-1 if another rank owns
// it); ties go to the smallest label. Every quantity is an exact min/max over the ranks, so the choice
// does not depend on the partition. Why the middle: an interior particle is held by neighbours on all
// sides should the restoring solve (spread_pinned_residual) be loose, where a corner one was driven out
// through the walls (docs/verification/lid_driven_cavity_3d.md, "History").
template <int D> long central_fluid_particle(const Particles<D>& P) {
  const std::size_t n = P.n_owned;
  double lo[D], hi[D];
  for (int d = 0; d < D; ++d) lo[d] = std::numeric_limits<double>::max(), hi[d] = -lo[d];
  for (std::size_t i = 0; i < n; ++i)
    if (P.kind[i] == kFluid)
      for (int d = 0; d < D; ++d) lo[d] = std::min(lo[d], P.x[i][d]), hi[d] = std::max(hi[d], P.x[i][d]);
  MPI_Allreduce(MPI_IN_PLACE, lo, D, MPI_DOUBLE, MPI_MIN, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, hi, D, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  Vector<D> centre;
  for (int d = 0; d < D; ++d) centre[d] = 0.5 * (lo[d] + hi[d]);

  double nearest = std::numeric_limits<double>::max();
  for (std::size_t i = 0; i < n; ++i)
    if (P.kind[i] == kFluid) nearest = std::min(nearest, (P.x[i] - centre).squaredNorm());
  MPI_Allreduce(MPI_IN_PLACE, &nearest, 1, MPI_DOUBLE, MPI_MIN, PETSC_COMM_WORLD);
  long long label = std::numeric_limits<long long>::max();
  for (std::size_t i = 0; i < n; ++i)
    if (P.kind[i] == kFluid && (P.x[i] - centre).squaredNorm() == nearest) label = std::min<long long>(label, P.id[i]);
  MPI_Allreduce(MPI_IN_PLACE, &label, 1, MPI_LONG_LONG, MPI_MIN, PETSC_COMM_WORLD);
  for (std::size_t i = 0; i < n; ++i)
    if (P.kind[i] == kFluid && P.id[i] == label) return static_cast<long>(i);
  return -1;
}

}  // namespace

template <int D> PressurePoisson<D>::~PressurePoisson() {
  destroy_system();
  if (ksp_) KSPDestroy(&ksp_);
  if (mat_viewer_) PetscViewerDestroy(&mat_viewer_);
}

template <int D> void PressurePoisson<D>::destroy_system() {
  if (nullspace_) MatNullSpaceDestroy(&nullspace_);
  if (P_) MatDestroy(&P_);
  if (A_) MatDestroy(&A_);
  if (pinned_equation_) VecDestroy(&pinned_equation_);
  if (spread_) VecDestroy(&spread_);
  if (b_) VecDestroy(&b_);
  if (x_) VecDestroy(&x_);
}

template <int D> void PressurePoisson<D>::release() {
  // The KSP keeps its type and options for describe(); reset, it lets go of the matrices and the AMG.
  if (ksp_) SPH_PETSC(KSPReset(ksp_));
  destroy_system();
  rows_.release(), pc_rows_.release();
}

template <int D> void PressurePoisson<D>::assemble(const Particles<D>& P, const Neighbourhood<D>& nh,
                                                   const Kernel<D>& K, const Vector<D>& body_force,
                                                   const std::vector<char>* dirichlet,
                                                   const std::vector<LaplacianCorrection<D>>* consistent,
                                                   const SurfaceNodes<D>* nodes, const WallImpact<D>* impact,
                                                   const std::vector<Vector<D>>* wall_acceleration) {
  const std::size_t n = P.n_owned;
  kind_.assign(P.kind.begin(), P.kind.begin() + n);
  if (dirichlet) dirichlet_ = *dirichlet;
  else dirichlet_.assign(n, 0);
  int any_dirichlet = 0;
  for (char c : dirichlet_) any_dirichlet |= c;
  if (nodes)
    for (std::size_t i = 0; i < n; ++i) any_dirichlet |= nodes->has(i);
  MPI_Allreduce(MPI_IN_PLACE, &any_dirichlet, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);

  int any_wall = 0;
  for (std::size_t i = 0; i < n; ++i) any_wall |= P.kind[i] == kWall;
  MPI_Allreduce(MPI_IN_PLACE, &any_wall, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);

  // A non-symmetric singular matrix (no Dirichlet rows) has an unknown left null space, so the
  // right-hand side cannot be projected onto its range.
  //  - Walled domains pin one fluid particle to p = 0: dropping its continuity equation makes the
  //    system regular, and spread_pinned_residual restores that equation after each solve. The
  //    pinned particle is the one nearest the middle of the fluid (see central_fluid_particle).
  //  - Periodic domains (the consistent Laplacian) add eps * mean(diag) to the diagonal instead. With
  //    p = c 1 + q, the constant part c absorbs the part of b outside the range, which the q part
  //    then sees spread evenly over all rows; q is changed by O(eps) and c is removed afterwards.
  //    A pin would put all of that part on one particle as a point source (docs/pressure-solve.md,
  //    "Design measurements").
  pinned_ = -1;
  closed_ = nonsymmetric_ && !any_dirichlet && any_wall;
  regularised_ = nonsymmetric_ && !any_dirichlet && !any_wall;
  if (closed_) pinned_ = central_fluid_particle(P);

  // The matrix may be a view of the rows' arrays: it goes first, with the KSP (and its
  // preconditioner's references to it).
  destroy_system();
  SPH_PETSC(KSPDestroy(&ksp_));
  rows_.build(P, nh.list(), K, body_force, dirichlet_, pinned_, consistent, nodes, impact, wall_acceleration);
  // A new KSP for each new matrix, made from the options database: every option, viewers included,
  // then acts on every solve. Keeping one KSP saves no set-up time (the preconditioner is rebuilt for
  // each new matrix either way), and some preconditioners cannot be set up again on another matrix
  // (docs/pressure-solve.md, "Design measurements").
  // Made first: its preconditioner decides which matrix that is built from.
  create_ksp();
  // BoomerAMG only: a one-level preconditioner loses by it (docs/pressure-solve.md, "The preconditioner's
  // matrix"). A row's own diagonal decides what it drops, which would
  // make the preconditioner of a symmetric matrix non-symmetric, and CG needs a symmetric one:
  // symmetric matrices keep theirs whole. Taken before the matrices are made: an MPIAIJ view
  // renumbers its off-diagonal columns in place.
  PC pc;
  SPH_PETSC(KSPGetPC(ksp_, &pc));
  if (nonsymmetric_ && pc_drop_tol_ > 0 && is_boomeramg(pc)) {
    pc_rows_ = lump_weak_entries(rows_, static_cast<PetscInt>(n), pc_drop_tol_);
    P_ = make_ppe_matrix(pc_rows_, static_cast<PetscInt>(n), false);
  }
  A_ = make_ppe_matrix(rows_, static_cast<PetscInt>(n), !nonsymmetric_);
  if (P_) {
    MatInfo a, p;
    SPH_PETSC(MatGetInfo(A_, MAT_GLOBAL_SUM, &a));
    SPH_PETSC(MatGetInfo(P_, MAT_GLOBAL_SUM, &p));
    if (a.nz_used > 0) pc_kept_entries_ = p.nz_used / a.nz_used;
  }

  if (!nonsymmetric_ && !any_dirichlet) {  // symmetric and singular: the constants span both null spaces
    SPH_PETSC(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_TRUE, 0, nullptr, &nullspace_));
    SPH_PETSC(MatSetNullSpace(A_, nullspace_));
    SPH_PETSC(MatSetTransposeNullSpace(A_, nullspace_));
  }
  SPH_PETSC(MatCreateVecs(A_, &x_, &b_));
  if (regularised_) {
    PetscScalar trace;
    PetscInt rows;
    SPH_PETSC(MatGetDiagonal(A_, x_));
    SPH_PETSC(VecSum(x_, &trace));
    SPH_PETSC(VecGetSize(x_, &rows));
    SPH_PETSC(MatShift(A_, regularisation * trace / rows));
    if (P_) SPH_PETSC(MatShift(P_, regularisation * trace / rows));
  }
  SPH_PETSC(KSPSetOperators(ksp_, A_, P_ ? P_ : A_));
  if (closed_) prepare_spread();
}

// A closed domain's equations are not all satisfiable: the discrete source has a part outside the
// matrix's range (the left null vector y is not known: the wall rows and the consistent Laplacian
// make A non-symmetric). The mean removed by remove_net_source is most of it, not all. With one
// equation dropped for the pin, the rest lands on the pinned particle as a point source, a pressure spike
// that makes the results depend on where the pin is (docs/verification/lid_driven_cavity.md, "The walls
// at rest in the source, and the closed domain's pinned pressure"). So the pinned equation is restored
// instead: p' = p - lambda z, where A z = e (1 on the fluid rows but the pinned one), satisfies every
// fluid row up to the same even source lambda, the pinned one included, when
// lambda = (a_k . p - b_k) / (a_k . z - 1).
// z costs one solve per matrix, shared by the step's solves.
template <int D> void PressurePoisson<D>::prepare_spread() {
  SPH_PETSC(VecDuplicate(x_, &pinned_equation_));
  SPH_PETSC(VecSet(pinned_equation_, 0.0));
  for (const auto& [column, value] : rows_.pinned_equation)
    SPH_PETSC(VecSetValue(pinned_equation_, column, value, ADD_VALUES));
  SPH_PETSC(VecAssemblyBegin(pinned_equation_));
  SPH_PETSC(VecAssemblyEnd(pinned_equation_));

  SPH_PETSC(VecDuplicate(x_, &spread_));
  SPH_PETSC(VecSet(spread_, 0.0));
  PetscScalar* e;
  PetscInt n;
  SPH_PETSC(VecGetLocalSize(b_, &n));
  SPH_PETSC(VecGetArray(b_, &e));
  for (PetscInt i = 0; i < n; ++i) e[i] = kind_[i] == kFluid && i != pinned_ ? 1.0 : 0.0;
  SPH_PETSC(VecRestoreArray(b_, &e));
  announce_solve("closed-domain spread (A z = 1)");
  SPH_PETSC(KSPSolve(ksp_, b_, spread_));
  view_solve();
  KSPConvergedReason reason;
  SPH_PETSC(KSPGetConvergedReason(ksp_, &reason));
  SPH_PETSC(KSPGetIterationNumber(ksp_, &spread_iterations_));
  if (reason < 0)
    throw Error(std::string("pressure Poisson solve for the closed domain's even source did not converge (") +
                KSPConvergedReasons[reason] +
                "); try -ppe_ksp_max_it, another -ppe_ksp_type/-ppe_pc_type, or a smaller -cfl");
  SPH_PETSC(VecDot(pinned_equation_, spread_, &spread_denominator_));
  spread_denominator_ -= 1.0;
}

// PETSc prints -ppe_ksp_view and the like itself; -ppe_pc_view (the PC's prefix is the KSP's) is left
// to whoever drives the PC, and the matrix is shown by -mat_view once per solve (see set_from_options).
template <int D> void PressurePoisson<D>::view_solve() const {
  PC pc;
  SPH_PETSC(KSPGetPC(ksp_, &pc));
  SPH_PETSC(PCViewFromOptions(pc, reinterpret_cast<PetscObject>(ksp_), "-pc_view"));
  if (mat_viewer_) {
    SPH_PETSC(PetscViewerPushFormat(mat_viewer_, mat_format_));
    SPH_PETSC(MatView(A_, mat_viewer_));
    SPH_PETSC(PetscViewerPopFormat(mat_viewer_));
  }
}

template <int D> void PressurePoisson<D>::announce_solve(const char* which) const {
  if (announce_solves_) SPH_PETSC(PetscPrintf(PETSC_COMM_WORLD, "PPE %s solve\n", which));
}

// x holds the pinned system's solution; b_k, the pinned row's own right-hand side, is `pinned_rhs`.
template <int D> void PressurePoisson<D>::spread_pinned_residual(double pinned_rhs) {
  PetscScalar pinned_lhs;
  SPH_PETSC(VecDot(pinned_equation_, x_, &pinned_lhs));
  SPH_PETSC(VecAXPY(x_, -(pinned_lhs - pinned_rhs) / spread_denominator_, spread_));
}

// In a closed walled domain the continuity equations of the fluid, summed, say that no net mass
// leaves it: the mass-weighted sources must add up to zero, or no pressure satisfies them all. Wall
// ends (where a lid meets a corner) and round-off leave a net source; with one equation dropped for
// the pinned particle, all of it would land on that particle as a point source, whose pressure
// spike can expel it through the wall (docs/verification/lid_driven_cavity.md, "Design measurements").
// So the net source is spread evenly over the fluid rows instead.
template <int D> double PressurePoisson<D>::remove_net_source(const std::vector<double>& source,
                                                              const std::vector<double>& mass, PetscScalar* b,
                                                              PetscInt n) const {
  // The pinned particle's continuity equation is dropped from the system but still counts here, and
  // its share of the mean is part of the right-hand side that spread_pinned_residual restores.
  double sums[2] = {0.0, 0.0};  // sum of -m s over the fluid particles, their number
  for (PetscInt i = 0; i < n; ++i) {
    if (kind_[i] != kFluid || dirichlet_[i]) continue;
    sums[0] -= mass[i] * source[i];
    sums[1] += 1.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  if (sums[1] == 0.0) return 0.0;
  const double mean = sums[0] / sums[1];
  for (PetscInt i = 0; i < n; ++i)
    if (kind_[i] == kFluid && i != pinned_ && !dirichlet_[i]) b[i] -= mean;
  return mean;
}

template <int D> StepReport PressurePoisson<D>::solve(const std::vector<double>& source,
                                                      const std::vector<double>& mass, std::vector<double>& p,
                                                      bool use_guess, bool correction) {
  PetscScalar *b, *x;
  PetscInt n;
  SPH_PETSC(VecGetLocalSize(b_, &n));
  SPH_PETSC(VecGetArray(b_, &b));
  SPH_PETSC(VecGetArray(x_, &x));
  for (PetscInt i = 0; i < n; ++i) {
    const bool fluid_row = kind_[i] == kFluid && i != pinned_ && !dirichlet_[i];
    b[i] = fluid_row ? -mass[i] * source[i] : correction ? 0.0 : rows_.rhs[i];
    x[i] = use_guess ? p[i] : 0.0;
  }
  double pinned_rhs = 0.0;  // b_k, the pinned row's right-hand side were it not pinned
  if (closed_) {
    const double mean = remove_net_source(source, mass, b, n);
    if (pinned_ >= 0) pinned_rhs = -mass[pinned_] * source[pinned_] - mean;
    MPI_Allreduce(MPI_IN_PLACE, &pinned_rhs, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  }
  if (regularised_) {  // most of the part of b outside the range is its mean: spread it evenly
    double sums[2] = {0.0, static_cast<double>(n)};
    for (PetscInt i = 0; i < n; ++i) sums[0] += b[i];
    MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    for (PetscInt i = 0; i < n; ++i) b[i] -= sums[0] / sums[1];
  }
  SPH_PETSC(VecRestoreArray(b_, &b));
  SPH_PETSC(VecRestoreArray(x_, &x));
  // The discrete divergence of u* need not sum to zero exactly: project out the part of the
  // right-hand side that no pressure can produce.
  if (nullspace_) SPH_PETSC(MatNullSpaceRemove(nullspace_, b_));
  // A correction solve (a pressure increment, smaller than the pressure by the relative size of the
  // divergence it removes) needs the first solve's accuracy in absolute terms, not relative to its
  // own right-hand side: its residual is held to rtol times the first solve's right-hand side.
  PetscReal rtol, atol, dtol;
  PetscInt max_it;
  SPH_PETSC(KSPGetTolerances(ksp_, &rtol, &atol, &dtol, &max_it));
  if (correction) SPH_PETSC(KSPSetTolerances(ksp_, rtol, std::max(atol, rtol * first_rhs_norm_), dtol, max_it));
  else SPH_PETSC(VecNorm(b_, NORM_2, &first_rhs_norm_));
  announce_solve(correction ? "correction" : "projection");
  SPH_PETSC(KSPSolve(ksp_, b_, x_));
  if (correction) SPH_PETSC(KSPSetTolerances(ksp_, rtol, atol, dtol, max_it));
  view_solve();
  if (nullspace_) SPH_PETSC(MatNullSpaceRemove(nullspace_, x_));
  if (closed_) spread_pinned_residual(pinned_rhs);
  if (regularised_) {  // the constant part c (see assemble) carries no physics
    PetscScalar sum;
    PetscInt rows;
    SPH_PETSC(VecSum(x_, &sum));
    SPH_PETSC(VecGetSize(x_, &rows));
    SPH_PETSC(VecShift(x_, -sum / rows));
  }

  StepReport report;
  KSPConvergedReason reason;
  PetscInt its;
  SPH_PETSC(KSPGetConvergedReason(ksp_, &reason));
  SPH_PETSC(KSPGetIterationNumber(ksp_, &its));
  SPH_PETSC(KSPGetResidualNorm(ksp_, &report.linear_residual));
  report.linear_iterations = static_cast<int>(its);
  if (!correction) report.linear_iterations += static_cast<int>(spread_iterations_), spread_iterations_ = 0;
  report.linear_reason = static_cast<int>(reason);
  if (reason < 0) {
    std::ostringstream msg;
    msg << "pressure Poisson solve did not converge (" << KSPConvergedReasons[reason] << " after " << its
        << " iterations, residual " << report.linear_residual
        << "); try -ppe_ksp_max_it, another -ppe_ksp_type/-ppe_pc_type, or a smaller -cfl";
    throw Error(msg.str());
  }
  const PetscScalar* xs;
  SPH_PETSC(VecGetArrayRead(x_, &xs));
  for (PetscInt i = 0; i < n; ++i) p[i] = xs[i];
  SPH_PETSC(VecRestoreArrayRead(x_, &xs));
  return report;
}

template <int D> nlohmann::json PressurePoisson<D>::describe() const {
  KSPType ktype;
  PCType ptype;
  PC pc;
  PetscReal rtol, abstol, dtol;
  PetscInt maxit;
  SPH_PETSC(KSPGetType(ksp_, &ktype));
  SPH_PETSC(KSPGetPC(ksp_, &pc));
  SPH_PETSC(PCGetType(pc, &ptype));
  SPH_PETSC(KSPGetTolerances(ksp_, &rtol, &abstol, &dtol, &maxit));
  nlohmann::json j{{"type", ktype ? ktype : ""}, {"pc_type", ptype ? ptype : ""}, {"rtol", rtol}, {"max_it", maxit}};
  if (pc_kept_entries_ >= 0.0) {  // the lumped preconditioner's tolerance, and the last matrix's entries it kept
    j["pc_drop_tol"] = pc_drop_tol_;
    j["pc_kept_entries"] = pc_kept_entries_;
  }
  if (ptype && std::string(ptype) == PCHYPRE) {
    const char* htype = nullptr;
    SPH_PETSC(PCHYPREGetType(pc, &htype));
    if (htype) j["pc_hypre_type"] = htype;
  }
  return j;
}

template class PressurePoisson<1>;
template class PressurePoisson<2>;
template class PressurePoisson<3>;

}  // namespace sph
