#pragma once
// Run-time options live in PETSc's options database: components read theirs in
// PetscOptionsBegin/End blocks (so -help documents them), -options_file loads a scene and the command
// line overrides. This file holds what the blocks themselves do not: value checks with one-line
// messages and the unknown-option check.
#include <functional>
#include <string>
#include <vector>

#include "src/core/error.hpp"

namespace sph {

// Throws sph::Error("-name must be ... (got value)") unless the condition holds.
void require(bool condition, const std::string& option, const std::string& what, double value);

// Options nobody has read so far are typos or options that do not apply to the chosen case/solver:
// this throws naming the first one, with the closest documented option if one is close. Options
// that PETSc reads only late in a run (viewers, logging) are exempt; `finish_options_check` warns
// about those that are still unused at the end of the run. `list_all_options` reads every options
// block of the program (what -help prints); it is called only to make the suggestion.
void check_unused_options(const std::function<void()>& list_all_options);
void finish_options_check();

// The option names a call of `read_all` documents: its -help text, captured instead of printed.
std::vector<std::string> documented_options(const std::function<void()>& read_all);

}  // namespace sph
