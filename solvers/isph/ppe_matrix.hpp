#pragma once
// The PETSc matrix of the pressure Poisson rows. Its type follows PETSc's conventions: AIJ (SeqAIJ on
// one rank, so the factorisations ILU, ICC and LU apply; MPIAIJ on more), or whatever -mat_type asks
// for (with the other -mat_* options).
//  - AIJ is a view of the rows' own arrays (MatCreateSeqAIJWithArrays / MatCreateMPIAIJWithSplitArrays):
//    copying them in cost about 0.01 s of a 0.16 s step (Taylor-Green nx 128). It must be destroyed before
//    the rows are rebuilt.
//  - Any other type is filled with MatSetValues into an exact preallocation.
#include <petscmat.h>

#include "solvers/isph/ppe_rows.hpp"

namespace sph {

// Creates and assembles the n x n (owned rows) matrix. `symmetric` says whether the rows are, so that a
// -mat_type storing half the matrix (sbaij) is refused where it would drop half of it.
::Mat make_ppe_matrix(PpeRows& rows, PetscInt n, bool symmetric);

}  // namespace sph
