#include "app/simulation.hpp"

#include <filesystem>
#include <memory>

#include "cases/registry.hpp"
#include "solvers/registry.hpp"
#include "src/core/options.hpp"
#include "src/kernels/kernel_options.hpp"
#include "src/run/memory_budget.hpp"
#include "src/run/run_control.hpp"
#include "src/run/time_loop.hpp"

namespace sph {

// Every case and solver, with its options and whether this run chose it (see check_unused_options).
std::vector<OptionOwner> option_owners(const RunOptions& chosen);

namespace {

template <int D> void run_in_dim(const RunOptions& names) {
  const std::unique_ptr<Case<D>> run_case = create_case<D>(names.case_name);
  const std::unique_ptr<Solver<D>> solver = create_solver<D>(names.solver_name);
  {
    // A scene read from a file may build its particles' positions here: the memory check applies.
    const MemoryBudgetScope budget(solver->bytes_per_particle(), names.solver_name);
    run_case->set_from_options();
  }
  solver->set_from_options();
  RunControl control;
  control.t_end = run_case->default_t_end();
  read_run_control(control, run_case->steady_tolerance(), D);
  const KernelChoice kernel = read_kernel_options(solver->default_kernel(run_case->physics()));
  // A restart continues its run where the checkpoint is, unless -output_dir says otherwise.
  const std::string checkpoint_folder = std::filesystem::path(control.restart).parent_path().string();
  const std::string output_dir =
      control.output_dir[0] ? std::string(control.output_dir)
      : control.restarting()
          ? (checkpoint_folder.empty() ? std::string(".") : checkpoint_folder)
          : "out/" + run_case->output_name() + "-" + names.solver_name + "-" + std::to_string(run_case->resolution());
  check_unused_options(option_owners(names));
  run_time_loop<D>({*run_case, *solver, names.case_name, names.solver_name, control, kernel, output_dir,
                    [&names] { check_late_options(option_owners(names)); }});
  finish_options_check();
}

}  // namespace

std::vector<OptionOwner> option_owners(const RunOptions& chosen) {
  std::vector<OptionOwner> owners;
  for (const auto& entry : case_registry()) {
    OptionOwner o{"-case " + entry.name, {}, {}, entry.name == chosen.case_name};
    if (entry.make2) o.read = [&entry] { entry.make2()->set_from_options(); };
    else if (entry.make1) o.read = [&entry] { entry.make1()->set_from_options(); };
    else if (entry.make3) o.read = [&entry] { entry.make3()->set_from_options(); };
    owners.push_back(o);
  }
  for (const auto& name : solver_names()) {
    auto reads_late = [name](const std::string& option) { return create_solver<2>(name)->reads_late(option); };
    auto renamed = [name](const std::string& option) { return create_solver<2>(name)->renamed_option(option); };
    owners.push_back({"-solver " + name, [name] { create_solver<2>(name)->set_from_options(); }, reads_late,
                      name == chosen.solver_name, renamed, create_solver<2>(name)->options_prefix()});
  }
  owners.push_back({"",
                    [] {  // run control and kernel: read by every run
                      read_run_control_block();
                      read_kernel_options();
                    },
                    {},
                    true});
  return owners;
}

void print_all_options(int) {
  // Reading an options block with -help set prints it; the values are not used, so a value check
  // failing for one component (an -nx another case would refuse) must not hide the others.
  for (const OptionOwner& o : option_owners(RunOptions{})) {
    try {
      o.read();
    } catch (const Error&) {}
  }
}

void run_simulation(const RunOptions& opts, int dim) {
  switch (dim) {
    case 1: run_in_dim<1>(opts); break;
    case 2: run_in_dim<2>(opts); break;
    case 3: run_in_dim<3>(opts); break;
    default: throw Error("-dim must be 1, 2 or 3 (got " + std::to_string(dim) + ")");
  }
}

}  // namespace sph
