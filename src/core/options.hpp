#pragma once
// Run-time options live in PETSc's options database: components read theirs in
// PetscOptionsBegin/End blocks (so -help documents them), -options_file loads a scene and the command
// line overrides. This file holds what the blocks themselves do not: value checks with one-line
// messages and the unknown-option check.
#include <string>
#include <vector>

#include "src/core/error.hpp"

namespace sph {

// Throws sph::Error("-name must be ... (got value)") unless the condition holds.
void require(bool condition, const std::string& option, const std::string& what, double value);

// Options nobody has read so far are typos or options that do not apply to the chosen case/solver:
// this throws naming the first one (with the closest known option, if any). Options that PETSc reads
// only late in a run (viewers, logging) are exempt; `finish_options_check` warns about those that are
// still unused at the end of the run.
void check_unused_options();
void finish_options_check();

// Names of options read so far (used for "did you mean" suggestions).
std::vector<std::string> used_option_names();

}  // namespace sph
