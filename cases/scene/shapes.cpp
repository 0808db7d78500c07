#include "cases/scene/shapes.hpp"

#include <vtkCellArray.h>
#include <vtkFeatureEdges.h>
#include <vtkImplicitPolyDataDistance.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "src/core/error.hpp"

namespace sph {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Bounds everywhere() { return {Point3::Constant(-kInf), Point3::Constant(kInf)}; }

class Box : public Shape {
 public:
  Box(const Point3& lo, const Point3& hi, int dim) : lo_(lo), hi_(hi), dim_(dim) {
    if (dim == 2) lo_.z() = hi_.z() = 0.0;
  }
  double distance(const Point3& x) const override {
    double outside = 0.0, inside = -kInf;
    for (int a = 0; a < dim_; ++a) {
      const double q = std::abs(x[a] - 0.5 * (lo_[a] + hi_[a])) - 0.5 * (hi_[a] - lo_[a]);
      outside += std::max(q, 0.0) * std::max(q, 0.0);
      inside = std::max(inside, q);
    }
    return std::sqrt(outside) + std::min(inside, 0.0);
  }
  Bounds bounds() const override {
    Bounds b = everywhere();
    for (int a = 0; a < dim_; ++a) b.lo[a] = lo_[a], b.hi[a] = hi_[a];
    return b;
  }
  double highest(const Point3& up) const override {
    double h = 0.0;
    for (int a = 0; a < dim_; ++a) h += std::max(lo_[a] * up[a], hi_[a] * up[a]);
    return h;
  }

 private:
  Point3 lo_, hi_;
  int dim_;
};

class Ball : public Shape {
 public:
  Ball(const Point3& c, double r) : c_(c), r_(r) {}
  double distance(const Point3& x) const override { return (x - c_).norm() - r_; }
  Bounds bounds() const override { return {c_.array() - r_, c_.array() + r_}; }
  double highest(const Point3& up) const override { return c_.dot(up) + r_ * up.norm(); }

 private:
  Point3 c_;
  double r_;
};

class Polygon : public Shape {
 public:
  explicit Polygon(std::vector<Eigen::Vector2d> v) : v_(std::move(v)) {}
  // Distance to the nearest edge; inside by the crossing number (even-odd rule).
  double distance(const Point3& x3) const override {
    const Eigen::Vector2d x(x3.x(), x3.y());
    double d2 = kInf;
    bool inside = false;
    for (std::size_t i = 0, j = v_.size() - 1; i < v_.size(); j = i++) {
      const Eigen::Vector2d e = v_[j] - v_[i], w = x - v_[i];
      const double t = std::clamp(w.dot(e) / e.squaredNorm(), 0.0, 1.0);
      d2 = std::min(d2, (w - t * e).squaredNorm());
      if ((v_[i].y() > x.y()) != (v_[j].y() > x.y()) && x.x() < v_[i].x() + (x.y() - v_[i].y()) * e.x() / e.y())
        inside = !inside;
    }
    return inside ? -std::sqrt(d2) : std::sqrt(d2);
  }
  Bounds bounds() const override {
    Bounds b = everywhere();
    b.lo.head<2>() = b.hi.head<2>() = v_[0];
    for (const auto& p : v_) b.lo.head<2>() = b.lo.head<2>().cwiseMin(p), b.hi.head<2>() = b.hi.head<2>().cwiseMax(p);
    return b;
  }
  double highest(const Point3& up) const override {
    double h = -kInf;
    for (const auto& p : v_) h = std::max(h, p.dot(up.head<2>()));
    return h;
  }

