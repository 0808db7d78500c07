#pragma once
// JSON files (summary.json) written by rank 0 of PETSC_COMM_WORLD, pretty-printed with an indent of 2,
// atomically: the text goes to "<path>.tmp", which is then renamed over `path`, so a reader (or a run
// that is killed) never sees half a file. Other ranks return at once; not collective.
//
// Note: JSON has no NaN or infinity; nlohmann::json serialises NaN/Inf doubles as null. That is
// accepted here (a diverged run's error norms then read as null). Strings that are not valid UTF-8
// are written with U+FFFD replacement characters instead of throwing.
#include <nlohmann/json.hpp>
#include <string>

namespace sph {

// Throws sph::Error naming the file if it cannot be written or renamed.
void write_json_file(const std::string& path, const nlohmann::json& j);

}  // namespace sph
