#include "src/io/json_file.hpp"

#include <petscsys.h>

#include <cstdio>
#include <fstream>

#include "src/core/error.hpp"

namespace sph {

void write_json_file(const std::string& path, const nlohmann::json& j) {
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw Error("cannot write " + path + "; check that -output_dir is writable");
    out << j.dump(2) << "\n";
    if (!out) throw Error("failed writing " + path);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw Error("cannot rename " + tmp + " to " + path);
}

}  // namespace sph