 private:
  std::vector<Eigen::Vector2d> v_;
};

// Exact distance to a capped cylinder (Quilez, "distance functions": capped cylinder, arbitrary axis).
class Cylinder : public Shape {
 public:
  Cylinder(const Point3& a, const Point3& b, double r) : a_(a), b_(b), r_(r) {}
  double distance(const Point3& p) const override {
    const Point3 ba = b_ - a_, pa = p - a_;
    const double baba = ba.squaredNorm(), paba = pa.dot(ba);
    const double x = (pa * baba - ba * paba).norm() - r_ * baba;  // radial, times baba
    const double y = std::abs(paba - 0.5 * baba) - 0.5 * baba;    // axial, times |ba|
    const double x2 = x * x, y2 = y * y * baba;
    const double d = std::max(x, y) < 0 ? -std::min(x2, y2) : (x > 0 ? x2 : 0.0) + (y > 0 ? y2 : 0.0);
    return std::copysign(std::sqrt(std::abs(d)), d) / baba;
  }
  Bounds bounds() const override {
    const Point3 e = (b_ - a_).normalized();
    const Point3 reach = r_ * (Point3::Ones() - e.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
    return {a_.cwiseMin(b_) - reach, a_.cwiseMax(b_) + reach};
  }
  double highest(const Point3& up) const override {
    const Point3 e = (b_ - a_).normalized();
    const double along = e.dot(up);
    return std::max(a_.dot(up), b_.dot(up)) + r_ * std::sqrt(std::max(0.0, up.squaredNorm() - along * along));
  }

 private:
  Point3 a_, b_;
  double r_;
};

class HalfSpace : public Shape {
 public:
  HalfSpace(const Point3& p, const Point3& n) : p_(p), n_(n.normalized()) {}
  double distance(const Point3& x) const override { return (x - p_).dot(n_); }
  // Bounded only along an axis that the normal follows: a floor or a side wall.
  Bounds bounds() const override {
    Bounds b = everywhere();
    for (int a = 0; a < 3; ++a)
      if (std::abs(n_[a]) == 1.0) (n_[a] > 0 ? b.hi[a] : b.lo[a]) = p_[a];
    return b;
  }
  double highest(const Point3& up) const override {
    const double u = up.norm();
    return u > 0 && n_.dot(up) >= u * (1 - 1e-12) ? p_.dot(up) : kInf;
  }

 private:
  Point3 p_, n_;
};

enum class Combine { Union, Intersection, Difference };

class Combination : public Shape {
 public:
  Combination(Combine op, std::vector<ShapePtr> parts) : op_(op), parts_(std::move(parts)) {}
  double distance(const Point3& x) const override {
    double d = parts_[0]->distance(x);
    for (std::size_t k = 1; k < parts_.size(); ++k) {
      const double dk = parts_[k]->distance(x);
      d = op_ == Combine::Union ? std::min(d, dk) : op_ == Combine::Intersection ? std::max(d, dk) : std::max(d, -dk);
    }
    return d;
  }
  Bounds bounds() const override {
    Bounds b = parts_[0]->bounds();
    for (std::size_t k = 1; k < parts_.size() && op_ != Combine::Difference; ++k) {
      const Bounds bk = parts_[k]->bounds();
      if (op_ == Combine::Union) b.lo = b.lo.cwiseMin(bk.lo), b.hi = b.hi.cwiseMax(bk.hi);
      else b.lo = b.lo.cwiseMax(bk.lo), b.hi = b.hi.cwiseMin(bk.hi);
    }
    return b;
  }
  double highest(const Point3& up) const override {
    double h = parts_[0]->highest(up);
    for (std::size_t k = 1; k < parts_.size() && op_ != Combine::Difference; ++k)
      h = op_ == Combine::Union ? std::max(h, parts_[k]->highest(up)) : std::min(h, parts_[k]->highest(up));
    return h;
  }

 private:
  Combine op_;
  std::vector<ShapePtr> parts_;
};

class Mesh : public Shape {
 public:
  explicit Mesh(vtkSmartPointer<vtkPolyData> surface) : surface_(surface) {
    distance_->SetInput(surface_);
    double b[6];
    surface_->GetBounds(b);
    bounds_ = {Point3(b[0], b[2], b[4]), Point3(b[1], b[3], b[5])};
  }
  double distance(const Point3& x) const override {
    double p[3] = {x.x(), x.y(), x.z()};
    return distance_->EvaluateFunction(p);
  }
  Bounds bounds() const override { return bounds_; }
  double highest(const Point3& up) const override {
    double h = -kInf, p[3];
    for (vtkIdType i = 0; i < surface_->GetNumberOfPoints(); ++i)
      surface_->GetPoint(i, p), h = std::max(h, Point3(p[0], p[1], p[2]).dot(up));
    return h;
  }
  SurfaceMesh own_surface() const override {
    SurfaceMesh mesh;
    double p[3];
    for (vtkIdType i = 0; i < surface_->GetNumberOfPoints(); ++i)
      surface_->GetPoint(i, p), mesh.points.push_back({p[0], p[1], p[2]});
    const vtkIdType* ids = nullptr;
    vtkIdType count = 0;
    vtkCellArray* cells = surface_->GetPolys();
    for (cells->InitTraversal(); cells->GetNextCell(count, ids);) mesh.cells.emplace_back(ids, ids + count);
    return mesh;
  }

