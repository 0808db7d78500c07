#pragma once
// Run-time options live in PETSc's options database: components read theirs in
// PetscOptionsBegin/End blocks (so -help documents them), -options_file loads a scene and the command
// line overrides. The blocks read through src/core/option_reads.hpp, which refuses a missing or
// non-finite value; this file holds the other value checks with one-line messages and the
// unknown-option check, which asks PETSc (PetscOptionsLeft) what no one read.
#include <functional>
#include <string>
#include <vector>

#include "src/core/error.hpp"

namespace sph {

// Throws sph::Error("-name must be ... (got value)") unless the condition holds.
void require(bool condition, const std::string& option, const std::string& what, double value);

// An option nobody reads: the run stops before it starts (or after its first step, for options read
// only then), since carrying on would silently ignore what the user asked for.
class OptionError : public Error {
 public:
  using Error::Error;
};

// An option's name now, where it once had another, and why it changed (now empty: never renamed).
struct RenamedOption {
  std::string now;
  std::string why;
};

// A component a run may read options for: a case or a solver as the user picks it ("-solver isph").
struct OptionOwner {
  std::string label;
  std::function<void()> read;  // reads its options blocks and sets up the PETSc objects that read theirs
  std::function<bool(const std::string&)> reads_late;  // options PETSc reads for it only during steps (may be empty)
  bool active = false;                                 // chosen for this run
  // The name now of an option it read under an old name, named without the dash (may be empty).
  std::function<RenamedOption(const std::string&)> renamed = {};
  // The prefix its own options carry (without the dash; empty: none): an unused option under it is
  // looked up in this owner alone.
  std::string prefix = {};
};

// At start-up, every option in the database must have been read by now, except the ones an active
// owner or PETSc itself reads later (a solve's viewers, -log_view). Throws OptionError naming the
// first other one: with its name now when it is the old name of one an owner reads (-ksp_rtol is
// -ppe_ksp_rtol), with the owner that reads it when it belongs to a case or solver not chosen, else
// with the closest option there is.
void check_unused_options(const std::vector<OptionOwner>& owners);
// The choice within two edits of `given` (a value of a choice option), or "" when none is.
std::string closest_choice(const std::string& given, const std::vector<std::string>& choices);
// After the first step: the options the active owners read late must have been read by then.
void check_late_options(const std::vector<OptionOwner>& owners);
// End of run: warns about options still unused (those only PETSc's finalisation reads are exempt).
void finish_options_check();

}  // namespace sph
