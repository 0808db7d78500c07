#include "solvers/isph/ppe_matrix.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "src/core/options.hpp"

namespace sph {

namespace {

// The matrix type the options ask for, from an empty matrix of the same layout.
std::string requested_type(PetscInt n) {
  ::Mat probe;
  MatType type;
  SPH_PETSC(MatCreate(PETSC_COMM_WORLD, &probe));
  SPH_PETSC(MatSetSizes(probe, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  SPH_PETSC(MatSetType(probe, MATAIJ));
  SPH_PETSC(MatSetFromOptions(probe));
  SPH_PETSC(MatGetType(probe, &type));
  const std::string name = type;
  SPH_PETSC(MatDestroy(&probe));
  return name;
}

}  // namespace

::Mat make_ppe_matrix(PpeRows& rows, PetscInt n, bool symmetric) {
  const std::string type = requested_type(n);
  ::Mat A;
  if (type == MATSEQAIJ) {
    SPH_PETSC(MatCreateSeqAIJWithArrays(PETSC_COMM_WORLD, n, n, rows.di.data(), rows.dj.data(), rows.da.data(), &A));
    return A;
  }
  if (type == MATMPIAIJ) {
    SPH_PETSC(MatCreateMPIAIJWithSplitArrays(PETSC_COMM_WORLD, n, n, PETSC_DETERMINE, PETSC_DETERMINE, rows.di.data(),
                                             rows.dj.data(), rows.da.data(), rows.oi.data(), rows.oj.data(),
                                             rows.oa.data(), &A));
    return A;
  }
  const bool half = type.find("sbaij") != std::string::npos;
  if (half && !symmetric)
    throw OptionError("-mat_type " + type +
                      " stores half of a symmetric matrix, but this pressure matrix is not symmetric (walls, a free "
                      "surface or -isph_operators consistent); use -mat_type aij");
  SPH_PETSC(MatCreate(PETSC_COMM_WORLD, &A));
  SPH_PETSC(MatSetSizes(A, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  SPH_PETSC(MatSetType(A, type.c_str()));
  SPH_PETSC(MatSetFromOptions(A));
  std::vector<PetscInt> dnz(n), onz(n);
  for (PetscInt i = 0; i < n; ++i) dnz[i] = rows.di[i + 1] - rows.di[i], onz[i] = rows.oi[i + 1] - rows.oi[i];
  SPH_PETSC(MatXAIJSetPreallocation(A, 1, dnz.data(), onz.data(), dnz.data(), onz.data()));
  if (half) SPH_PETSC(MatSetOption(A, MAT_IGNORE_LOWER_TRIANGULAR, PETSC_TRUE));
  PetscInt first;
  SPH_PETSC(MatGetOwnershipRange(A, &first, nullptr));
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> vals;
  for (PetscInt i = 0; i < n; ++i) {
    cols.clear(), vals.clear();
    for (PetscInt k = rows.di[i]; k < rows.di[i + 1]; ++k)
      cols.push_back(rows.dj[k] + first), vals.push_back(rows.da[k]);
    for (PetscInt k = rows.oi[i]; k < rows.oi[i + 1]; ++k) cols.push_back(rows.oj[k]), vals.push_back(rows.oa[k]);
    const PetscInt row = first + i;
    SPH_PETSC(MatSetValues(A, 1, &row, static_cast<PetscInt>(cols.size()), cols.data(), vals.data(), INSERT_VALUES));
  }
  SPH_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  SPH_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  return A;
}

// Rows are counted, then filled, in parallel: each row is the same on any thread count.
PpeRows lump_weak_entries(const PpeRows& rows, PetscInt n, double tol) {
  // Below this an off-diagonal entry of row i is lumped; 0 (nothing) for a row without its diagonal,
  // which would have nowhere to put it.
  std::vector<double> weak(static_cast<std::size_t>(n), 0.0);
  std::vector<PetscInt> diagonal(static_cast<std::size_t>(n), -1);
  PpeRows out;
  out.di.assign(static_cast<std::size_t>(n) + 1, 0), out.oi.assign(static_cast<std::size_t>(n) + 1, 0);
#pragma omp parallel for schedule(static)
  for (PetscInt i = 0; i < n; ++i) {
    for (PetscInt k = rows.di[i]; k < rows.di[i + 1]; ++k)
      if (rows.dj[k] == i) diagonal[i] = k, weak[i] = tol * std::abs(rows.da[k]);
    PetscInt kept_d = 0, kept_o = 0;
    for (PetscInt k = rows.di[i]; k < rows.di[i + 1]; ++k)
      kept_d += k == diagonal[i] || std::abs(rows.da[k]) >= weak[i];
    for (PetscInt k = rows.oi[i]; k < rows.oi[i + 1]; ++k) kept_o += std::abs(rows.oa[k]) >= weak[i];
    out.di[i + 1] = kept_d, out.oi[i + 1] = kept_o;
  }
  for (PetscInt i = 0; i < n; ++i) out.di[i + 1] += out.di[i], out.oi[i + 1] += out.oi[i];
  // One spare entry, as in PpeRows::build: PETSc is handed valid pointers even when a block is empty.
  out.dj.resize(static_cast<std::size_t>(out.di[n]) + 1), out.da.resize(out.dj.size());
  out.oj.resize(static_cast<std::size_t>(out.oi[n]) + 1), out.oa.resize(out.oj.size());
#pragma omp parallel for schedule(static)
  for (PetscInt i = 0; i < n; ++i) {
    double lumped = 0.0;
    PetscInt d = out.di[i], o = out.oi[i], out_diagonal = -1;
    for (PetscInt k = rows.di[i]; k < rows.di[i + 1]; ++k) {
      if (k == diagonal[i]) out_diagonal = d;
      else if (std::abs(rows.da[k]) < weak[i]) {
        lumped += rows.da[k];
        continue;
      }
      out.dj[d] = rows.dj[k], out.da[d++] = rows.da[k];
    }
    for (PetscInt k = rows.oi[i]; k < rows.oi[i + 1]; ++k) {
      if (std::abs(rows.oa[k]) < weak[i]) lumped += rows.oa[k];
      else out.oj[o] = rows.oj[k], out.oa[o++] = rows.oa[k];
    }
    if (out_diagonal >= 0) out.da[out_diagonal] += lumped;
  }
  return out;
}

}  // namespace sph
