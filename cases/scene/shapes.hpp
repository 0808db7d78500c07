#pragma once
// Solids and regions of YAML scenes (cases/scene/scene_yaml.hpp) as signed distance functions: negative
// inside, zero on the surface, positive outside. Points are 3D; a 2D shape ignores z (2D scenes sample
// z = 0). The primitives give the exact Euclidean distance; union, intersection and difference take the
// min / max of their parts, a bound with the right sign that is exact near each part's own surface.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "src/io/surface_writer.hpp"

namespace sph {

using Point3 = Eigen::Vector3d;

struct Bounds {
  Point3 lo, hi;  // +-infinity along unbounded directions
};

class Shape {
 public:
  virtual ~Shape() = default;
  virtual double distance(const Point3& x) const = 0;
  virtual Bounds bounds() const = 0;
  // The largest up . x over the shape (+infinity when unbounded that way): a region's top for its
  // hydrostatic pressure. An upper bound for intersections and differences (their first part's top).
  virtual double highest(const Point3& up) const = 0;
  // The shape's own surface, where it has one (a mesh's triangles): exact where a contour of the
  // distance would cut its edges. Empty for the others.
  virtual SurfaceMesh own_surface() const { return {}; }
};
using ShapePtr = std::shared_ptr<const Shape>;

// dim 2: lo, hi in x and y, z ignored.
ShapePtr make_box(const Point3& lo, const Point3& hi, int dim);
ShapePtr make_ball(const Point3& centre, double radius);  // circle in 2D (z = 0), sphere in 3D
ShapePtr make_polygon(const std::vector<Eigen::Vector2d>& vertices);
ShapePtr make_cylinder(const Point3& end_a, const Point3& end_b, double radius);  // capped, 3D
// The solid side is (x - point) . normal <= 0; normal need not be a unit vector.
ShapePtr make_half_space(const Point3& point, const Point3& normal);
ShapePtr make_union(std::vector<ShapePtr> parts);
ShapePtr make_intersection(std::vector<ShapePtr> parts);
ShapePtr make_difference(std::vector<ShapePtr> parts);  // the first minus the others

// A closed surface from .stl, .obj or .vtp, inside by vtkImplicitPolyDataDistance with its normals
// turned outward. Throws sph::Error("<path>: <why>") when it cannot be read, is empty or is not closed.
ShapePtr make_mesh(const std::string& path);

}  // namespace sph
