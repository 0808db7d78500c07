#include "src/core/error.hpp"

#include <cstring>

namespace sph {

namespace {
// Keeps the first (most specific) message of an error traceback; PETSc calls the handler once per
// frame on the way up, the first call carries the text written at the point of failure.
std::string g_first_message;

PetscErrorCode remember_error(MPI_Comm, int, const char*, const char*, PetscErrorCode n,
                              PetscErrorType p, const char* mess, void*) {
  if (p == PETSC_ERROR_INITIAL) {
    const char* text = nullptr;
    PetscErrorMessage(n, &text, nullptr);
    g_first_message = (mess && *mess) ? mess : (text ? text : "unknown PETSc error");
  }
  return n;
}
}  // namespace

void install_error_handler() { PetscPushErrorHandler(remember_error, nullptr); }

void check_petsc(PetscErrorCode ierr, const char* expr) {
  if (!ierr) return;
  std::string msg = g_first_message.empty() ? std::string("PETSc error in ") + expr : g_first_message;
  g_first_message.clear();
  // PETSc messages may span lines; the user gets one.
  for (char& c : msg)
    if (c == '\n') c = ' ';
  while (!msg.empty() && msg.back() == ' ') msg.pop_back();
  throw Error(msg);
}

}  // namespace sph
