#pragma once
// The PETSc matrix of the pressure Poisson rows. Its type follows PETSc's conventions: AIJ (SeqAIJ on
// one rank, so the factorisations ILU, ICC and LU apply; MPIAIJ on more), or whatever -mat_type asks
// for (with the other -mat_* options).
//  - AIJ is a view of the rows' own arrays (MatCreateSeqAIJWithArrays / MatCreateMPIAIJWithSplitArrays),
//    which saves the copy (docs/performance.md, "Design measurements"). It must be destroyed before the
//    rows are rebuilt.
//  - Any other type is filled with MatSetValues into an exact preallocation.
#include <petscmat.h>

#include "solvers/isph/ppe_rows.hpp"

namespace sph {

// Creates and assembles the n x n (owned rows) matrix. `symmetric` says whether the rows are, so that a
// -mat_type storing half the matrix (sbaij) is refused where it would drop half of it.
::Mat make_ppe_matrix(PpeRows& rows, PetscInt n, bool symmetric);

// The preconditioner's rows (-ppe_pc_drop_tol): each off-diagonal entry with |a_ij| < tol |a_ii| is
// added to its row's diagonal instead of kept, so every row sum stays what it was (a Laplacian row's
// zero, a wall row's extrapolation weights summing to one). A consistent-Laplacian row has about 29
// entries in 2D (support 3 dx) and 110 in 3D, most of them the weak outer shells of the kernel;
// BoomerAMG's set-up and every V-cycle cost in proportion to the entries it is given, while the
// Krylov method still iterates on the whole matrix, so the solve's tolerance means what it meant.
// Only the rows' values and columns are filled (no right-hand side, no pinned equation).
PpeRows lump_weak_entries(const PpeRows& rows, PetscInt n, double tol);

}  // namespace sph
