#pragma once
// Small dense algebra shared by the whole code: D is the spatial dimension (1, 2 or 3).
// (Not named Vec/Mat: those are PETSc types in the global namespace.)
#include <petscsys.h>

#include <Eigen/Dense>

namespace sph {

template <int D> using Vector = Eigen::Matrix<double, D, 1>;
template <int D> using Tensor = Eigen::Matrix<double, D, D>;

// Global particle index: the row of the particle in every distributed PETSc object.
using GlobalIndex = PetscInt;

}  // namespace sph
