#include "src/core/option_reads.hpp"

#include <strings.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "src/core/options.hpp"

namespace sph {

namespace {

OptionNames* g_open = nullptr;

void record(const char* name) {
  if (g_open && name[0] == '-') g_open->record(name + 1);
}

// PETSc drops an option given without a value and keeps the default: the run would not be the one
// asked for. `shown` is the default the message names (may be empty).
PetscErrorCode refuse_missing_value(PetscOptionItems* block, const char* name, const std::string& shown) {
  PetscFunctionBeginUser;
  const char* value = nullptr;
  PetscBool found = PETSC_FALSE;
  PetscCall(PetscOptionsFindPair(block->options, block->prefix, name, &value, &found));
  const std::string dflt = shown.empty() ? std::string() : " (its default is " + shown + ")";
  PetscCheck(!found || value, block->comm, PETSC_ERR_USER_INPUT,
             "option %s was given without a value%s; give it a value or leave it out", name, dflt.c_str());
  PetscFunctionReturn(0);
}

// PETSc reads inf and nan as reals; no option of this program takes them.
PetscErrorCode refuse_non_finite(PetscOptionItems* block, const char* name, const PetscReal* values, PetscInt n) {
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < n; ++k) {
    if (std::isfinite(values[k])) continue;
    const char* given = nullptr;
    PetscCall(PetscOptionsFindPair(block->options, block->prefix, name, &given, nullptr));
    SETERRQ(block->comm, PETSC_ERR_USER_INPUT, "option %s has the value '%s', which is not a finite number", name,
            given ? given : "");
  }
  PetscFunctionReturn(0);
}

// The option's text as given; null when it is absent or has no value.
PetscErrorCode given_value(PetscOptionItems* block, const char* name, const char** given) {
  PetscFunctionBeginUser;
  PetscBool found = PETSC_FALSE;
  PetscCall(PetscOptionsFindPair(block->options, block->prefix, name, given, &found));
  if (!found) *given = nullptr;
  PetscFunctionReturn(0);
}

// A choice that is none of the option's, named with its choices and the nearest of them (PETSc's own
// message lists them without the nearest). PETSc matches choices ignoring case.
PetscErrorCode refuse_unknown_choice(PetscOptionItems* block, const char* name, const char* const* choices,
                                     PetscInt n) {
  PetscFunctionBeginUser;
  const char* given = nullptr;
  PetscCall(given_value(block, name, &given));
  if (!given) PetscFunctionReturn(0);
  std::vector<std::string> all;
  for (PetscInt k = 0; k < n; ++k) {
    if (strcasecmp(given, choices[k]) == 0) PetscFunctionReturn(0);
    all.emplace_back(choices[k]);
  }
  std::string list;
  for (const std::string& c : all) list += (list.empty() ? "" : ", ") + c;
  const std::string best = closest_choice(given, all);
  const std::string hint = best.empty() ? std::string() : "; did you mean " + best + "?";
  SETERRQ(block->comm, PETSC_ERR_USER_INPUT, "option %s has the value '%s', which is none of its choices (%s)%s", name,
          given, list.c_str(), hint.c_str());
}

// PETSc wraps an integer beyond its int type (2147483648 reads as a negative number): refused, named.
PetscErrorCode refuse_out_of_range(PetscOptionItems* block, const char* name) {
  PetscFunctionBeginUser;
  const char* given = nullptr;
  PetscCall(given_value(block, name, &given));
  if (!given) PetscFunctionReturn(0);
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(given, &end, 10);
  const bool integer = end != given && *end == '\0';
  PetscCheck(!integer || (errno != ERANGE && v >= PETSC_MIN_INT && v <= PETSC_MAX_INT), block->comm,
             PETSC_ERR_USER_INPUT, "option %s has the value '%s', beyond the integers it takes (%d to %d)", name, given,
             PETSC_MIN_INT, PETSC_MAX_INT);
  PetscFunctionReturn(0);
}

// PETSc reads "0,,-1" and "0,-1," as [0, -1] and names no option for "0,-1x": each component must be
// a whole number, refused naming the option otherwise.
PetscErrorCode refuse_malformed_list(PetscOptionItems* block, const char* name) {
  PetscFunctionBeginUser;
  const char* given = nullptr;
  PetscCall(given_value(block, name, &given));
  if (!given) PetscFunctionReturn(0);
  const std::string list = given;
  std::size_t start = 0;
  for (int k = 1;; ++k) {
    const std::size_t comma = list.find(',', start);
    const std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    PetscCheck(!item.empty(), block->comm, PETSC_ERR_USER_INPUT,
               "option %s has the value '%s', whose component %d is empty; give a number in each place, "
               "separated by commas",
               name, given, k);
    char* end = nullptr;
    std::strtod(item.c_str(), &end);
    PetscCheck(end != item.c_str() && *end == '\0', block->comm, PETSC_ERR_USER_INPUT,
               "option %s has the value '%s', whose component %d ('%s') is not a number; give a number in each "
               "place, separated by commas",
               name, given, k, item.c_str());
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  PetscFunctionReturn(0);
}

// The help line as -help prints it.
std::string text(const char* help, OptionLevel level) {
  return level == OptionLevel::expert ? std::string("(expert) ") + help : std::string(help);
}

template <class T> std::string shown(T value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

}  // namespace

OptionNames::OptionNames() : outer_(g_open) { g_open = this; }
OptionNames::~OptionNames() { g_open = outer_; }

void record_option_names(const std::string& prefix, const std::vector<const char*>& names) {
  if (!g_open) return;
  for (const char* name : names) g_open->record(prefix + (name[0] == '-' ? name + 1 : name));
}

void refuse_valueless(const char* prefix, const std::vector<const char*>& names) {
  for (const char* name : names) {
    const char* value = nullptr;
    PetscBool found = PETSC_FALSE;
    SPH_PETSC(PetscOptionsFindPair(nullptr, prefix, name, &value, &found));
    if (found && !value)
      throw OptionError("option -" + std::string(prefix ? prefix : "") + (name + 1) +
                        " was given without a value; give it a value or leave it out");
  }
}

PetscErrorCode option_real(PetscOptionItems* block, const char* name, const char* help, PetscReal current,
                           PetscReal* value, PetscBool* set, OptionLevel level) {
  PetscFunctionBeginUser;
  record(name);
  PetscCall(refuse_missing_value(block, name, shown(current)));
  PetscBool given = PETSC_FALSE;
  PetscCall(PetscOptionsReal_Private(block, name, text(help, level).c_str(), "", current, value, &given));
  if (given) PetscCall(refuse_non_finite(block, name, value, 1));
  if (set) *set = given;
  PetscFunctionReturn(0);
}

PetscErrorCode option_int(PetscOptionItems* block, const char* name, const char* help, PetscInt current,
                          PetscInt* value, PetscBool* set, OptionLevel level) {
  PetscFunctionBeginUser;
  record(name);
  PetscCall(refuse_missing_value(block, name, shown(current)));
  PetscCall(refuse_out_of_range(block, name));
  PetscCall(PetscOptionsInt_Private(block, name, text(help, level).c_str(), "", current, value, set, PETSC_MIN_INT,
                                    PETSC_MAX_INT));
  PetscFunctionReturn(0);
}

PetscErrorCode option_bool(PetscOptionItems* block, const char* name, const char* help, PetscBool current,
                           PetscBool* value, PetscBool* set, OptionLevel level) {
  PetscFunctionBeginUser;
  record(name);
  PetscCall(PetscOptionsBool_Private(block, name, text(help, level).c_str(), "", current, value, set));
  PetscFunctionReturn(0);
}

PetscErrorCode option_choice(PetscOptionItems* block, const char* name, const char* help, const char* const* choices,
                             PetscInt n, const char* current, PetscInt* value, PetscBool* set, OptionLevel level) {
  PetscFunctionBeginUser;
  record(name);
  PetscCall(refuse_missing_value(block, name, current ? current : ""));
  PetscCall(refuse_unknown_choice(block, name, choices, n));
  PetscCall(PetscOptionsEList_Private(block, name, text(help, level).c_str(), "", choices, n, current, value, set));
  PetscFunctionReturn(0);
}

PetscErrorCode option_string(PetscOptionItems* block, const char* name, const char* help, const char* current,
                             char* value, size_t length, PetscBool* set, OptionLevel level) {
  PetscFunctionBeginUser;
  record(name);
  PetscCall(refuse_missing_value(block, name, current ? current : ""));
  PetscCall(PetscOptionsString_Private(block, name, text(help, level).c_str(), "", current, value, length, set));
  PetscFunctionReturn(0);
}

PetscErrorCode option_reals(PetscOptionItems* block, const char* name, const char* help, PetscReal* values, PetscInt* n,
                            PetscBool* set, OptionLevel level) {
  PetscFunctionBeginUser;
  record(name);
  PetscCall(refuse_missing_value(block, name, ""));
  PetscCall(refuse_malformed_list(block, name));
  PetscBool given = PETSC_FALSE;
  PetscCall(PetscOptionsRealArray_Private(block, name, text(help, level).c_str(), "", values, n, &given));
  if (given) PetscCall(refuse_non_finite(block, name, values, *n));
  if (set) *set = given;
  PetscFunctionReturn(0);
}

}  // namespace sph
