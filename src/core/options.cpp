#include "src/core/options.hpp"

#include <petscsys.h>

#include <algorithm>
#include <optional>
#include <sstream>
#include <utility>

#include "src/core/option_reads.hpp"

namespace sph {

void require(bool condition, const std::string& option, const std::string& what, double value) {
  if (condition) return;
  std::ostringstream msg;
  msg << option << " must be " << what << " (got " << value << ")";
  throw Error(msg.str());
}

namespace {

// PETSc itself reads these after start-up (at finalisation, or as it goes), or reads them during
// initialisation without marking them used. Exact names: a typo of one is still caught.
const std::vector<std::string>& petsc_late_options() {
  static const std::vector<std::string> names = {"log_view",
                                                 "log_view_memory",
                                                 "log_view_gpu_time",
                                                 "log_all",
                                                 "log_trace",
                                                 "log_exclude",
                                                 "log_sync",
                                                 "log_summary",
                                                 "log_mpe",
                                                 "log_perfstubs",
                                                 "memory_view",
                                                 "malloc_view",
                                                 "malloc_view_threshold",
                                                 "malloc_dump",
                                                 "malloc_debug",
                                                 "malloc_test",
                                                 "malloc_requested_size",
                                                 "objects_dump",
                                                 "options_left",
                                                 "options_view",
                                                 "options_monitor",
                                                 "options_monitor_cancel",
                                                 "info",
                                                 "info_exclude",
                                                 "history",
                                                 "citations",
                                                 "fp_trap",
                                                 "on_error_abort",
                                                 "on_error_attach_debugger",
                                                 "no_signal_handler",
                                                 "check_pointer_intensity",
                                                 "use_gpu_aware_mpi",
                                                 "error_output_stdout",
                                                 "error_output_none",
                                                 "saws_options"};
  return names;
}

// Names to suggest that no options block records: the choices every run makes first (read before
// any block), PETSc's initialisation options, and those a solve reads.
const std::vector<std::string>& unrecorded_options() {
  static const std::vector<std::string> names = {"case",
                                                 "solver",
                                                 "dim",
                                                 "options_file",
                                                 "options_file_yaml",
                                                 "options_string_yaml",
                                                 "help",
                                                 "version",
                                                 "start_in_debugger",
                                                 "stop_for_debugger",
                                                 "mat_type",
                                                 "mat_view",
                                                 "ppe_pc_view",
                                                 "ppe_ksp_converged_reason"};
  return names;
}

bool in(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> before(b.size() + 1), prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
      // Two neighbouring letters swapped count as one edit ("options_fiel" is one from "options_file").
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) cur[j] = std::min(cur[j], before[j - 2] + 1);
    }
    before = prev;
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// The closest candidate within two edits, also after a sub-solver prefix ("sub_pc_typ" -> "sub_pc_type"),
// which follows the solver's own ("ppe_sub_pc_typ" -> "ppe_sub_pc_type", from "ppe_pc_type").
std::string closest(const std::string& name, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = 3;  // suggest only close matches
  for (std::size_t cut = 0; cut < name.size(); cut = name.find('_', cut) + 1) {
    const std::string head = name.substr(0, cut), tail = name.substr(cut);
    if (cut > 0 && tail.size() < 5) break;
    for (const std::string& known : candidates) {
      // The candidate, and the candidate less a prefix it shares with the head.
      for (std::size_t own = 0; own <= head.size() && known.compare(0, own, head, 0, own) == 0;
           own = known.find('_', own) + 1) {
        const std::string rest = known.substr(own);
        const std::size_t d = edit_distance(tail, rest);
        if (d < best_d && head + rest != name) best_d = d, best = head + rest;
        if (known.find('_', own) == std::string::npos) break;
      }
    }
    if (!best.empty() || name.find('_', cut) == std::string::npos) break;
  }
  return best;
}

// Every option the owners' blocks read (each owner's read, its names recorded), PETSc's own that no
// block reads, and those a solve reads.
std::vector<std::string> known_options(const std::vector<OptionOwner>& owners) {
  std::vector<std::string> known = petsc_late_options();
  known.insert(known.end(), unrecorded_options().begin(), unrecorded_options().end());
  const OptionNames recorded;
  for (const OptionOwner& o : owners) {
    try {
      o.read();
    } catch (const Error&) {
      // Only the names matter here; a value check may fail for a component this run did not choose.
    }
  }
  known.insert(known.end(), recorded.names().begin(), recorded.names().end());
  return known;
}

std::string suggestion(const std::string& name, const std::vector<OptionOwner>& owners) {
  const std::string best = closest(name, known_options(owners));
  return (best.empty() ? std::string(".") : "; did you mean -" + best + "?") + " Run with -help to list the options";
}

std::string join_labels(const std::vector<const OptionOwner*>& owners, const char* separator) {
  std::string s;
  for (const OptionOwner* o : owners)
    if (!o->label.empty()) s += (s.empty() ? "" : separator) + o->label;
  return s;
}

// Whether o's options blocks (and the PETSc objects it sets up) read -name: the option is put in the
// database afresh, with `value`, o reads its options, and PETSc says whether -name was used. A
// temporary option (one the user did not give) is taken out again.
bool reads(const OptionOwner& o, const std::string& name, const std::optional<std::string>& value, bool temporary) {
  if (o.reads_late && o.reads_late(name)) return true;
  const std::string option = "-" + name;
  // A temporary name the user gave as well (both spellings) keeps its value.
  const char* given = nullptr;
  PetscBool was_given = PETSC_FALSE;
  if (temporary) SPH_PETSC(PetscOptionsFindPair(nullptr, nullptr, option.c_str(), &given, &was_given));
  const std::optional<std::string> kept = given ? std::optional<std::string>(given) : std::nullopt;
  SPH_PETSC(PetscOptionsClearValue(nullptr, option.c_str()));
  SPH_PETSC(PetscOptionsSetValue(nullptr, option.c_str(), value ? value->c_str() : nullptr));
  try {
    o.read();
  } catch (const Error&) {
    // A value check of its own failed after its blocks were read: what was read is marked used.
  }
  PetscBool used = PETSC_FALSE;
  SPH_PETSC(PetscOptionsUsed(nullptr, name.c_str(), &used));  // names without the dash
  if (temporary) {
    SPH_PETSC(PetscOptionsClearValue(nullptr, option.c_str()));
    if (was_given) SPH_PETSC(PetscOptionsSetValue(nullptr, option.c_str(), kept ? kept->c_str() : nullptr));
  }
  return used;
}

bool has_prefix(const OptionOwner& o, const std::string& name) {
  return !o.prefix.empty() && name.rfind(o.prefix, 0) == 0;
}

// The owners not chosen for this run that read `name`, at start-up or later. A name under an owner's
// prefix is asked of that owner only.
std::vector<const OptionOwner*> inactive_readers(const std::string& name, const std::optional<std::string>& value,
                                                 const std::vector<OptionOwner>& owners) {
  const bool prefixed = std::any_of(owners.begin(), owners.end(), [&](const auto& o) { return has_prefix(o, name); });
  std::vector<const OptionOwner*> readers;
  for (const OptionOwner& o : owners)
    if (!o.active && (!prefixed || has_prefix(o, name)) && reads(o, name, value, false)) readers.push_back(&o);
  return readers;
}

bool read_late_by_active(const std::string& name, const std::vector<OptionOwner>& owners) {
  for (const OptionOwner& o : owners)
    if (o.active && o.reads_late && o.reads_late(name)) return true;
  return false;
}

// An old name's name now (see OptionOwner::renamed), from any owner, the chosen ones first (an old
// name two owners renamed apart, -operators, is told this run's); `known` when that owner reads the
// new name (a typo of an old name has a new name nobody reads).
struct Rename {
  RenamedOption to;
  bool known = false;
};

Rename renamed(const std::string& name, const std::optional<std::string>& value,
               const std::vector<OptionOwner>& owners) {
  for (const bool chosen : {true, false})
    for (const OptionOwner& o : owners) {
      if (o.active != chosen || !o.renamed) continue;
      const RenamedOption to = o.renamed(name);
      if (to.now.empty()) continue;
      return {to, reads(o, to.now, value, true)};
    }
  return {};
}

// The options not yet read, with their values as given (none: given without one).
std::vector<std::pair<std::string, std::optional<std::string>>> unused_options() {
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  SPH_PETSC(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::vector<std::pair<std::string, std::optional<std::string>>> left;
  for (PetscInt k = 0; k < n; ++k)
    left.emplace_back(names[k], values[k] ? std::optional<std::string>(values[k]) : std::nullopt);
  SPH_PETSC(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  return left;
}

}  // namespace

std::string closest_choice(const std::string& given, const std::vector<std::string>& choices) {
  return closest(given, choices);
}

void check_unused_options(const std::vector<OptionOwner>& owners) {
  for (const auto& [name, value] : unused_options()) {
    if (in(petsc_late_options(), name)) continue;
    // Before the options read late: an old name may have been one (-mat_mumps_icntl_4).
    const Rename rename = renamed(name, value, owners);
    if (rename.known) throw OptionError("option -" + name + " is now -" + rename.to.now + ": " + rename.to.why);
    if (read_late_by_active(name, owners)) continue;
    std::vector<const OptionOwner*> chosen;
    for (const OptionOwner& o : owners)
      if (o.active) chosen.push_back(&o);
    const std::vector<const OptionOwner*> readers = inactive_readers(name, value, owners);
    if (!readers.empty())
      throw OptionError("option -" + name + " is read by " + join_labels(readers, ", ") + ", not by this run's " +
                        join_labels(chosen, " and ") + "; remove it or choose " +
                        (readers.size() == 1 ? readers[0]->label : "one of those"));
    // An old name's typo: the suggestion is spelled the new way.
    throw OptionError("unknown option -" + name + " (not used by the chosen case or solver)" +
                      suggestion(rename.to.now.empty() ? name : rename.to.now, owners));
  }
}

void check_late_options(const std::vector<OptionOwner>& owners) {
  for (const auto& [name, value] : unused_options()) {
    if (in(petsc_late_options(), name) || !read_late_by_active(name, owners)) continue;
    throw OptionError("option -" + name + " was not used by the first step: nothing in this configuration reads it" +
                      suggestion(name, owners));
  }
}

void finish_options_check() {
  for (const auto& left : unused_options()) {
    const std::string& name = left.first;
    if (in(petsc_late_options(), name)) continue;
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: warning: option -%s was never used\n", name.c_str());
  }
}

}  // namespace sph
