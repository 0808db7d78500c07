// The pressure solve's Krylov solver: made anew for every matrix from the defaults (GMRES or CG by
// the matrix's symmetry, BoomerAMG, right preconditioning, the 3D coarsening) and then the user's
// -ppe_ksp_* / -ppe_pc_* options (the KSP's options prefix is ppe_), with the checks of what those
// make of it. The matrix and the solve: pressure_poisson.cpp.
#include <string>
#include <utility>
#include <vector>

#include "solvers/isph/pressure_poisson.hpp"
#include "src/core/error.hpp"
#include "src/core/option_reads.hpp"
#include "src/core/options.hpp"

namespace sph {

bool is_boomeramg(PC pc) {
  PetscBool hypre = PETSC_FALSE;
  SPH_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCHYPRE, &hypre));
  const char* htype = nullptr;
  if (hypre) SPH_PETSC(PCHYPREGetType(pc, &htype));
  return htype && std::string(htype) == "boomeramg";
}

bool is_multilevel(PC pc) {
  PetscBool mg = PETSC_FALSE;
  SPH_PETSC(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &mg, PCGAMG, PCMG, PCML, ""));
  return mg || is_boomeramg(pc);
}

// The defaults, then every -ppe_ksp_* / -ppe_pc_* option from the database (viewers included:
// KSPReset dropped those, which is why the KSP is made anew instead of reset).
template <int D> void PressurePoisson<D>::create_ksp() {
  if (ksp_) SPH_PETSC(KSPDestroy(&ksp_));
  SPH_PETSC(KSPCreate(PETSC_COMM_WORLD, &ksp_));
  // Its PC, and the solvers a PC makes (-ppe_sub_*, -ppe_mg_levels_*), take the prefix too.
  SPH_PETSC(KSPSetOptionsPrefix(ksp_, options_prefix));
  SPH_PETSC(KSPSetType(ksp_, nonsymmetric_ ? KSPGMRES : KSPCG));
  PC pc;
  SPH_PETSC(KSPGetPC(ksp_, &pc));
  // BoomerAMG unless -ppe_pc_hypre_type says otherwise (PCHYPRESetType would fix it).
  SPH_PETSC(PCSetType(pc, PCHYPRE));
  SPH_PETSC(KSPSetTolerances(ksp_, 1e-8, 1e-50, PETSC_DEFAULT, 1000));
  // The previous step's pressure is a good first guess.
  SPH_PETSC(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE));
  if (nonsymmetric_) SPH_PETSC(KSPSetPCSide(ksp_, PC_RIGHT));  // before the options: -help shows it
  SPH_PETSC(KSPSetFromOptions(ksp_));
  right_preconditioning();
  check_ksp_choice();
  aggressive_coarsening_in_3d();
  symmetric_coarse_solve();
}

// What the defaults above would make of the user's KSP: a direct solve (preonly) takes no first guess,
// and a method for symmetric matrices is warned against on the non-symmetric matrix, not refused: it
// may converge there or not, depending on the preconditioner (docs/solvers.md).
template <int D> void PressurePoisson<D>::check_ksp_choice() {
  PetscBool preonly = PETSC_FALSE, symmetric_only = PETSC_FALSE, user_guess = PETSC_FALSE;
  SPH_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(ksp_), KSPPREONLY, &preonly));
  SPH_PETSC(PetscOptionsHasName(nullptr, options_prefix, "-ksp_initial_guess_nonzero", &user_guess));
  if (preonly && !user_guess) SPH_PETSC(KSPSetInitialGuessNonzero(ksp_, PETSC_FALSE));
  SPH_PETSC(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(ksp_), &symmetric_only, KSPCG, KSPPIPECG,
                                      KSPGROPPCG, KSPPIPECGRR, KSPCR, KSPPIPECR, KSPMINRES, KSPSYMMLQ, ""));
  static bool warned = false;  // the KSP is made anew every step
  if (nonsymmetric_ && symmetric_only && !warned) {
    KSPType type = nullptr;
    SPH_PETSC(KSPGetType(ksp_, &type));
    SPH_PETSC(
        PetscFPrintf(PETSC_COMM_WORLD, stderr,
                     "sph: warning: -ppe_ksp_type %s assumes a symmetric matrix, and this run's pressure matrix "
                     "is not (the consistent operators, walls or a free surface make it so): it may not "
                     "converge; the default (gmres) or bcgs suit it, or -isph_operators classic in a periodic scene\n",
                     type));
    warned = true;
  }
}

