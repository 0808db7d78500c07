#pragma once
// The pressure Poisson equation of the ISPH projection, assembled into a PETSc matrix and solved with
// a PETSc KSP (default: CG + hypre BoomerAMG; every KSP/PC choice can be changed with PETSc's
// -ksp_* / -pc_* options under the prefix ppe_: -ppe_ksp_type, -ppe_pc_type, ...).
//
// Discretisation (fluid rows, each multiplied by -m_i):
//  - by default the consistent Laplacian (src/sph/consistent_laplacian.hpp), div(grad p / rho)_i =
//    sum_j w_ij (p_j - p_i) / rho_i with the density at rho0: exact for quadratic p on any particle
//    distribution, positive weights, zero row sums, but not symmetric: GMRES with AMG. Periodic
//    domains, where the system is singular, get a tiny diagonal shift (see assemble);
//  - with -isph_operators classic, the Laplacian of Cummins & Rudman (1999),
//    div(grad p / rho)_i = sum_j c_ij (p_i - p_j),  c_ij = 8 m_j F_ij / (rho_i + rho_j)^2.
//    Because m_i c_ij = m_j c_ji the matrix is symmetric, and since F_ij < 0 it is a positive
//    semi-definite M-matrix: CG with AMG applies. With no Dirichlet rows (periodic or closed domains)
//    the constant vector spans its null space; it is attached with MatSetNullSpace and removed from
//    the right-hand side, which makes the singular system consistent.
// Rows and columns use global particle indices, so the same code assembles a distributed matrix.
//
// Walls (Adami, Hu & Adams 2012): each wall particle has a row expressing its pressure as the
// Shepard-weighted extrapolation of the fluid pressure plus the body-force head,
//   p_w - sum_f w_wf p_f = sum_f w_wf rho_f g . r_wf,
// so fluid rows see walls through the same Laplacian and the wall pressure makes the normal pressure
// gradient balance the body force (the homogeneous Neumann condition without one). These rows are
// not symmetric: the default KSP becomes GMRES (BoomerAMG still preconditions it well: the matrix
// stays an M-matrix with zero row sums), and a closed domain's singular system is regularised instead
// of given a null space (see assemble), so that what no pressure can balance is spread evenly over
// the fluid rows.
//
// Free surface: particles flagged as on the surface get the Dirichlet row p = 0 (Lind et al. 2012);
// the pressure level is then fixed and neither a null space nor a pin is needed.
#include <petscksp.h>

#include <string>
#include <vector>

#include "solvers/isph/ppe_rows.hpp"
#include "src/run/solver.hpp"