 private:
  vtkSmartPointer<vtkPolyData> surface_;
  vtkNew<vtkImplicitPolyDataDistance> distance_;
  Bounds bounds_;
};

// VTK's readers print their complaints on their own; the file is judged here by what they returned.
struct QuietVtk {
  int saved = vtkObject::GetGlobalWarningDisplay();
  QuietVtk() { vtkObject::GlobalWarningDisplayOff(); }
  ~QuietVtk() { vtkObject::SetGlobalWarningDisplay(saved); }
};

template <class Reader> vtkSmartPointer<vtkPolyData> read_with(const std::string& path) {
  const QuietVtk quiet;
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkPolyData> out = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !out || out->GetNumberOfPolys() == 0)
    throw Error("'" + path + "' holds no surface (no polygons could be read); check that the file is complete");
  return out;
}

// VTK's OBJ reader trusts the faces' vertex numbers: one past the vertices (f 1 2 99) or 0 (OBJ counts
// from 1) is read out of bounds. Checked here first: the largest, the smallest and any zero number
// against the vertices the file holds (a face may name a vertex given after it; -k counts back).
void check_obj_faces(const std::string& path) {
  std::ifstream in(path);
  long vertices = 0, line_no = 0, highest = 0, lowest = 0, highest_at = 0, lowest_at = 0, zero_at = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") ++vertices;
    if (tag != "f" && tag != "l" && tag != "p") continue;
    for (std::string w; words >> w;) {
      char* end = nullptr;
      const long k = std::strtol(w.c_str(), &end, 10);
      if (end == w.c_str()) continue;  // not a number: the reader's to judge
      if (k == 0 && !zero_at) zero_at = line_no;
      if (k > highest) highest = k, highest_at = line_no;
      if (k < lowest) lowest = k, lowest_at = line_no;
    }
  }
  const std::string where = "'" + path + "' line ";
  if (zero_at)
    throw Error(where + std::to_string(zero_at) +
                ": a face names vertex 0; OBJ numbers vertices from 1 (or -1 for the last): fix the face");
  if (highest > vertices)
    throw Error(where + std::to_string(highest_at) + ": a face names vertex " + std::to_string(highest) + " of the " +
                std::to_string(vertices) + " the file holds; fix the face or add its vertices");
  if (-lowest > vertices)
    throw Error(where + std::to_string(lowest_at) + ": a face names vertex " + std::to_string(lowest) +
                ", before the " + std::to_string(vertices) + " the file holds; fix the face");
}

// An STL is binary (an 80-byte header, a 4-byte triangle count, 50 bytes a triangle) or text starting
// "solid" with "facet" soon after. Checked here from the file's size and first bytes, so that a file
// that is neither (a 3 GB archive named .stl) is refused at once instead of read whole by VTK.
void check_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[1024] = {};
  in.read(head, sizeof head);
  const std::size_t got = static_cast<std::size_t>(in.gcount());
  const std::uintmax_t size = std::filesystem::file_size(path);
  if (size >= 84) {
    const auto* b = reinterpret_cast<const unsigned char*>(head + 80);
    const std::uintmax_t triangles = b[0] | (b[1] << 8) | (b[2] << 16) | (std::uintmax_t(b[3]) << 24);
    if (size == 84 + 50 * triangles) return;  // binary (its header may start with "solid" too)
  }
  const std::string text(head, got);
  if (text.rfind("solid", 0) == 0 && (text.find("facet") != std::string::npos || size <= got)) return;
  throw Error("'" + path +
              "' is not an STL file: neither text starting 'solid ... facet' nor binary (84 bytes + 50 a " +
              "triangle; this file has " + std::to_string(size) + " bytes); export the surface as STL, OBJ or VTP");
}

