#include "src/core/options.hpp"

#include <petscsys.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

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

// Names to suggest that no options block prints at start-up: PETSc's initialisation options, and those
// a solve reads.
const std::vector<std::string>& unprinted_options() {
  static const std::vector<std::string> names = {
      "options_file", "options_file_yaml", "options_string_yaml",     "help",
      "version",      "start_in_debugger", "stop_for_debugger",       "mat_type",
      "mat_view",     "ppe_pc_view",       "ppe_ksp_converged_reason"};
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

struct Unused {
  std::vector<std::string> names;
};

Unused unused_options() {
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  SPH_PETSC(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  Unused u;
  for (PetscInt k = 0; k < n; ++k) u.names.emplace_back(names[k]);
  SPH_PETSC(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  return u;
}

}  // namespace

namespace {
std::string g_help_text;

PetscErrorCode capture_help(MPI_Comm, const char format[], ...) {
  char buf[4096];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  g_help_text += buf;
  return 0;
}
}  // namespace

std::string options_help(const std::function<void()>& read_all) {
  g_help_text.clear();
  const auto saved = PetscHelpPrintf;
  PetscHelpPrintf = capture_help;
  // PETSc prints each options block once per run; a fresh record makes the blocks already read
  // by this run print again.
  PetscOptionsHelpPrinted printed = PetscOptionsHelpPrintedSingleton;
  // Lists of types (-ksp_type ...) go straight to standard output rather than through
  // PetscHelpPrintf: capture the file descriptor too.
  std::FILE* type_lists = std::tmpfile();
  std::fflush(stdout);
  const int stdout_saved = type_lists ? dup(STDOUT_FILENO) : -1;
  if (stdout_saved >= 0) dup2(fileno(type_lists), STDOUT_FILENO);
  SPH_PETSC(PetscOptionsHelpPrintedCreate(&PetscOptionsHelpPrintedSingleton));
  SPH_PETSC(PetscOptionsSetValue(nullptr, "-help", nullptr));
  try {
    read_all();
  } catch (const Error&) {
    // Reading the blocks is all that matters here; value checks may fail for other components.
  }
  SPH_PETSC(PetscOptionsClearValue(nullptr, "-help"));
  SPH_PETSC(PetscOptionsHelpPrintedDestroy(&PetscOptionsHelpPrintedSingleton));
  PetscOptionsHelpPrintedSingleton = printed;
  PetscHelpPrintf = saved;
  std::fflush(stdout);
  if (stdout_saved >= 0) {
    dup2(stdout_saved, STDOUT_FILENO);
    close(stdout_saved);
  }
  if (type_lists) {
    std::rewind(type_lists);
    char line[4096];
    while (std::fgets(line, sizeof line, type_lists)) g_help_text += line;
    std::fclose(type_lists);
  }
  return g_help_text;
}

std::vector<std::string> documented_options(const std::function<void()>& read_all) {
  const std::string text = options_help(read_all);
  std::vector<std::string> names;
  const std::regex option("\\n  -([A-Za-z0-9_]+)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it)
    names.push_back((*it)[1].str());
  return names;
}

namespace {

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

std::string suggestion(const std::string& name, const std::vector<OptionOwner>& owners) {
  std::vector<std::string> candidates = petsc_late_options();
  candidates.insert(candidates.end(), unprinted_options().begin(), unprinted_options().end());
  for (const OptionOwner& o : owners) {
    const std::vector<std::string> names = documented_options(o.read);
    candidates.insert(candidates.end(), names.begin(), names.end());
  }
  const std::string best = closest(name, candidates);
  return (best.empty() ? std::string(".") : "; did you mean -" + best + "?") + " Run with -help to list the options";
}

std::string join_labels(const std::vector<const OptionOwner*>& owners, const char* separator) {
  std::string s;
  for (const OptionOwner* o : owners)
    if (!o->label.empty()) s += (s.empty() ? "" : separator) + o->label;
  return s;
}

// The owners not chosen for this run that read `name`, at start-up or later.
std::vector<const OptionOwner*> inactive_readers(const std::string& name, const std::vector<OptionOwner>& owners) {
  std::vector<const OptionOwner*> readers;
  for (const OptionOwner& o : owners) {
    if (o.active) continue;
    if ((o.reads_late && o.reads_late(name)) || in(documented_options(o.read), name)) readers.push_back(&o);
  }
  return readers;
}

bool read_late_by_active(const std::string& name, const std::vector<OptionOwner>& owners) {
  for (const OptionOwner& o : owners)
    if (o.active && o.reads_late && o.reads_late(name)) return true;
  return false;
}

// An old name's name now (see OptionOwner::renamed), from any owner, chosen or not; `known` when
// that owner reads the new name (a typo of an old name has a new name nobody reads).
struct Rename {
  RenamedOption to;
  bool known = false;
};

Rename renamed(const std::string& name, const std::vector<OptionOwner>& owners) {
  for (const OptionOwner& o : owners) {
    if (!o.renamed) continue;
    const RenamedOption to = o.renamed(name);
    if (to.now.empty()) continue;
    return {to, (o.reads_late && o.reads_late(to.now)) || in(documented_options(o.read), to.now)};
  }
  return {};
}

}  // namespace

namespace {

// What an option's -help line says of its value. PETSc prints a flag as "-name: <TRUE : TRUE>", a
// real as "-name <0.1 : 0.1>" and an integer, a string or a choice as "-name <now 64 : formerly 64>".
enum class ValueKind { undocumented, flag, real, other };

ValueKind value_kind(const std::string& help, const std::string& name, std::string* shown) {
  std::smatch m;
  if (!std::regex_search(help, m, std::regex("\\n  -" + name + "(:?) <(now )?([^>:]*)")))
    return ValueKind::undocumented;
  *shown = m[3].str();
  while (!shown->empty() && shown->back() == ' ') shown->pop_back();
  if (m[1].length() > 0) return ValueKind::flag;
  return m[2].length() > 0 ? ValueKind::other : ValueKind::real;
}

// Whether a value (a number or a comma-separated list) holds inf or nan, which PETSc parses as reals.
bool holds_non_finite(const std::string& value) {
  std::istringstream items(value);
  std::string item;
  while (std::getline(items, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (end != item.c_str() && *end == '\0' && !std::isfinite(x)) return true;
  }
  return false;
}

}  // namespace

namespace {

// The options not yet read, with their values as given (none: given without one); before any block
// reads them, every option the user gave.
std::vector<std::pair<std::string, std::optional<std::string>>> given_options() {
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  SPH_PETSC(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::vector<std::pair<std::string, std::optional<std::string>>> given;
  for (PetscInt k = 0; k < n; ++k)
    given.emplace_back(names[k], values[k] ? std::optional<std::string>(values[k]) : std::nullopt);
  SPH_PETSC(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  return given;
}

// Calls f(name, kind, shown default) for each of `names` that an active owner's -help documents. The
// owners' blocks are read again to print their help: the cheapest first (run control, then solvers,
// then cases, which may read a scene file), and only until every name is found.
template <class F> void classify(std::vector<std::string> names, const std::vector<OptionOwner>& owners, F&& f) {
  for (auto o = owners.rbegin(); o != owners.rend() && !names.empty(); ++o) {
    if (!o->active) continue;
    const std::string help = options_help(o->read);
    for (auto it = names.begin(); it != names.end();) {
      std::string shown;
      const ValueKind kind = value_kind(help, *it, &shown);
      if (kind == ValueKind::undocumented) {
        ++it;
        continue;
      }
      f(*it, kind, shown);
      it = names.erase(it);
    }
  }
}

}  // namespace

std::vector<std::string> check_finite_option_values(const std::vector<OptionOwner>& owners) {
  std::vector<std::string> valueless, non_finite;
  std::map<std::string, std::string> value_of;
  for (const auto& [name, value] : given_options()) {
    if (!value) valueless.push_back(name);
    else if (holds_non_finite(*value)) non_finite.push_back(name), value_of[name] = *value;
  }
  classify(non_finite, owners, [&](const std::string& name, ValueKind kind, const std::string&) {
    if (kind == ValueKind::real)
      throw OptionError("option -" + name + " has the value '" + value_of[name] + "', which is not a finite number");
  });
  return valueless;
}

void check_valueless_options(const std::vector<std::string>& valueless, const std::vector<OptionOwner>& owners) {
  classify(valueless, owners, [](const std::string& name, ValueKind kind, const std::string& shown) {
    if (kind == ValueKind::real || kind == ValueKind::other)
      throw OptionError("option -" + name + " was given without a value" +
                        (shown.empty() ? std::string() : " (its default is " + shown + ")") +
                        "; give it a value or leave it out");
  });
}

void check_unused_options(const std::vector<OptionOwner>& owners) {
  for (const std::string& name : unused_options().names) {
    if (in(petsc_late_options(), name)) continue;
    // Before the options read late: an old name may have been one (-mat_mumps_icntl_4).
    const Rename rename = renamed(name, owners);
    if (rename.known) throw OptionError("option -" + name + " is now -" + rename.to.now + ": " + rename.to.why);
    if (read_late_by_active(name, owners)) continue;
    std::vector<const OptionOwner*> chosen;
    for (const OptionOwner& o : owners)
      if (o.active) chosen.push_back(&o);
    const std::vector<const OptionOwner*> readers = inactive_readers(name, owners);
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
  for (const std::string& name : unused_options().names) {
    if (in(petsc_late_options(), name) || !read_late_by_active(name, owners)) continue;
    throw OptionError("option -" + name + " was not used by the first step: nothing in this configuration reads it" +
                      suggestion(name, owners));
  }
}

void finish_options_check() {
  for (const std::string& name : unused_options().names) {
    if (in(petsc_late_options(), name)) continue;
    PetscFPrintf(PETSC_COMM_WORLD, stderr, "sph: warning: option -%s was never used\n", name.c_str());
  }
}

}  // namespace sph
