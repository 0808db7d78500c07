#include "src/core/options_files.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>

namespace sph {

// A line of an options file as PETSc splits it: words, a double-quoted one counting as one.
std::vector<std::string> options_file_words(const std::string& line) {
  std::vector<std::string> out;
  for (std::size_t k = line.find_first_not_of(" \t\r\n"); k != std::string::npos;
       k = line.find_first_not_of(" \t\r\n", k)) {
    const bool quoted = line[k] == '"';
    const std::size_t end = quoted ? line.find('"', k + 1) : line.find_first_of(" \t\r\n", k);
    out.push_back(line.substr(k + quoted, end == std::string::npos ? std::string::npos : end - k - quoted));
    k = end == std::string::npos ? end : end + quoted;
  }
  return out;
}

// What PETSc would refuse in an options file with a traceback (or, for a file that includes itself,
// with a crash): checked here, with the files it includes, so the user gets one line naming the cause.
// `chain` holds the files that include this one. Returns the one-line message, or "" when all is well.
std::string options_file_problem(const std::string& path, const std::string& opt, std::vector<std::string>& chain) {
  struct stat st {};
  if (stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    return "options file '" + path + "' (" + opt + ") is a folder; give the path of a file";
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (!f) return "cannot read options file '" + path + "' (" + opt + "); check the path";
  char* real = realpath(path.c_str(), nullptr);
  const std::string id = real ? real : path;
  std::free(real);
  for (const std::string& outer : chain)
    if (outer == id) {
      std::fclose(f);
      return "options file '" + path + "' includes itself (through -options_file); remove the loop";
    }
  chain.push_back(id);
  std::string problem;
  char buf[4096];
  for (int line = 1; problem.empty() && std::fgets(buf, sizeof buf, f); ++line) {
    std::string text(buf);
    const std::vector<std::string> w = options_file_words(text.substr(0, text.find('#')));  // '#' starts a comment
    const std::string where = "options file '" + path + "' line " + std::to_string(line) + ": ";
    if (w.empty() || w[0] == "alias") continue;
    if (w[0][0] != '-')
      problem = where + "'" + w[0] + "' is not an option; each line holds -name [value], and '#' starts a comment";
    else if (w.size() > 2)
      problem = where + "'" + w[2] + "' follows the value of " + w[0] + "; put each option on a line of its own";
    else if (w.size() == 2 && (w[0] == "-options_file" || w[0] == "-options_file_yaml"))
      problem = w[0] == "-options_file" ? options_file_problem(w[1], w[0], chain) : "";
  }
  std::fclose(f);
  chain.pop_back();
  return problem;
}

// PETSc reads -options_file during initialisation, before a quiet error handler can be installed:
// check the files first so a wrong path or a malformed line gets one line instead of a PETSc traceback.
bool options_files_valid(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string opt = argv[k];
    if (opt != "-options_file" && opt != "-options_file_yaml") continue;
    // Without a file name PETSc prints a 20-line traceback; the next word is a name as PETSc reads it
    // unless it is an option (a '-' not starting a number).
    const char* next = k + 1 < argc ? argv[k + 1] : nullptr;
    if (!next || (next[0] == '-' && !std::isdigit(static_cast<unsigned char>(next[1])) && next[1] != '.')) {
      std::fprintf(stderr,
                   "sph: error: option %s was given without a file name; give the path of an options file "
                   "(e.g. %s cases/taylor_green.opts) or leave it out\n",
                   opt.c_str(), opt.c_str());
      return false;
    }
    std::vector<std::string> chain;
    std::string problem;
    if (opt == "-options_file") problem = options_file_problem(argv[k + 1], opt, chain);
    else if (access(argv[k + 1], R_OK) != 0)  // a YAML file's contents are PETSc's to parse
      problem = "cannot read options file '" + std::string(argv[k + 1]) + "' (" + opt + "); check the path";
    if (!problem.empty()) {
      std::fprintf(stderr, "sph: error: %s\n", problem.c_str());
      return false;
    }
  }
  return true;
}

// Whether this invocation only prints (-help, -version) and runs nothing.
bool only_prints(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "-help" || a == "-h" || a == "--help" || a == "-version") return true;
  }
  return false;
}

}  // namespace sph