// BoomerAMG under a temporary option: PCHYPRE reads its BoomerAMG settings from the options database
// only, so each (name, value) is put there, under the PC's prefix, for one PCSetFromOptions and taken
// out again. Settings a PCSetFromOptions does not find keep their values, so later calls do not undo
// these. Names as PETSc knows them without a prefix ("-pc_hypre_boomeramg_agg_nl").
namespace {
PetscErrorCode set_boomeramg_options(PC pc, const std::vector<std::pair<const char*, const char*>>& options) {
  PetscFunctionBeginUser;
  const char* prefix = nullptr;
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  auto prefixed = [prefix](const char* name) { return "-" + std::string(prefix ? prefix : "") + (name + 1); };
  for (const auto& [name, value] : options) PetscCall(PetscOptionsSetValue(nullptr, prefixed(name).c_str(), value));
  PetscCall(PCSetFromOptions(pc));
  for (const auto& [name, value] : options) PetscCall(PetscOptionsClearValue(nullptr, prefixed(name).c_str()));
  PetscFunctionReturn(0);
}

}  // namespace

// In 3D a PPE row has about 110 neighbours instead of 20, and BoomerAMG's default (Falgout coarsening,
// classical interpolation, strong threshold 0.25) spends half the pressure solve in its set-up, which
// is made anew every solve. HMIS coarsening with ext+i interpolation, strong threshold 0.5 and one
// level of aggressive coarsening takes twice the iterations and a fifth of the set-up, a faster solve
// with the same results; in 2D it does not pay (docs/pressure-solve.md, "BoomerAMG in 3D"). So this is
// the 3D default only, and only when the user sets none of these four options.
template <int D> void PressurePoisson<D>::aggressive_coarsening_in_3d() {
  if (D != 3) return;
  PC pc;
  SPH_PETSC(KSPGetPC(ksp_, &pc));
  if (!is_boomeramg(pc)) return;
  const std::vector<std::pair<const char*, const char*>> options = {{"-pc_hypre_boomeramg_coarsen_type", "HMIS"},
                                                                    {"-pc_hypre_boomeramg_interp_type", "ext+i"},
                                                                    {"-pc_hypre_boomeramg_strong_threshold", "0.5"},
                                                                    {"-pc_hypre_boomeramg_agg_nl", "1"}};
  for (const auto& [name, value] : options) {
    PetscBool user = PETSC_FALSE;
    SPH_PETSC(PetscOptionsHasName(nullptr, options_prefix, name, &user));
    if (user) return;
  }
  SPH_PETSC(set_boomeramg_options(pc, options));
}

// Right preconditioning for the non-symmetric matrix: the tolerance then applies to the true residual.
// With left preconditioning it applies to the preconditioned one, which the near-null constant mode of
// a regularised periodic system (see assemble) inflates by 1/eps, which left the solution far less
// accurate than the tolerance and dependent on the rank count (docs/pressure-solve.md, "Design
// measurements").
// Only for the KSP types that offer both sides, and unless -ppe_ksp_pc_side says otherwise.
template <int D> void PressurePoisson<D>::right_preconditioning() {
  PetscBool user_side = PETSC_FALSE, both_sides = PETSC_FALSE;
  SPH_PETSC(PetscOptionsHasName(nullptr, options_prefix, "-ksp_pc_side", &user_side));
  SPH_PETSC(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(ksp_), &both_sides, KSPGMRES, KSPLGMRES, KSPDGMRES,
                                      KSPPGMRES, KSPBCGS, KSPIBCGS, KSPFBCGS, KSPFBCGSR, KSPBCGSL, KSPPIPEBCGS, ""));
  if (user_side) return;
  // Set before the options for -help; a type chosen there that has one side only decides it itself.
  SPH_PETSC(KSPSetPCSide(ksp_, nonsymmetric_ && both_sides ? PC_RIGHT : PC_SIDE_DEFAULT));
}

// CG needs a symmetric positive definite preconditioner. BoomerAMG's default coarse solve, Gaussian
// elimination, is not one on the singular coarse matrix of a periodic domain (CG stops with
// DIVERGED_INDEFINITE_PC). So under a CG-type KSP the coarse level is relaxed with the
// symmetric-SOR/Jacobi of the other levels, unless the user chose a coarse or an all-level relaxation;
// it costs no iterations (docs/pressure-solve.md, "The coarse level under CG").
template <int D> void PressurePoisson<D>::symmetric_coarse_solve() {
  PetscBool cg = PETSC_FALSE, user = PETSC_FALSE, user_all = PETSC_FALSE;
  SPH_PETSC(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(ksp_), &cg, KSPCG, KSPPIPECG, KSPGROPPCG,
                                      KSPPIPECGRR, KSPCR, KSPPIPECR, KSPMINRES, KSPSYMMLQ, ""));
  PC pc;
  SPH_PETSC(KSPGetPC(ksp_, &pc));
  SPH_PETSC(PetscOptionsHasName(nullptr, options_prefix, coarse_relax_option, &user));
  SPH_PETSC(PetscOptionsHasName(nullptr, options_prefix, "-pc_hypre_boomeramg_relax_type_all", &user_all));
  if (!cg || !is_boomeramg(pc) || user || user_all) return;
  SPH_PETSC(set_boomeramg_options(pc, {{coarse_relax_option, "symmetric-SOR/Jacobi"}}));
}

