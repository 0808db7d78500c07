#include "src/run/run_identity.hpp"

#include <petscsys.h>

#include <cctype>
#include <cstdlib>
#include <set>
#include <sstream>

#include "src/core/error.hpp"
#include "src/sph/operator_options.hpp"

namespace sph {

namespace {

// Options that steer a run without changing what it computes: a restart may change them (e.g. a
// later -t_end to continue a run).
bool steers_only(const std::string& name) {
  static const std::set<std::string> exact = {"t_end",
                                              "max_steps",
                                              "output_dir",
                                              "output_interval",
                                              "checkpoint_interval",
                                              "checkpoints_kept",
                                              "progress",
                                              "threads",
                                              "partition_interval",
                                              "restart",
                                              "overwrite",
                                              "steady_tol",
                                              "dt_force",
                                              "case",
                                              "solver",
                                              "dim",
                                              "help",
                                              "version",
                                              "options_file",
                                              "options_file_yaml",
                                              "skip_petscrc"};
  static const char* prefixes[] = {"log",
                                   "info",
                                   "malloc",
                                   "options_",
                                   "ppe_ksp_monitor",
                                   "ppe_ksp_view",
                                   "ppe_ksp_converged_reason",
                                   "ppe_ksp_converged_rate",
                                   "mat_view",
                                   "vec_view",
                                   "ppe_pc_view",
                                   "memory_view",
                                   "objects_dump",
                                   "on_error",
                                   "fp_trap",
                                   "no_signal_handler",
                                   "use_gpu_aware_mpi",
                                   "citations",
                                   "error_output",
                                   "saws",
                                   "check_pointer_intensity",
                                   "mpi_linear_solver_server",
                                   "viewer"};
  if (exact.count(name)) return true;
  for (const char* p : prefixes)
    if (name.rfind(p, 0) == 0) return true;
  return false;
}

// Options that name an input file whose content the case's parameters identify (the scene file's
// checksum): the same file by another path is the same run, another file with the same name is not.
bool identified_by_content(const std::string& name) { return name == "scene_file"; }

// Options that change only how the steps to come are taken, not the problem: a restart may change
// them to rescue a failing run (a smaller step, another linear solver); the change is recorded.
bool changes_numerics_only(const std::string& name) {
  static const std::set<std::string> exact = {"cfl", "acoustic_cfl", "cfl_force", "dt", "ppe_pc_drop_tol", "mat_type"};
  static const char* prefixes[] = {"ppe_ksp_", "ppe_pc_", "ppe_sub_ksp_", "ppe_sub_pc_"};
  if (exact.count(name)) return true;
  for (const char* p : prefixes)
    if (name.rfind(p, 0) == 0) return true;
  return false;
}

// A checkpoint written before the pressure solve's options took the prefix ppe_ records -ksp_rtol
// where this run has -ppe_ksp_rtol, one of an explicit scheme written before its Courant number was
// named -acoustic_cfl records -cfl, and one written before the schemes' own operator choices took
// their prefix records -operators: its names are read as they are spelled now.
nlohmann::json with_current_names(const nlohmann::json& options, const std::string& solver) {
  static const char* old_prefixes[] = {"ksp_", "pc_", "sub_ksp_", "sub_pc_"};
  nlohmann::json renamed = nlohmann::json::object();
  for (const auto& [name, value] : options.items()) {
    bool old = false;
    for (const char* p : old_prefixes) old = old || name.rfind(p, 0) == 0;
    bool scheme_own = false;
    for (const char* own : scheme_operator_options) scheme_own = scheme_own || name == own;
    if (solver != "isph" && name == "cfl") renamed["acoustic_cfl"] = value;
    else if (scheme_own) renamed[solver + "_" + name] = value;
    else renamed[old ? "ppe_" + name : name] = value;
  }
  return renamed;
}

bool is_option_name(const std::string& token) {
  return token.size() > 1 && token[0] == '-' && !std::isdigit(static_cast<unsigned char>(token[1])) && token[1] != '.';
}

// An option's value in a form where 0.01 == 1e-2 and a bare flag == true == 1.
std::string normalised(const nlohmann::json& v) {
  if (v.is_null()) return "1";
  std::string s = v.get<std::string>();
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "true" || s == "yes") return "1";
  if (s == "false" || s == "no") return "0";
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (!s.empty() && end && *end == '\0') {
    std::ostringstream out;
    out.precision(17);
    out << x;
    return out.str();
  }
  return s;
}

std::string shown(const nlohmann::json& obj, const std::string& key) {
  if (!obj.contains(key)) return "-" + key + " unset (its default)";
  const nlohmann::json& v = obj[key];
  return "-" + key + " " + (v.is_null() ? std::string("(flag)") : v.is_string() ? v.get<std::string>() : v.dump());
}

[[noreturn]] void refuse(const std::string& path, const std::string& what_then, const std::string& what_now,
                         const std::string& option) {
  throw Error("checkpoint " + path + " was written with " + what_then + ", this run has " + what_now +
              "; restart with the same -" + option + " or start a new run without -restart");
}

}  // namespace