vtkSmartPointer<vtkPolyData> read_surface(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".stl" && ext != ".obj" && ext != ".vtp")
    throw Error("'" + path + "' is not .stl, .obj or .vtp; convert the surface to one of those");
  if (!std::filesystem::is_regular_file(path)) throw Error("cannot read '" + path + "'; check the path");
  return ext == ".stl"   ? (check_stl(path), read_with<vtkSTLReader>(path))
         : ext == ".obj" ? (check_obj_faces(path), read_with<vtkOBJReader>(path))
                         : read_with<vtkXMLPolyDataReader>(path);
}

}  // namespace

ShapePtr make_box(const Point3& lo, const Point3& hi, int dim) { return std::make_shared<Box>(lo, hi, dim); }
ShapePtr make_ball(const Point3& centre, double radius) { return std::make_shared<Ball>(centre, radius); }
ShapePtr make_polygon(const std::vector<Eigen::Vector2d>& vertices) { return std::make_shared<Polygon>(vertices); }
ShapePtr make_cylinder(const Point3& a, const Point3& b, double radius) {
  return std::make_shared<Cylinder>(a, b, radius);
}
ShapePtr make_half_space(const Point3& point, const Point3& normal) {
  return std::make_shared<HalfSpace>(point, normal);
}
ShapePtr make_union(std::vector<ShapePtr> parts) {
  return std::make_shared<Combination>(Combine::Union, std::move(parts));
}
ShapePtr make_intersection(std::vector<ShapePtr> parts) {
  return std::make_shared<Combination>(Combine::Intersection, std::move(parts));
}
ShapePtr make_difference(std::vector<ShapePtr> parts) {
  return std::make_shared<Combination>(Combine::Difference, std::move(parts));
}

ShapePtr make_mesh(const std::string& path) {
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(read_surface(path));
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  // An open surface has no inside: its edges used by one triangle only give it away.
  vtkNew<vtkFeatureEdges> open;
  open->SetInputConnection(triangles->GetOutputPort());
  open->BoundaryEdgesOn();
  open->FeatureEdgesOff();
  open->ManifoldEdgesOff();
  open->NonManifoldEdgesOff();
  open->Update();
  const vtkIdType edges = open->GetOutput()->GetNumberOfLines();
  if (edges > 0)
    throw Error("'" + path + "' is not a closed surface (" + std::to_string(edges) +
                " edges border one triangle only); close it, e.g. fill its holes");
  // Inside is told by the normals: turned consistently outward, whatever the file's winding.
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(triangles->GetOutputPort());
  normals->SplittingOff();
  normals->ConsistencyOn();
  normals->AutoOrientNormalsOn();
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOn();
  normals->Update();
  vtkSmartPointer<vtkPolyData> surface = normals->GetOutput();
  // A closed surface of no volume (every z equal) has no inside to tell: its distance's sign is noise,
  // and the lattice points near it all read as inside. Its volume by the divergence theorem.
  double volume = 0, b[6], p[3][3];
  surface->GetBounds(b);
  const vtkIdType* ids = nullptr;
  vtkIdType count = 0;
  vtkCellArray* cells = surface->GetPolys();
  for (cells->InitTraversal(); cells->GetNextCell(count, ids);) {
    if (count != 3) continue;
    for (int c = 0; c < 3; ++c) surface->GetPoint(ids[c], p[c]);
    volume += (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
               p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) /
              6.0;
  }
  const double size = std::max({b[1] - b[0], b[3] - b[2], b[5] - b[4]});
  if (!(std::abs(volume) > 1e-9 * size * size * size))
    throw Error("'" + path + "' encloses no volume (a flat surface: its extent is " + std::to_string(b[1] - b[0]) +
                " x " + std::to_string(b[3] - b[2]) + " x " + std::to_string(b[5] - b[4]) +
                "); give a solid with thickness");
  return std::make_shared<Mesh>(surface);
}

}  // namespace sph