namespace {
// PETSc reads a tolerance of -1 or -2 as PETSC_DECIDE / PETSC_DEFAULT, so a negative one is not refused
// there: it failed at the first solve, blamed on the solve. Checked at start-up instead. Names without
// the prefix, which the message puts in front.
void check_ksp_tolerances(const char* prefix) {
  auto get = [prefix](const char* name, bool positive_integer, auto ok, const char* what) {
    PetscReal v = 0.0;
    PetscInt k = 0;
    PetscBool set = PETSC_FALSE;
    if (positive_integer) SPH_PETSC(PetscOptionsGetInt(nullptr, prefix, name, &k, &set)), v = static_cast<double>(k);
    else SPH_PETSC(PetscOptionsGetReal(nullptr, prefix, name, &v, &set));
    if (set) require(ok(v), "-" + std::string(prefix) + (name + 1), what, v);
  };
  get(
      "-ksp_rtol", false, [](double v) { return v > 0 && v < 1; }, "in (0, 1)");
  get(
      "-ksp_atol", false, [](double v) { return v >= 0; }, "non-negative");
  get(
      "-ksp_divtol", false, [](double v) { return v > 1; }, "above 1");
  get(
      "-ksp_max_it", true, [](double v) { return v >= 1; }, "at least 1");
}
}  // namespace

namespace {
PetscErrorCode read_ppe_options(PetscReal* pc_drop_tol) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "Pressure Poisson equation (-solver isph)", "Solver");
  PetscCall(option_real(PetscOptionsObject, "-ppe_pc_drop_tol",
                        "The preconditioner (BoomerAMG) is built from the pressure matrix with each off-diagonal "
                        "entry below this fraction of its row's diagonal added to the diagonal instead; the "
                        "Krylov method still solves the whole matrix to -ppe_ksp_rtol (0: the whole matrix; "
                        "BoomerAMG on non-symmetric matrices only, the default solver and operators)",
                        *pc_drop_tol, pc_drop_tol, nullptr, OptionLevel::expert));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
}  // namespace

namespace {
// The pressure solve's PETSc options that this program names (in -help's essential section, the
// checks above and below, the docs): the hints for a misspelt one. PETSc reads many more, found
// when given (PetscOptionsUsed), but cannot list them without printing its help.
const std::vector<const char*> needs_value = {"-ksp_type",
                                              "-pc_type",
                                              "-ksp_rtol",
                                              "-ksp_atol",
                                              "-ksp_divtol",
                                              "-ksp_max_it",
                                              "-ksp_norm_type",
                                              "-ksp_pc_side",
                                              "-ksp_gmres_restart",
                                              "-pc_hypre_type",
                                              "-pc_hypre_boomeramg_coarsen_type",
                                              "-pc_hypre_boomeramg_interp_type",
                                              "-pc_hypre_boomeramg_strong_threshold",
                                              "-pc_hypre_boomeramg_agg_nl",
                                              "-pc_hypre_boomeramg_relax_type_all",
                                              "-pc_hypre_boomeramg_relax_type_coarse",
                                              "-pc_hypre_boomeramg_max_iter",
                                              "-pc_factor_mat_solver_type"};
const std::vector<const char*> flags_and_viewers = {"-ksp_monitor",
                                                    "-ksp_monitor_short",
                                                    "-ksp_monitor_true_residual",
                                                    "-ksp_converged_reason",
                                                    "-ksp_view",
                                                    "-ksp_view_final_residual",
                                                    "-ksp_initial_guess_nonzero",
                                                    "-ksp_error_if_not_converged",
                                                    "-pc_view",
                                                    "-pc_hypre_boomeramg_print_statistics"};
}  // namespace

