#pragma once
// The reads of an options block. Each function reads one option inside a PetscOptionsBegin/End block
// (`block` is the block's PetscOptionsObject), as PETSc's PetscOptionsReal, ... do, printing its -help
// line, and refuses what PETSc would take silently: an option given without the value it needs (PETSc
// drops it and keeps the default) and, for reals, inf or nan (PETSc parses them). While an OptionNames
// is open, each records the name it read: the unknown-option check's hints (src/core/options.hpp).
#include <petscsys.h>

#include <string>
#include <utility>
#include <vector>

namespace sph {

// How much a run needs an option. -help lists the essential ones first, in a section of their own
// (app/sph.cpp); an expert one, a setting of the numerical method whose default the verification pages
// justify and few runs change, starts its -help line with "(expert)"; the rest are standard.
enum class OptionLevel { standard, expert };

PetscErrorCode option_real(PetscOptionItems* block, const char* name, const char* help, PetscReal current,
                           PetscReal* value, PetscBool* set, OptionLevel level = OptionLevel::standard);
PetscErrorCode option_int(PetscOptionItems* block, const char* name, const char* help, PetscInt current,
                          PetscInt* value, PetscBool* set, OptionLevel level = OptionLevel::standard);
// A flag: given alone it is true.
PetscErrorCode option_bool(PetscOptionItems* block, const char* name, const char* help, PetscBool current,
                           PetscBool* value, PetscBool* set, OptionLevel level = OptionLevel::standard);
// One of `choices` (n of them); *value is the index of the one given.
PetscErrorCode option_choice(PetscOptionItems* block, const char* name, const char* help, const char* const* choices,
                             PetscInt n, const char* current, PetscInt* value, PetscBool* set,
                             OptionLevel level = OptionLevel::standard);
PetscErrorCode option_string(PetscOptionItems* block, const char* name, const char* help, const char* current,
                             char* value, size_t length, PetscBool* set, OptionLevel level = OptionLevel::standard);
// Up to *n comma-separated reals; *n becomes the number given.
PetscErrorCode option_reals(PetscOptionItems* block, const char* name, const char* help, PetscReal* values, PetscInt* n,
                            PetscBool* set, OptionLevel level = OptionLevel::standard);

// Records the names (without the dash) of the options read while it is open, by the functions above
// and by record_option_names. One at a time; options are read by one thread.
class OptionNames {
 public:
  OptionNames();
  ~OptionNames();
  OptionNames(const OptionNames&) = delete;
  OptionNames& operator=(const OptionNames&) = delete;
  const std::vector<std::string>& names() const { return names_; }
  void record(std::string name) { names_.push_back(std::move(name)); }

 private:
  std::vector<std::string> names_;
  OptionNames* outer_;
};

// For options another object reads (a PETSc solver's): records their names in the open OptionNames.
void record_option_names(const std::string& prefix, const std::vector<const char*>& names);

// Throws OptionError naming any of `names` (with the dash) given under `prefix` without a value: for the
// options PETSc's own objects read, which PETSc drops when their value is missing.
void refuse_valueless(const char* prefix, const std::vector<const char*>& names);

}  // namespace sph
