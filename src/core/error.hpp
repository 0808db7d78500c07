#pragma once
// Errors that reach the user as one line: what went wrong and how to fix it.
#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace sph {

// Bad input or a failed run: main() prints what() on one line and exits non-zero.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Turns a PETSc error code into an sph::Error carrying PETSc's own one-line message.
// PETSc's error handler is set to return codes silently (see install_error_handler), so this is
// the single place where PETSc failures become user-facing messages.
void check_petsc(PetscErrorCode ierr, const char* expr);
void install_error_handler();

}  // namespace sph

#define SPH_PETSC(call) ::sph::check_petsc((call), #call)
