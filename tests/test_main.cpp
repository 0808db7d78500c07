// GoogleTest entry point: PETSc (and MPI) live for the whole test binary.
#include <gtest/gtest.h>
#include <petscsys.h>

#include "src/core/error.hpp"
#include "src/neighbours/ghost_check.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) return 1;
  sph::install_error_handler();
  sph::ghost_checks() = true;  // every pair loop of every test reads fresh ghosts
  const int result = RUN_ALL_TESTS();
  PetscFinalize();
  return result;
}
