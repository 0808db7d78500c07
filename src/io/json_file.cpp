#include "src/io/json_file.hpp"

#include <petscsys.h>

#include <cstdio>
#include <fstream>

#include "src/core/error.hpp"
#include "src/io/output_dir.hpp"

namespace sph {

void write_json_file(const std::string& path, const nlohmann::json& j) {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  // replace: invalid UTF-8 in a string becomes U+FFFD rather than a nlohmann::json::type_error.
  const std::string text = j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  note_output(path);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error("cannot write " + path + "; check that -output_dir is writable");
    out << text;
    out.flush();
    if (!out) {
      out.close();
      std::remove(tmp.c_str());
      throw Error("failed writing " + path + " (disk full?)");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error("cannot replace " + path + " (rename from " + tmp + " failed)");
  }
}

}  // namespace sph
