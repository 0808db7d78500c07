#include "src/core/error.hpp"

#include <cstring>
#include <sstream>

namespace sph {

namespace {
// Keeps the first (most specific) message of an error traceback; PETSc calls the handler once per
// frame on the way up, the first call carries the text written at the point of failure.
std::string g_first_message;

PetscErrorCode remember_error(MPI_Comm, int, const char*, const char*, PetscErrorCode n, PetscErrorType p,
                              const char* mess, void*) {
  if (p == PETSC_ERROR_INITIAL) {
    const char* text = nullptr;
    PetscErrorMessage(n, &text, nullptr);
    g_first_message = (mess && *mess) ? mess : (text ? text : "unknown PETSc error");
  }
  return n;
}
}  // namespace

void install_error_handler() { PetscPushErrorHandler(remember_error, nullptr); }

// PETSc's "Input string abc has no integer value" does not say which option held it: find the
// options given that value in the database and name them.
std::string name_the_option(const std::string& msg) {
  static const std::string head = "Input string ";
  if (msg.compare(0, head.size(), head) != 0) return msg;
  const std::string value = msg.substr(head.size(), msg.find(' ', head.size()) - head.size());
  char* all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all) || !all) return msg;
  std::istringstream tokens(all);
  PetscFree(all);
  std::string previous, token, names;
  while (tokens >> token) {
    if (token == value && previous.size() > 1 && previous[0] == '-') names += (names.empty() ? "" : ", ") + previous;
    previous = token;
  }
  if (names.empty()) return msg;
  const bool integer = msg.find("integer") != std::string::npos;
  return "option " + names + " has the value '" + value + "', which is not " + (integer ? "an integer" : "a number") +
         "; give it a number (" + msg + ")";
}

void check_petsc(PetscErrorCode ierr, const char* expr) {
  if (!ierr) return;
  std::string msg = g_first_message.empty() ? std::string("PETSc error in ") + expr : name_the_option(g_first_message);
  g_first_message.clear();
  // PETSc messages may span lines; the user gets one.
  for (char& c : msg)
    if (c == '\n') c = ' ';
  while (!msg.empty() && msg.back() == ' ') msg.pop_back();
  throw Error(msg);
}

}  // namespace sph
