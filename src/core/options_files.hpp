// The command line's checks before PETSc starts: PETSc reads -options_file during its initialisation,
// before a quiet error handler can be installed, so a wrong path or a malformed line would otherwise
// end in a PETSc traceback instead of one line naming the cause.
#pragma once

#include <string>
#include <vector>

namespace sph {

// A line of an options file as PETSc splits it: words, a double-quoted one counting as one.
std::vector<std::string> options_file_words(const std::string& line);

// The one-line message for what PETSc would refuse in the options file `path` (given as option `opt`)
// or a file it includes; "" when all is well. `chain` holds the files that include this one.
std::string options_file_problem(const std::string& path, const std::string& opt, std::vector<std::string>& chain);

// Checks every -options_file and -options_file_yaml of the command line; prints the problem as
// "sph: error: ..." on stderr and returns false at the first one.
bool options_files_valid(int argc, char** argv);

// Whether this invocation only prints (-help, -version) and runs nothing.
bool only_prints(int argc, char** argv);

}  // namespace sph
