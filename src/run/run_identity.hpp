#pragma once
// What makes a run the run it is, so that a restart can be checked against the checkpoint it resumes:
// the case, the solver, the dimension, the case's effective parameters and every option in PETSc's
// database except those that only steer the run (end time, output, checkpoints, threads, logging).
// A restart may also change the options that set only the numerics of the steps to come.
#include <nlohmann/json.hpp>
#include <string>

namespace sph {

// Every option in PETSc's database (command line and options files) as {name without dash: value or null}.
nlohmann::json options_database();

// The identity recorded in a checkpoint.
nlohmann::json run_identity(const std::string& case_name, const std::string& solver_name, int dim,
                            const nlohmann::json& case_parameters);

// Throws sph::Error naming the first option that changes the problem and whose value differs between
// the checkpoint's identity (`saved`, read from `path`) and this run's (`now`). Options that change only
// the numerics of the steps to come (-cfl, -dt, -ppe_ksp_*, -ppe_pc_*) may differ: returns those changed, as
// {name: {"was": value, "now": value}} (a flag's value is null; "default" where not given).
nlohmann::json check_same_run(const nlohmann::json& saved, const nlohmann::json& now, const std::string& path);

}  // namespace sph
