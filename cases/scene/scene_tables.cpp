// Tables a scene names by file (a body's motion, an inlet's speed): CSV, a header line, then rows of
// numbers, time first. Read in one place so that every table is checked the same way, row by row.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

#include "cases/scene/scene_reader.hpp"
#include "src/core/error.hpp"

namespace sph::scene_detail {

namespace {
// A CSV line's cells, each trimmed of blanks.
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream row(line);
  for (std::string cell; std::getline(row, cell, ',');) {
    const auto a = cell.find_first_not_of(" \t\r"), b = cell.find_last_not_of(" \t\r");
    out.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
  }
  return out;
}
}  // namespace

CsvTable Reader::csv_table(const YAML::Node& file_key, const std::string& key, const std::string& what,
                           const std::function<void(const CsvTable&)>& check_header) {
  std::filesystem::path file(file_key.Scalar());
  if (file.is_relative()) file = dir_ / file;
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    fail(file_key, key,
         "'" + file.string() + "' is a folder, not a file; give " + what + " (paths are relative to the scene file)");
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file_key, key, "cannot be opened ('" + file.string() + "'; paths are relative to the scene file)");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  checksum = fnv1a(checksum, text.data(), text.size());  // the table is part of the scene
  std::istringstream lines(text);
  CsvTable table;
  table.where = key + " '" + file.string() + "'";
  std::getline(lines, table.header_line);
  table.header = cells(table.header_line);
  check_header(table);
  std::string line;
  for (int row = 2; std::getline(lines, line); ++row) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> v = cells(line);
    if (v.size() != table.header.size())
      fail(file_key, table.where,
           "row " + std::to_string(row) + " has " + std::to_string(v.size()) + " values; give " +
               std::to_string(table.header.size()));
    std::vector<double> x;
    for (const std::string& cell : v) {
      char* end = nullptr;
      const double value = std::strtod(cell.c_str(), &end);
      if (cell.empty() || *end != '\0' || !std::isfinite(value))
        fail(file_key, table.where, "row " + std::to_string(row) + ": '" + cell + "' is not a finite number");
      x.push_back(value);
    }
    if (!table.rows.empty() && !(x[0] > table.rows.back()[0]))
      fail(file_key, table.where, "row " + std::to_string(row) + ": t = " + number_text(x[0]) + " does not increase");
    table.rows.push_back(std::move(x));
  }
  if (table.rows.size() < 2) fail(file_key, table.where, "holds fewer than two rows; give two times at least");
  return table;
}

void Reader::inlet_speed_table(const YAML::Node& file_key, const std::string& key, OpenBoundarySpec& b) {
  if (!file_key.IsScalar()) fail(file_key, key, "is not a file name; give speed_table: inflow.csv (t,factor)");
  const CsvTable table =
      csv_table(file_key, key, "the speed table, a CSV with the header t,factor", [&](const CsvTable& t) {
        if (t.header != std::vector<std::string>{"t", "factor"})
          fail(file_key, t.where, "has the header '" + t.header_line + "'; give t,factor in the first line");
      });
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    const double factor = table.rows[k][1];
    // A negative factor would turn the inlet's velocity out of the box: fluid cannot leave through an inlet.
    if (factor < 0)
      fail(file_key, table.where,
           "row " + std::to_string(k + 2) + ": factor " + number_text(factor) +
               " is negative; an inlet's speed is the velocity given times a factor of 0 or more");
    b.speed_t.push_back(table.rows[k][0]);
    b.speed_factor.push_back(factor);
  }
}

}  // namespace sph::scene_detail