template <int D> void PressurePoisson<D>::set_from_options() {
  if (ksp_) return;
  record_option_names(options_prefix, needs_value);
  record_option_names(options_prefix, flags_and_viewers);
  // PETSc drops such an option given without a value and keeps its default.
  refuse_valueless(options_prefix, needs_value);
  check_ksp_tolerances(options_prefix);
  PetscReal pc_drop_tol = pc_drop_tol_;
  SPH_PETSC(read_ppe_options(&pc_drop_tol));
  require(pc_drop_tol >= 0 && pc_drop_tol < 1, "-ppe_pc_drop_tol", "in [0, 1)", pc_drop_tol);
  pc_drop_tol_ = pc_drop_tol;
  // -mat_view: PETSc shows every matrix assembled while it is set, the preconditioners' own too
  // (hypre's copy, multigrid's coarse levels, a diagonal shift's re-assembly). The PPE takes it out of
  // the database and shows its own matrix once per solve instead.
  PetscBool set = PETSC_FALSE;
  SPH_PETSC(PetscOptionsGetViewer(PETSC_COMM_WORLD, nullptr, nullptr, "-mat_view", &mat_viewer_, &mat_format_, &set));
  if (set) SPH_PETSC(PetscOptionsClearValue(nullptr, "-mat_view"));
  // A step solves the PPE two or three times with one KSP; PETSc's viewers do not say which solve
  // they show, so each solve is announced while one of them is on.
  for (const char* viewer : {"-ksp_monitor", "-ksp_monitor_short", "-ksp_monitor_true_residual",
                             "-ksp_converged_reason", "-ksp_view", "-ksp_view_final_residual"}) {
    PetscBool given = PETSC_FALSE;
    SPH_PETSC(PetscOptionsHasName(nullptr, options_prefix, viewer, &given));  // -ppe_ksp_monitor, ...
    announce_solves_ = announce_solves_ || given;
  }
  create_ksp();
}

template <int D> void PressurePoisson<D>::use_nonsymmetric(bool nonsymmetric) {
  if (nonsymmetric == nonsymmetric_ && ksp_) return;
  nonsymmetric_ = nonsymmetric;
  create_ksp();  // the defaults differ
}

template <int D> bool PressurePoisson<D>::reads_late(const std::string& option) {
  // Read during a solve or an assembly: the solve's viewers, the matrix's -mat_* options (-mat_type),
  // and, with the KSP's prefix before their own, a factorisation package's (-ppe_mat_mumps_icntl_4: the
  // factor takes the PC's prefix) and the options of the solvers a preconditioner makes in its set-up
  // (bjacobi/asm blocks, multigrid levels).
  static const char* const exact[] = {"ppe_ksp_converged_reason", "ppe_pc_view"};
  static const char* const prefixes[] = {"mat_",           "ppe_mat_",       "ppe_sub_",
                                         "ppe_mg_levels_", "ppe_mg_coarse_", "ppe_redundant_"};
  for (const char* e : exact)
    if (option == e) return true;
  for (const char* p : prefixes)
    if (option.rfind(p, 0) == 0) return true;
  return false;
}

template <int D> RenamedOption PressurePoisson<D>::renamed_option(const std::string& option) {
  // The KSP's own options and its PC's, those of the solvers a PC makes and a factorisation package's
  // (see reads_late); the matrix's own (-mat_type, -mat_view) have no prefix.
  static const char* const unprefixed[] = {"ksp_",           "pc_",         "sub_",       "mg_levels_",
                                           "mg_coarse_",     "redundant_",  "mat_mumps_", "mat_superlu_",
                                           "mat_strumpack_", "mat_pastix_", "mat_mkl_",   "mat_cholmod_",
                                           "mat_umfpack_",   "mat_klu_"};
  for (const char* p : unprefixed)
    if (option.rfind(p, 0) == 0)
      return {options_prefix + option, std::string("the pressure solve's options carry the prefix ") + options_prefix};
  return {};
}

// pressure_poisson.cpp's explicit instantiations of the class see only that file's members.
template void PressurePoisson<1>::create_ksp();
template void PressurePoisson<1>::check_ksp_choice();
template void PressurePoisson<1>::aggressive_coarsening_in_3d();
template void PressurePoisson<1>::right_preconditioning();
template void PressurePoisson<1>::symmetric_coarse_solve();
template void PressurePoisson<1>::set_from_options();
template void PressurePoisson<1>::use_nonsymmetric(bool);
template bool PressurePoisson<1>::reads_late(const std::string&);
template RenamedOption PressurePoisson<1>::renamed_option(const std::string&);
template void PressurePoisson<2>::create_ksp();
template void PressurePoisson<2>::check_ksp_choice();
template void PressurePoisson<2>::aggressive_coarsening_in_3d();
template void PressurePoisson<2>::right_preconditioning();
template void PressurePoisson<2>::symmetric_coarse_solve();
template void PressurePoisson<2>::set_from_options();
template void PressurePoisson<2>::use_nonsymmetric(bool);
template bool PressurePoisson<2>::reads_late(const std::string&);
template RenamedOption PressurePoisson<2>::renamed_option(const std::string&);
template void PressurePoisson<3>::create_ksp();
template void PressurePoisson<3>::check_ksp_choice();
template void PressurePoisson<3>::aggressive_coarsening_in_3d();
template void PressurePoisson<3>::right_preconditioning();
template void PressurePoisson<3>::symmetric_coarse_solve();
template void PressurePoisson<3>::set_from_options();
template void PressurePoisson<3>::use_nonsymmetric(bool);
template bool PressurePoisson<3>::reads_late(const std::string&);
template RenamedOption PressurePoisson<3>::renamed_option(const std::string&);

}  // namespace sph
