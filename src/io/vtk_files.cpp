#include "src/io/vtk_files.hpp"

#include <petscsys.h>
#include <vtkErrorCode.h>
#include <vtkXMLPolyDataWriter.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <regex>

#include "src/io/output_dir.hpp"

namespace sph {

namespace {
// Moves a complete temporary file over `path` (atomic on POSIX file systems): readers see the old
// file or the new one, never a part.
void replace_with(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp.c_str());
    throw Error("cannot replace " + path + " (rename from " + tmp + ": " + std::strerror(err) + ")");
  }
}
}  // namespace

std::string frame_stem(const std::string& base, int frame) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%05d", frame);
  return base + buf;
}

std::string xml_attr(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

Error write_failure(const std::string& path, int err) {
  const std::string why = err ? std::strerror(err) : "unknown reason";
  return Error("cannot write " + path + " (" + why + "); " +
               (err == ENOSPC || err == EDQUOT
                    ? "free space on the disk of -output_dir, or write fewer frames (-output_interval)"
                    : "check that -output_dir is writable"));
}

void write_atomically(const std::string& path, const std::string& text) {
  note_output(path);
  const std::string tmp = path + ".tmp";
  {
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw write_failure(path, errno);
    out << text;
    out.flush();
    if (!out) {
      const int err = errno;
      std::remove(tmp.c_str());
      throw write_failure(path, err);
    }
  }
  replace_with(tmp, path);
}

void write_frame(vtkXMLPolyDataWriter* writer, const std::string& path) {
  note_output(path);
  const std::string tmp = path + ".tmp";
  writer->SetFileName(tmp.c_str());
  const vtkTypeBool warnings = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();
  errno = 0;
  const bool written = writer->Write() == 1 && writer->GetErrorCode() == vtkErrorCode::NoError;
  const int err = errno;
  const unsigned long code = writer->GetErrorCode();
  vtkObject::SetGlobalWarningDisplay(warnings);
  if (!written) {
    std::remove(tmp.c_str());
    throw write_failure(path, code == vtkErrorCode::OutOfDiskSpaceError ? ENOSPC : err);
  }
  replace_with(tmp, path);
}

void FrameSeries::add(double time, const std::string& file) {
  frames_.emplace_back(time, file);
  write_pvd();
}

void FrameSeries::resume(double t) {
  frames_.clear();
  std::ifstream in(pvd_path());
  const std::regex entry("<DataSet[^>]*timestep=\"([^\"]+)\"[^>]*file=\"([^\"]+)\"");
  std::string line;
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, entry) && std::stod(m[1].str()) <= t * (1 + 1e-12))
      frames_.emplace_back(std::stod(m[1].str()), m[2].str());
}

void FrameSeries::write_pvd() const {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) return;
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& f : frames_) {
    char ts[40];
    std::snprintf(ts, sizeof ts, "%.17g", f.first);
    text += std::string("    <DataSet timestep=\"") + ts + "\" group=\"\" part=\"0\" file=\"" + xml_attr(f.second) +
            "\"/>\n";
  }
  text += "  </Collection>\n</VTKFile>\n";
  write_atomically(pvd_path(), text);
}

}  // namespace sph
