#include "cases/scene/body_surface.hpp"

#include <vtkCellArray.h>
#include <vtkContourFilter.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sph {

namespace {

double distance_to(const std::vector<const Shape*>& parts, const Point3& x) {
  double d = std::numeric_limits<double>::infinity();
  for (const Shape* s : parts) d = std::min(d, s->distance(x));
  return d;
}

// Orders each cell's points so that its normal (mesh_normal) points out of the body, where the
// distance grows, and marks the mesh closed when its normals sum to zero: a uniform pressure then
// pushes on it with no net force, which the surface's force integral relies on.
void orient_outwards(SurfaceMesh& mesh, const std::vector<const Shape*>& parts, int dim, double step) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (std::vector<long>& cell : mesh.cells) {
    if (cell.size() < static_cast<std::size_t>(dim)) continue;
    const Point3 centre = face_centre(mesh, cell), n = face_area_normal(mesh, cell);
    if (!(n.norm() > 0.0)) continue;
    const Point3 e = 0.25 * step * n.normalized();
    if (distance_to(parts, centre + e) < distance_to(parts, centre - e)) std::reverse(cell.begin(), cell.end());
    sum += face_area_normal(mesh, cell), total += n.norm();
  }
  mesh.closed = total > 0.0 && sum.norm() <= 1e-9 * total;
}

// Splits every triangle into four, by its edges' midpoints, until no edge is longer than `step`: a
// mesh's own triangles may span the body, and the surface's force takes one pressure a face.
void refine_triangles(SurfaceMesh& mesh, double step) {
  std::vector<std::vector<long>> done, todo = mesh.cells;
  const auto point = [&](long k) { return Point3(mesh.points[static_cast<std::size_t>(k)].data()); };
  const auto add = [&](const Point3& x) {
    mesh.points.push_back({x[0], x[1], x[2]});
    return static_cast<long>(mesh.points.size()) - 1;
  };
  while (!todo.empty()) {
    std::vector<long> t = todo.back();
    todo.pop_back();
    const bool long_edge =
        t.size() == 3 && ((point(t[0]) - point(t[1])).norm() > step || (point(t[1]) - point(t[2])).norm() > step ||
                          (point(t[2]) - point(t[0])).norm() > step);
    if (!long_edge) {
      done.push_back(t);
      continue;
    }
    const long a = add(0.5 * (point(t[0]) + point(t[1]))), b = add(0.5 * (point(t[1]) + point(t[2]))),
               c = add(0.5 * (point(t[2]) + point(t[0])));
    for (const std::vector<long>& s : {std::vector<long>{t[0], a, c}, std::vector<long>{a, t[1], b},
                                       std::vector<long>{c, b, t[2]}, std::vector<long>{a, b, c}})
      todo.push_back(s);
  }
  mesh.cells = std::move(done);
}

}  // namespace

SurfaceMesh body_surface(const std::vector<const Shape*>& parts, int dim, const Point3& lo, const Point3& hi,
                         double step) {
  if (parts.size() == 1 && dim == 3) {
    SurfaceMesh own = parts[0]->own_surface();
    if (!own.cells.empty()) {
      refine_triangles(own, step);
      orient_outwards(own, parts, dim, step);
      return own;
    }
  }
  int n[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = std::max(2, static_cast<int>(std::ceil((hi[a] - lo[a]) / step)) + 1);
  vtkNew<vtkImageData> grid;
  grid->SetDimensions(n);
  grid->SetOrigin(lo[0], lo[1], dim == 3 ? lo[2] : 0.0);
  grid->SetSpacing(step, step, step);
  vtkNew<vtkDoubleArray> distance;
  distance->SetName("distance");
  distance->SetNumberOfTuples(static_cast<vtkIdType>(n[0]) * n[1] * n[2]);
  vtkIdType k = 0;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x, ++k) {
        const Point3 p(lo[0] + x * step, lo[1] + y * step, dim == 3 ? lo[2] + z * step : 0.0);
        distance->SetValue(k, distance_to(parts, p));
      }
  grid->GetPointData()->SetScalars(distance);
  vtkNew<vtkContourFilter> contour;
  contour->SetInputData(grid);
  contour->SetValue(0, 0.0);
  contour->Update();
  vtkPolyData* out = contour->GetOutput();
  SurfaceMesh mesh;
  mesh.lines = dim == 2;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i) {
    double x[3];
    out->GetPoint(i, x);
    mesh.points.push_back({x[0], x[1], x[2]});
  }
  vtkCellArray* cells = dim == 2 ? out->GetLines() : out->GetPolys();
  const vtkIdType* ids = nullptr;
  vtkIdType count = 0;
  for (cells->InitTraversal(); cells->GetNextCell(count, ids);) mesh.cells.emplace_back(ids, ids + count);
  orient_outwards(mesh, parts, dim, step);
  return mesh;
}

}  // namespace sph
