#pragma once
// The surface of a body of a YAML scene, for ParaView (src/io/surface_writer.hpp): the zero contour
// of its signed distance, sampled on a grid finer than the particles (lines in 2D, triangles in 3D).
#include <vector>

#include "cases/scene/shapes.hpp"
#include "src/io/surface_writer.hpp"

namespace sph {

// The surface where the union of `parts` meets the rest, within [lo, hi], sampled every `step`; a
// single part with a surface of its own (a mesh) gives that, whole.
SurfaceMesh body_surface(const std::vector<const Shape*>& parts, int dim, const Point3& lo, const Point3& hi,
                         double step);

}  // namespace sph