namespace sph {

// Whether a preconditioner is hypre's BoomerAMG (ppe_krylov.cpp).
bool is_boomeramg(PC pc);
// Whether it is a multigrid (BoomerAMG, GAMG, MG, ML): one that resolves a near-null constant mode.
bool is_multilevel(PC pc);

template <int D> class PressurePoisson {
 public:
  PressurePoisson() = default;
  ~PressurePoisson();
  PressurePoisson(const PressurePoisson&) = delete;
  PressurePoisson& operator=(const PressurePoisson&) = delete;

  // Creates the KSP with the defaults above, then applies the user's -ppe_ksp_*/-ppe_pc_* options.
  // Each assemble makes the KSP anew the same way, so every option, viewers included, acts on every
  // solve.
  void set_from_options();

  // The options prefix of the KSP (and so of its PC and the solvers that makes): PETSc's -ksp_rtol is
  // -ppe_ksp_rtol here. Both solves of a step (the projection and the correction) use that one KSP.
  static constexpr const char* options_prefix = "ppe_";

  // Options PETSc reads only during a solve or an assembly (not at set-up): the driver checks them
  // after the first step instead of at start-up. Names without the leading dash.
  static bool reads_late(const std::string& option);
  // The options' names before they took the prefix (-ksp_rtol, -sub_pc_type): the name now, and why.
  static RenamedOption renamed_option(const std::string& option);

  // Tells the solver whether the matrix will be non-symmetric (walls, free surface, the consistent
  // Laplacian): the default KSP becomes GMRES unless the user chose one, and a singular system is
  // regularised instead of given a null space.
  void use_nonsymmetric(bool nonsymmetric);
  // The same before set_from_options, from what the options already say (the consistent operators),
  // so that -help shows the defaults a run gets (GMRES, right preconditioning); makes no KSP.
  void expect_nonsymmetric(bool nonsymmetric) { nonsymmetric_ = nonsymmetric; }
  // How the wall rows continue the fluid's pressure (the scheme's wall model; null: as published).
  const WallModel<D>* walls = nullptr;

  // Builds the matrix for the current particle positions (owned rows, global column indices).
  // Particles flagged in `dirichlet` (free surface) get the row p = 0.
  void assemble(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                const Vector<D>& body_force = Vector<D>::Zero(), const std::vector<char>* dirichlet = nullptr,
                const std::vector<LaplacianCorrection<D>>* consistent = nullptr, const SurfaceNodes<D>* nodes = nullptr,
                const WallImpact<D>* impact = nullptr, const std::vector<Vector<D>>* wall_acceleration = nullptr);

  // Solves div(grad p / rho) = source (one value per owned particle). With use_guess, p holds the
  // initial guess on entry (the previous step's pressure: a good one); otherwise the KSP starts from
  // zero. On exit p holds the solution; a system without Dirichlet rows gives it a zero mean over
  // the fluid. Throws sph::Error when the KSP does not
  // converge. A `correction` solve (a second one with the same matrix, for a pressure increment) gives
  // the wall rows a zero right-hand side (their body-force head is already in the first pressure) and
  // stops at the first solve's absolute accuracy (rtol times that solve's right-hand-side norm).
  StepReport solve(const std::vector<double>& source, const std::vector<double>& mass, std::vector<double>& p,
                   bool use_guess = true, bool correction = false);

  // Frees the matrix, its rows, the KSP and the preconditioner until the next assemble. A step's system
  // serves that step only; kept to the next, it adds to the peak of the neighbour search and the forces
  // (docs/performance.md, "Memory per particle").
  void release();

  ::Mat matrix() const { return A_; }
  // eps: a singular non-symmetric system's fluid rows get eps times its mean diagonal added (see assemble).
  static constexpr double regularisation = 1e-8;
  // The matrix BoomerAMG is built from: A's rows with their weak entries lumped (-ppe_pc_drop_tol), or A.
  ::Mat preconditioner_matrix() const { return P_ ? P_ : A_; }
  nlohmann::json describe() const;

 private:
  // Singular systems (see assemble): takes the net mass source's mean off the fluid rows of b, and
  // the part along the null vector off the solution.
  void remove_net_source(const std::vector<double>& source, const std::vector<double>& mass, PetscScalar* b,
                         PetscInt n) const;
  void remove_null_part();
  void drop_guess_the_divergence_test_fails();
  void hand_preconditioner_matrix_to_hypre();  // the lumped matrix, BoomerAMG's, in hypre's format
  void view_solve() const;
  void announce_solve(const char* which) const;
  void destroy_system();
  void make_matrices(std::size_t n);
  void regularise(std::size_t n);
  void create_ksp();
  void right_preconditioning();
  void check_ksp_choice();
  void symmetric_coarse_solve();
  void aggressive_coarsening_in_3d();
  // Without the prefix, as PETSc's functions that take one want it.
  static constexpr const char* coarse_relax_option = "-pc_hypre_boomeramg_relax_type_coarse";

  KSP ksp_ = nullptr;
  ::Mat A_ = nullptr;
  ::Mat P_ = nullptr;  // the preconditioner's matrix (lump_weak_entries), or null: A_ itself
  ::Vec b_ = nullptr, x_ = nullptr;
  MatNullSpace nullspace_ = nullptr;
  bool nonsymmetric_ = false;         // wall rows or the consistent Laplacian
  PetscReal first_rhs_norm_ = 0.0;    // |b| of the last solve that was not a correction
  PetscViewer mat_viewer_ = nullptr;  // -mat_view (see set_from_options)
  bool announce_solves_ = false;      // a KSP viewer is on: each solve prints which one it is
  PetscViewerFormat mat_format_ = PETSC_VIEWER_DEFAULT;
  bool regularised_ = false;     // non-symmetric and singular: the fluid rows' diagonal is shifted (see assemble)
  ::Vec null_vector_ = nullptr;  // v: 1 on the fluid rows and the wall rows that see fluid, 0 elsewhere
  std::vector<int> kind_;        // particle kind of each owned row
  std::vector<char> dirichlet_;  // rows with p = 0
  PpeRows rows_;                 // the matrix rows, and the right-hand side of wall rows
  PpeRows pc_rows_;              // P_'s rows
  // -ppe_pc_drop_tol (see assemble and lump_weak_entries). The default is the fastest pressure solve
  // across 2D and 3D scenes, lattices and disordered particles (docs/pressure-solve.md, "The
  // preconditioner's matrix").
  double pc_drop_tol_ = 0.02;
  double pc_kept_entries_ = -1.0;  // share of A's entries that P_ kept at the last assemble; -1: no P_
};

}  // namespace sph
