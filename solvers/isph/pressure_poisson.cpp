#include "solvers/isph/pressure_poisson.hpp"

#include <algorithm>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "solvers/isph/ppe_matrix.hpp"
#include "src/core/error.hpp"
#include "src/core/options.hpp"

namespace sph {

namespace {

// What to change when the solve fails, by PETSc's reason: a system that is no longer a number comes from
// a flow that blew up before this step (a smaller time step, not the solver, is the fix); one that ran
// out of iterations needs more of them or a stronger preconditioner; a breakdown, another method.
std::string unconverged_advice(KSPConvergedReason reason, PetscInt max_it) {
  if (reason == KSP_DIVERGED_NANORINF)
    return ": the pressure system holds NaN or Inf, so the flow blew up before this solve (the last frame shows "
           "where); a smaller -cfl or -dt from the start, or from a checkpoint well before, may run past it";
  if (reason == KSP_DIVERGED_ITS)
    return "; raise -ppe_ksp_max_it (now " + std::to_string(max_it) +
           ") or choose a stronger -ppe_pc_type (hypre, the default, or gamg)";
  return "; try another -ppe_ksp_type (gmres, bcgs) or -ppe_pc_type (hypre, gamg)";
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
  if (null_vector_) VecDestroy(&null_vector_);
  if (b_) VecDestroy(&b_);
  if (x_) VecDestroy(&x_);
}

template <int D> void PressurePoisson<D>::release() {
  // The KSP keeps its type and options for describe(); reset, it lets go of the matrices and the AMG.
  if (ksp_) SPH_PETSC(KSPReset(ksp_));
  destroy_system();
  rows_.release(), pc_rows_.release();
}

template <int D>
void PressurePoisson<D>::assemble(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                  const Vector<D>& body_force, const std::vector<char>* dirichlet,
                                  const std::vector<LaplacianCorrection<D>>* consistent, const SurfaceNodes<D>* nodes,
                                  const WallImpact<D>* impact, const std::vector<Vector<D>>* wall_acceleration) {
  const std::size_t n = P.n_owned;
  kind_.assign(P.kind.begin(), P.kind.begin() + n);
  if (dirichlet) dirichlet_ = *dirichlet;
  else dirichlet_.assign(n, 0);
  int any_dirichlet = 0;
  for (char c : dirichlet_) any_dirichlet |= c;
  if (nodes)
    for (std::size_t i = 0; i < n; ++i) any_dirichlet |= nodes->has(i);
  MPI_Allreduce(MPI_IN_PLACE, &any_dirichlet, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);

  // A non-symmetric singular matrix (no Dirichlet rows: a periodic or a closed walled domain) has an
  // unknown left null space, so the right-hand side cannot be projected onto its range. Its fluid rows
  // get eps * mean(diag) added to their diagonal instead. With p = c v + q (v the null vector: 1 on
  // the fluid and on the wall rows that see it), c absorbs the part of b outside the range, which q
  // sees spread evenly over the fluid rows, as one even source; the wall rows hold exactly. q is
  // changed by O(eps) and c v is removed afterwards. A pin would put all of that part on one particle
  // as a point source, and restoring its equation cost one more solve per matrix (docs/pressure-solve.md,
  // "Design measurements").
  regularised_ = nonsymmetric_ && !any_dirichlet;

  // The matrix may be a view of the rows' arrays: it goes first, with the KSP (and its
  // preconditioner's references to it).
  destroy_system();
  SPH_PETSC(KSPDestroy(&ksp_));
  // The fluid's pressure gradient along the walls, where the wall model uses it, is the last pressure's (P.p).
  const WallContinuation<D> continuation = walls ? walls->continuation(P, nh, K, P.p) : WallContinuation<D>();
  rows_.build(P, nh.list(), K, body_force, dirichlet_, consistent, nodes, impact, wall_acceleration, &continuation);
  // A new KSP for each new matrix, made from the options database: every option, viewers included,
  // then acts on every solve. Keeping one KSP saves no set-up time (the preconditioner is rebuilt for
  // each new matrix either way), and some preconditioners cannot be set up again on another matrix
  // (docs/pressure-solve.md, "Design measurements").
  // Made first: its preconditioner decides which matrix that is built from.
  create_ksp();
  make_matrices(n);
  if (!nonsymmetric_ && !any_dirichlet) {  // symmetric and singular: the constants span both null spaces
    SPH_PETSC(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_TRUE, 0, nullptr, &nullspace_));
    SPH_PETSC(MatSetNullSpace(A_, nullspace_));
    SPH_PETSC(MatSetTransposeNullSpace(A_, nullspace_));
  }
  SPH_PETSC(MatCreateVecs(A_, &x_, &b_));
  SPH_PETSC(MatCreateVecs(A_, &x_, &b_));
  if (regularised_) regularise(n);
  SPH_PETSC(KSPSetOperators(ksp_, A_, P_ ? P_ : A_));
}

// The matrix, and the preconditioner's own where it drops weak entries.
template <int D> void PressurePoisson<D>::make_matrices(std::size_t n) {
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
}

// The fluid rows' diagonal shifted by eps * mean(diag), and the null vector (assemble).
template <int D> void PressurePoisson<D>::regularise(std::size_t n) {
  PetscScalar trace;
  PetscInt rows;
  SPH_PETSC(MatGetDiagonal(A_, x_));
  SPH_PETSC(VecSum(x_, &trace));
  SPH_PETSC(VecGetSize(x_, &rows));
  const PetscScalar shift = regularisation * trace / rows;
  SPH_PETSC(VecDuplicate(x_, &null_vector_));
  PetscScalar *d, *v;
  SPH_PETSC(VecGetArray(x_, &d));
  SPH_PETSC(VecGetArray(null_vector_, &v));
  for (std::size_t i = 0; i < n; ++i) {
    d[i] = kind_[i] == kFluid ? shift : 0.0;
    v[i] = rows_.isolated[i] ? 0.0 : 1.0;
  }
  SPH_PETSC(VecRestoreArray(x_, &d));
  SPH_PETSC(VecRestoreArray(null_vector_, &v));
  SPH_PETSC(MatDiagonalSet(A_, x_, ADD_VALUES));
  if (P_) SPH_PETSC(MatDiagonalSet(P_, x_, ADD_VALUES));
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

// In a closed walled or periodic domain the continuity equations of the fluid, summed, say that no
// net mass leaves it: the mass-weighted sources must add up to zero, or no pressure satisfies them
// all. Wall ends (where a lid meets a corner) and round-off leave a net source. Its mean, most of the
// part outside the matrix's range, is taken off every fluid row here; the regularisation spreads the
// rest (see assemble). Left on one particle, it made a pressure spike that expelled it through the
// wall (docs/verification/lid_driven_cavity.md, "Design measurements").
template <int D> void PressurePoisson<D>::remove_net_source(const std::vector<double>& source,
                                                            const std::vector<double>& mass, PetscScalar* b,
                                                            PetscInt n) const {
  double sums[2] = {0.0, 0.0};  // sum of -m s over the fluid particles, their number
  for (PetscInt i = 0; i < n; ++i) {
    if (kind_[i] != kFluid || dirichlet_[i]) continue;
    sums[0] -= mass[i] * source[i];
    sums[1] += 1.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  if (sums[1] == 0.0) return;
  const double mean = sums[0] / sums[1];
  for (PetscInt i = 0; i < n; ++i)
    if (kind_[i] == kFluid && !dirichlet_[i]) b[i] -= mean;
}

// The solution less c v, c its mean over the fluid rows: the part along the null vector v that the
// regularisation let grow (see assemble) carries no physics. The fluid's mean pressure is zero.
template <int D> void PressurePoisson<D>::remove_null_part() {
  PetscScalar* x;
  const PetscScalar* v;
  PetscInt n;
  SPH_PETSC(VecGetLocalSize(x_, &n));
  SPH_PETSC(VecGetArray(x_, &x));
  SPH_PETSC(VecGetArrayRead(null_vector_, &v));
  double sums[2] = {0.0, 0.0};  // sum of x over the fluid rows, their number
  for (PetscInt i = 0; i < n; ++i)
    if (kind_[i] == kFluid) sums[0] += x[i], sums[1] += 1.0;
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  const double c = sums[1] > 0.0 ? sums[0] / sums[1] : 0.0;
  for (PetscInt i = 0; i < n; ++i) x[i] -= c * v[i];
  SPH_PETSC(VecRestoreArrayRead(null_vector_, &v));
  SPH_PETSC(VecRestoreArray(x_, &x));
}

// BoomerAMG builds from a copy of its matrix in hypre's format unless it is handed one. Converted at
// the first solve, once the caller has freed what only the assembly needed, PETSc's copy and the
// lumped rows go before the hierarchy is built: the step's memory peak (docs/performance.md, "Memory
// per particle").
template <int D> void PressurePoisson<D>::hand_preconditioner_matrix_to_hypre() {
  if (!P_) return;
  PetscBool converted = PETSC_FALSE;
  SPH_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(P_), MATHYPRE, &converted));
  if (converted) return;
  ::Mat copy;
  SPH_PETSC(MatConvert(P_, MATHYPRE, MAT_INITIAL_MATRIX, &copy));
  SPH_PETSC(MatDestroy(&P_));
  pc_rows_.release();
  P_ = copy;
  SPH_PETSC(KSPSetOperators(ksp_, A_, P_));
}

// Where b is near zero (a lone particle on a wall: nothing to project) the last pressure as a guess can
// leave a residual beyond PETSc's divergence test, dtol |b|, which then ends the solve at iteration 0
// (DIVERGED_DTOL). Such a guess starts from zero instead; any other guess is kept.
template <int D> void PressurePoisson<D>::drop_guess_the_divergence_test_fails() {
  Vec r;
  PetscReal b_norm, r_norm, rtol, atol, dtol;
  PetscInt max_it;
  SPH_PETSC(KSPGetTolerances(ksp_, &rtol, &atol, &dtol, &max_it));
  SPH_PETSC(VecDuplicate(b_, &r));
  SPH_PETSC(MatMult(A_, x_, r));
  SPH_PETSC(VecAYPX(r, -1.0, b_));
  SPH_PETSC(VecNorm(r, NORM_2, &r_norm));
  SPH_PETSC(VecNorm(b_, NORM_2, &b_norm));
  SPH_PETSC(VecDestroy(&r));
  if (r_norm > dtol * b_norm) SPH_PETSC(VecZeroEntries(x_));
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
    const bool fluid_row = kind_[i] == kFluid && !dirichlet_[i];
    b[i] = fluid_row ? -mass[i] * source[i] : correction ? 0.0 : rows_.rhs[i];
    x[i] = use_guess ? p[i] : 0.0;
  }
  if (regularised_) remove_net_source(source, mass, b, n);
  SPH_PETSC(VecRestoreArray(b_, &b));
  SPH_PETSC(VecRestoreArray(x_, &x));
  // The discrete divergence of u* need not sum to zero exactly: project out the part of the
  // right-hand side that no pressure can produce.
  if (nullspace_) SPH_PETSC(MatNullSpaceRemove(nullspace_, b_));
  if (use_guess) drop_guess_the_divergence_test_fails();
  // A correction solve (a pressure increment, smaller than the pressure by the relative size of the
  // divergence it removes) needs the first solve's accuracy in absolute terms, not relative to its
  // own right-hand side: its residual is held to rtol times the first solve's right-hand side.
  PetscReal rtol, atol, dtol;
  PetscInt max_it;
  SPH_PETSC(KSPGetTolerances(ksp_, &rtol, &atol, &dtol, &max_it));
  if (correction) SPH_PETSC(KSPSetTolerances(ksp_, rtol, std::max(atol, rtol * first_rhs_norm_), dtol, max_it));
  else SPH_PETSC(VecNorm(b_, NORM_2, &first_rhs_norm_));
  announce_solve(correction ? "correction" : "projection");
  hand_preconditioner_matrix_to_hypre();
  SPH_PETSC(KSPSolve(ksp_, b_, x_));
  if (correction) SPH_PETSC(KSPSetTolerances(ksp_, rtol, atol, dtol, max_it));
  view_solve();
  if (nullspace_) SPH_PETSC(MatNullSpaceRemove(nullspace_, x_));
  if (regularised_) remove_null_part();

  StepReport report;
  KSPConvergedReason reason;
  PetscInt its;
  SPH_PETSC(KSPGetConvergedReason(ksp_, &reason));
  SPH_PETSC(KSPGetIterationNumber(ksp_, &its));
  SPH_PETSC(KSPGetResidualNorm(ksp_, &report.linear_residual));
  report.linear_iterations = static_cast<int>(its);
  report.linear_reason = static_cast<int>(reason);
  if (reason < 0) {
    std::ostringstream msg;
    msg << "pressure Poisson solve did not converge (" << KSPConvergedReasons[reason] << " after " << its
        << " iterations, residual " << report.linear_residual << ")";
    PC pc;
    SPH_PETSC(KSPGetPC(ksp_, &pc));
    // A one-level preconditioner leaves the regularised system's near-null mode (eigenvalue eps) to
    // the Krylov method, which cannot reduce it where the source has a part outside the range.
    if (regularised_ && !is_multilevel(pc))
      msg << ": with no free surface the pressure system is singular, regularised by a tiny diagonal shift, and "
             "a one-level preconditioner stalls on the near-constant mode that leaves; use a multigrid one "
             "(-ppe_pc_type hypre, the default, or gamg)";
    else msg << unconverged_advice(reason, max_it);
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
