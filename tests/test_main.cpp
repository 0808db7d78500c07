// GoogleTest entry point: PETSc (and MPI) live for the whole test binary.
#include <gtest/gtest.h>
#include <petscsys.h>

#include "src/core/error.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) return 1;
  sph::install_error_handler();
  const int result = RUN_ALL_TESTS();
  PetscFinalize();
  return result;
}
