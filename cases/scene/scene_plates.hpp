// Thin plates (2D): the fluid kept off them, their wall layers and their outline (src/neighbours/screens.hpp
// says how the neighbour lists see them). Internal to cases/scene/.
#pragma once

#include <vector>

#include "cases/scene/scene_reader.hpp"

namespace sph::scene_detail {

// Whether lattice point x lies within a plate or closer to its faces than half a spacing: no fluid
// there (the first fluid particles stand dx/2 off each face, as beside any wall).
bool in_plate_gap(const std::vector<Region>& plates, const Point3& x, double dx);

// Each face's wall layers: rows along the plate's part within the box, spaced as near dx as divides
// that part (on an axis-aligned plate, the lattice's own points), from the face inwards through the
// plate and on, layer after layer, into the other side; each particle labelled with its face (+1 the
// side the normal points to, -1 the other) for the neighbour lists (src/neighbours/screens.hpp).
// Where an end stands on a wall (`solids`), the layers and the screen go on through that wall, as
// deep as its layers: a wall particle beside the plate's foot would otherwise see the fluid of both
// sides, and its pressure, extrapolated from both, let the two sides' pressures meet under the plate
// (still water at two levels either side of a plate lost a fifth of its force); screened without the
// layers, the fluid in the corner would miss the wall beyond the plate from its support
// (docs/verification/thin_plate.md).
void add_plate_layers(const std::vector<Region>& plates, const std::vector<Region>& solids, int wall_layers, double dx,
                      const Point3& box_lo, const Point3& box_hi, YamlScene& out);

// A plate's outline added to a body's surface: its two faces, each in segments no longer than
// `step`, and its ends when it has a thickness. The outline is closed, and each face's pressure is
// fitted from the fluid on its own side (src/sph/surface_force.hpp): a zero-thickness plate's faces
// lie on one line and still take their sides' pressures.
void add_outline(const PlateSpec& p, double step, SurfaceMesh& surface);

}  // namespace sph::scene_detail
