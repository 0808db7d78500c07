#include "cases/scene/scene_file.hpp"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "src/core/error.hpp"

namespace sph {

namespace {

std::uint64_t fnv1a_file(std::ifstream& in) {
  std::uint64_t h = kFnv1aBasis;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    h = fnv1a(h, buf, static_cast<std::size_t>(in.gcount()));
    if (!in) break;
  }
  return h;
}

std::string point(const std::array<double, 3>& x, int dim) {
  std::ostringstream s;
  s << "(" << x[0] << ", " << x[1];
  if (dim == 3) s << ", " << x[2];
  s << ")";
  return s.str();
}

// VTK reports a malformed file through its own warning window (several lines on stderr); the file is
// judged here instead, by what the reader returned.
struct QuietVtk {
  int saved = vtkObject::GetGlobalWarningDisplay();
  QuietVtk() { vtkObject::GlobalWarningDisplayOff(); }
  ~QuietVtk() { vtkObject::SetGlobalWarningDisplay(saved); }
};

}  // namespace

std::string SceneFile::error(const std::string& what) const { return "scene file '" + path + "': " + what; }

namespace {

// The point arrays a scene reads must be numeric, and one spelled like them in another case is a
// slip that would leave, say, a lid at rest: refused, naming it. Other arrays (a frame's density,
// mass, id used as a scene) are not read.
void check_array_names(const SceneFile& s, vtkPointData* pd) {
  for (int k = 0; k < pd->GetNumberOfArrays(); ++k) {
    vtkAbstractArray* a = pd->GetAbstractArray(k);
    if (!a || !a->GetName()) continue;
    const std::string name = a->GetName();
    std::string lower = name;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* known : {"kind", "velocity", "pressure", "free_slip"}) {
      if (lower != known) continue;
      if (name != known)
        throw Error(s.error("has a point array '" + name + "', which is not read: the array is '" + known +
                            "' (lower case); rename it"));
      if (!vtkDataArray::SafeDownCast(a))
        throw Error(s.error("point array '" + name + "' is not numeric (" + a->GetClassName() + "); write numbers"));
    }
  }
}

}  // namespace

SceneFile read_scene_file(const std::string& path) {
  SceneFile s;
  s.path = path;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(s.error("cannot be opened; check the path given to -scene_file"));
  s.checksum = fnv1a_file(in);

  vtkNew<vtkXMLPolyDataReader> reader;
  {
    const QuietVtk quiet;
    if (!reader->CanReadFile(path.c_str()))
      throw Error(s.error("is not a VTK XML PolyData (.vtp) file; write scenes with scripts/make-scene or VTK"));
    reader->SetFileName(path.c_str());
    reader->Update();
  }
  vtkPolyData* poly = reader->GetOutput();
  const vtkIdType n = poly ? poly->GetNumberOfPoints() : 0;
  if (reader->GetErrorCode() != 0 || n == 0)
    throw Error(s.error("holds no particles (no points could be read); check that the file is complete"));

  vtkPointData* pd = poly->GetPointData();
  vtkDataArray* kind = pd->GetArray("kind");
  if (!kind || kind->GetNumberOfComponents() != 1)
    throw Error(
        s.error("has no point array 'kind' (one value per particle: 0 fluid, 1 fixed wall, 2 moving wall); add it"));
  check_array_names(s, pd);
  vtkDataArray* vel = pd->GetArray("velocity");
  if (vel && (vel->GetNumberOfComponents() < 2 || vel->GetNumberOfComponents() > 3))
    throw Error(s.error("point array 'velocity' has " + std::to_string(vel->GetNumberOfComponents()) +
                        " component(s); give 2 or 3 (x, y[, z])"));
  vtkDataArray* pres = pd->GetArray("pressure");
  if (pres && pres->GetNumberOfComponents() != 1)
    throw Error(s.error("point array 'pressure' must have one component"));
  vtkDataArray* slip = pd->GetArray("free_slip");
  if (slip && slip->GetNumberOfComponents() != 1)
    throw Error(s.error("point array 'free_slip' must have one component (1 on free-slip wall particles, else 0)"));
  if (slip) s.free_slip.assign(n, 0);

  s.x.resize(n), s.v.assign(n, {0.0, 0.0, 0.0}), s.p.assign(n, 0.0), s.kind.resize(n);
  double z0 = 0.0;
  bool flat = true;
  long fluid = 0;
  for (vtkIdType i = 0; i < n; ++i) {
    poly->GetPoint(i, s.x[i].data());
    if (!std::isfinite(s.x[i][0]) || !std::isfinite(s.x[i][1]) || !std::isfinite(s.x[i][2]))
      throw Error(s.error("particle " + std::to_string(i) + " has a coordinate that is not a number " +
                          point(s.x[i], 3) + "; fix or remove it"));
    if (i == 0) z0 = s.x[i][2];
    flat = flat && s.x[i][2] == z0;
    const double k = kind->GetComponent(i, 0);
    if (k != kSceneFluid && k != kSceneFixedWall && k != kSceneMovingWall) {
      std::ostringstream v;
      v << k;
      throw Error(s.error("particle " + std::to_string(i) + " has kind " + v.str() +
                          "; kind must be 0 (fluid), 1 (fixed wall) or 2 (moving wall)"));
    }
    s.kind[i] = static_cast<int>(k);
    fluid += s.kind[i] == kSceneFluid;
    if (vel)
      for (int a = 0; a < vel->GetNumberOfComponents(); ++a) s.v[i][a] = vel->GetComponent(i, a);
    if (pres) s.p[i] = pres->GetComponent(i, 0);
    if (slip) {
      const double f = slip->GetComponent(i, 0);
      if (f != 0 && f != 1) {
        std::ostringstream v;
        v << f;
        throw Error(s.error("particle " + std::to_string(i) + " has free_slip " + v.str() +
                            "; give 1 on free-slip wall particles, else 0"));
      }
      if (f == 1 && s.kind[i] == kSceneFluid)
        throw Error(s.error("particle " + std::to_string(i) +
                            " is fluid with free_slip 1; only wall particles have a slip condition"));
      s.free_slip[i] = static_cast<char>(f);
    }
    if (!std::isfinite(s.v[i][0]) || !std::isfinite(s.v[i][1]) || !std::isfinite(s.v[i][2]) || !std::isfinite(s.p[i]))
      throw Error(
          s.error("particle " + std::to_string(i) + " has a velocity or pressure that is not a number; fix it"));
  }
  if (fluid == 0) throw Error(s.error("has no fluid particle (kind 0); a scene needs fluid to move"));
  s.dim = flat ? 2 : 3;

  vtkFieldData* fd = poly->GetFieldData();
  for (int k = 0; fd && k < fd->GetNumberOfArrays(); ++k) {
    vtkDataArray* a = fd->GetArray(k);  // null for string arrays: not scene parameters
    if (!a || !a->GetName()) continue;
    std::vector<double>& values = s.field[a->GetName()];
    for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
      for (int c = 0; c < a->GetNumberOfComponents(); ++c) values.push_back(a->GetComponent(t, c));
  }
  return s;
}

}  // namespace sph
