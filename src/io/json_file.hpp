#pragma once
// JSON files written atomically (temporary file + rename) by rank 0: a reader never sees half a file.
// nlohmann::json writes NaN and Inf as null.
#include <string>

#include <nlohmann/json.hpp>

namespace sph {

void write_json_file(const std::string& path, const nlohmann::json& j);

}  // namespace sph