nlohmann::json options_database() {
  char* all = nullptr;
  SPH_PETSC(PetscOptionsGetAll(nullptr, &all));
  std::istringstream in(all ? all : "");
  PetscFree(all);
  nlohmann::json db = nlohmann::json::object();
  std::string token, name;
  while (in >> token) {
    if (is_option_name(token)) {
      name = token.substr(1);
      db[name] = nullptr;
    } else if (!name.empty()) {
      db[name] = db[name].is_null() ? token : db[name].get<std::string>() + " " + token;
    }
  }
  return db;
}

nlohmann::json run_identity(const std::string& case_name, const std::string& solver_name, int dim,
                            const nlohmann::json& case_parameters) {
  nlohmann::json options = nlohmann::json::object();
  const nlohmann::json db = options_database();
  for (const auto& [name, value] : db.items())
    if (!steers_only(name) && !identified_by_content(name)) options[name] = value;
  return {{"case", case_name},
          {"solver", solver_name},
          {"dim", dim},
          {"parameters", case_parameters},
          {"options", options}};
}

nlohmann::json check_same_run(const nlohmann::json& saved, const nlohmann::json& now, const std::string& path) {
  if (!saved.is_object() || !saved.contains("options"))
    throw Error("checkpoint " + path + " does not record the options it was written with; start a new run");
  for (const char* key : {"case", "solver", "dim"})
    if (saved[key] != now[key])
      refuse(
          path,
          std::string("-") + key + " " + (saved[key].is_string() ? saved[key].get<std::string>() : saved[key].dump()),
          std::string("-") + key + " " + (now[key].is_string() ? now[key].get<std::string>() : now[key].dump()), key);
  const nlohmann::json a = with_current_names(saved["options"], saved["solver"].get<std::string>());
  const nlohmann::json& b = now["options"];
  const nlohmann::json &pa = saved["parameters"], &pb = now["parameters"];
  std::set<std::string> names;
  for (const auto& [name, value] : a.items()) names.insert(name);
  for (const auto& [name, value] : b.items()) names.insert(name);
  nlohmann::json changed = nlohmann::json::object();
  for (const std::string& name : names) {
    if (a.contains(name) && b.contains(name) && normalised(a[name]) == normalised(b[name])) continue;
    if (identified_by_content(name)) continue;  // recorded by checkpoints of earlier versions
    if (changes_numerics_only(name)) {
      changed[name] = {{"was", a.contains(name) ? a[name] : "default"},
                       {"now", b.contains(name) ? b[name] : "default"}};
      continue;
    }
    // Given on one side only: the same if the case's effective value agrees (-re 100 is the default).
    if (pa.contains(name) && pb.contains(name) && pa[name] == pb[name]) continue;
    refuse(path, shown(a, name), shown(b, name), name);
  }
  // The options agree: a parameter that differs comes from the case's input (a scene file edited since),
  // and is named as such, not as an option (-scene_checksum, -bodies do not exist).
  for (const auto& [name, value] : pa.items())
    if (!identified_by_content(name) && (!pb.contains(name) || pb[name] != value))
      throw Error("checkpoint " + path + " was written with " + name + " = " + value.dump() + ", this run has " + name +
                  " = " + (pb.contains(name) ? pb[name].dump() : "unset") +
                  ": the case's input changed since (a scene file edited, or another version of sph); restart "
                  "with the input it was written from or start a new run without -restart");
  return changed;
}

}  // namespace sph
