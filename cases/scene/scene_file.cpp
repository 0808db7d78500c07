#include "cases/scene/scene_file.hpp"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nanoflann.hpp>
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

namespace {

// The point arrays a scene's particles are read from, each checked for its components.
struct SceneArrays {
  vtkDataArray *kind, *velocity, *pressure, *free_slip;
};

SceneArrays scene_arrays(const SceneFile& s, vtkPointData* pd) {
  vtkDataArray* kind = pd->GetArray("kind");
  if (!kind)
    throw Error(
        s.error("has no point array 'kind' (one value per particle: 0 fluid, 1 fixed wall, 2 moving wall); add it"));
  if (kind->GetNumberOfComponents() != 1)
    throw Error(s.error("point array 'kind' has " + std::to_string(kind->GetNumberOfComponents()) +
                        " components; give one (0 fluid, 1 fixed wall, 2 moving wall per particle)"));
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
  return {kind, vel, pres, slip};
}

// Particle i's position, kind, velocity, pressure and slip flag, each checked.
void read_particle(SceneFile& s, vtkPolyData* poly, const SceneArrays& arrays, vtkIdType i) {
  poly->GetPoint(i, s.x[i].data());
  if (!std::isfinite(s.x[i][0]) || !std::isfinite(s.x[i][1]) || !std::isfinite(s.x[i][2]))
    throw Error(s.error("particle " + std::to_string(i) + " has a coordinate that is not a number " + point(s.x[i], 3) +
                        "; fix or remove it"));
  const double k = arrays.kind->GetComponent(i, 0);
  if (k != kSceneFluid && k != kSceneFixedWall && k != kSceneMovingWall) {
    std::ostringstream v;
    v << k;
    throw Error(s.error("particle " + std::to_string(i) + " has kind " + v.str() +
                        "; kind must be 0 (fluid), 1 (fixed wall) or 2 (moving wall)"));
  }
  s.kind[i] = static_cast<int>(k);
  if (vtkDataArray* vel = arrays.velocity)
    for (int a = 0; a < vel->GetNumberOfComponents(); ++a) s.v[i][a] = vel->GetComponent(i, a);
  if (arrays.pressure) s.p[i] = arrays.pressure->GetComponent(i, 0);
  if (arrays.free_slip) {
    const double f = arrays.free_slip->GetComponent(i, 0);
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
    throw Error(s.error("particle " + std::to_string(i) + " has a velocity or pressure that is not a number; fix it"));
}

// The field data: the scene's parameters by name (string arrays are not parameters).
void read_field_data(SceneFile& s, vtkFieldData* fd) {
  for (int k = 0; fd && k < fd->GetNumberOfArrays(); ++k) {
    vtkDataArray* a = fd->GetArray(k);  // null for string arrays
    if (!a || !a->GetName()) continue;
    std::vector<double>& values = s.field[a->GetName()];
    for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
      for (int c = 0; c < a->GetNumberOfComponents(); ++c) values.push_back(a->GetComponent(t, c));
  }
}

}  // namespace

SceneFile read_scene_file(const std::string& path) {
  SceneFile s;
  s.path = path;
  // A folder opens as a stream on Linux and fails at the first read, naming no file.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error(s.error("is a folder, not a scene file; give -scene_file the path of a .vtp or .yaml file"));
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

  const SceneArrays arrays = scene_arrays(s, poly->GetPointData());
  if (arrays.free_slip) s.free_slip.assign(n, 0);
  s.x.resize(n), s.v.assign(n, {0.0, 0.0, 0.0}), s.p.assign(n, 0.0), s.kind.resize(n);
  bool flat = true;
  long fluid = 0;
  for (vtkIdType i = 0; i < n; ++i) {
    read_particle(s, poly, arrays, i);
    flat = flat && s.x[i][2] == s.x[0][2];
    fluid += s.kind[i] == kSceneFluid;
  }
  if (fluid == 0) throw Error(s.error("has no fluid particle (kind 0); a scene needs fluid to move"));
  s.dim = flat ? 2 : 3;
  read_field_data(s, poly->GetFieldData());
  return s;
}

namespace {
struct SceneCloud {
  const std::vector<std::array<double, 3>>& pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t a) const { return pts[i][a]; }
  template <class BBox> bool kdtree_get_bbox(BBox&) const { return false; }
};
}  // namespace

double median_spacing(const SceneFile& s) {
  if (s.x.size() < 2) return 0.0;
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SceneCloud>, SceneCloud, 3,
                                                   std::uint32_t>;
  const SceneCloud cloud{s.x};
  Tree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  // A strided sample of the particles is enough for a median, and keeps a huge scene's check short.
  const std::size_t stride = std::max<std::size_t>(1, s.x.size() / 20000);
  std::vector<double> nearest;
  for (std::size_t i = 0; i < s.x.size(); i += stride) {
    std::uint32_t index[2];
    double d2[2];
    if (tree.knnSearch(s.x[i].data(), 2, index, d2) == 2) nearest.push_back(std::sqrt(d2[1]));
  }
  if (nearest.empty()) return 0.0;
  std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
  return nearest[nearest.size() / 2];
}

}  // namespace sph
