#pragma once
// Thin plates that the kernel must not see through (2D: segments). A solid thinner than the kernel
// support cannot hold the wall layers the support needs inside itself, so each face of a plate gets
// its own layers, laid from that face through the plate and on into the fluid of the other side, and
// seen from its own side only. The neighbour lists drop every pair that the plate separates: a face's
// layers and whatever lies on the other side, and two particles on opposite sides that both lie
// alongside the plate (docs/verification/thin_plate.md).
#include <cstdint>
#include <utility>
#include <vector>

#include "src/core/types.hpp"

namespace sph {

template <int D> class Screens {
 public:
  // A plate's mid-surface from a to b (2D only: other dimensions have no plates), and the body it
  // belongs to (-1: a wall's), whose motion carries it (MovingBodies::move_to).
  struct Plate {
    Vector<D> a, b;
    int body = -1;
  };

  Screens() = default;
  // face_of_id: by particle id, 0 for a particle of no plate's layers, +(k + 1) for the layers of
  // plate k's face on the side its normal points to, -(k + 1) for the other face's.
  Screens(std::vector<Plate> plates, std::vector<std::int8_t> face_of_id)
      : plates_(std::move(plates)), start_(plates_), face_of_id_(std::move(face_of_id)) {
    frames_.resize(plates_.size());
    for (std::size_t k = 0; k < plates_.size(); ++k) frame(k);
  }

  bool any() const { return !plates_.empty(); }
  const std::vector<Plate>& plates() const { return plates_; }
  // The plates where the scene laid them, at t = 0.
  const std::vector<Plate>& start() const { return start_; }
  // Places plate k's mid-surface from a to b (its body moved it; its length stays).
  void move(std::size_t k, const Vector<D>& a, const Vector<D>& b) {
    plates_[k].a = a, plates_[k].b = b;
    frame(k);
  }
  // The plate's unit normal: its +1 face looks this way.
  Vector<D> normal(std::size_t k) const { return frames_[k].normal; }

  // Which side of each plate a point alongside it lies on: 2k for plate k's normal side, 2k + 1 for the
  // other, none beyond its ends. Points with the same view see the same particles through the plates: a
  // body's surface pressure is fitted per view (surface_force.hpp), so that a plate's two faces take
  // their pressures from their own sides.
  std::vector<int> view(const Vector<D>& x) const {
    std::vector<int> sides;
    for (std::size_t k = 0; k < plates_.size(); ++k) {
      const Frame& f = frames_[k];
      const double along = (x - plates_[k].a).dot(f.along);
      if (along >= 0.0 && along <= f.length)
        sides.push_back(2 * static_cast<int>(k) + ((x - plates_[k].a).dot(f.normal) >= 0.0 ? 0 : 1));
    }
    return sides;
  }

  // Whether particles i and j (positions, permanent ids) see each other. Symmetric in i and j, so the
  // pair forces stay equal and opposite.
  bool see(const Vector<D>& xi, GlobalIndex id_i, const Vector<D>& xj, GlobalIndex id_j) const {
    const int face_i = face(id_i), face_j = face(id_j);
    for (std::size_t k = 0; k < plates_.size(); ++k) {
      const Frame& f = frames_[k];
      const double di = (xi - plates_[k].a).dot(f.normal), dj = (xj - plates_[k].a).dot(f.normal);
      const int own = static_cast<int>(k) + 1;
      const bool layer_i = face_i == own || face_i == -own, layer_j = face_j == own || face_j == -own;
      // A face's layer particle stands for its own side, wherever it lies.
      const int side_i = layer_i ? (face_i > 0 ? 1 : -1) : (di >= 0 ? 1 : -1);
      const int side_j = layer_j ? (face_j > 0 ? 1 : -1) : (dj >= 0 ? 1 : -1);
      if (side_i == side_j) continue;
      if (layer_i || layer_j) return false;
      // Opposite sides, both alongside the plate: the other side is where the layers stand. Beyond
      // either end the layers leave off, and what lies there is seen from both sides; a sight line
      // that only clips the end would cut a hole of missing neighbours under the layers' last row
      // (WCSPH still water pulled its fluid round a submerged end).
      const double along_i = (xi - plates_[k].a).dot(f.along), along_j = (xj - plates_[k].a).dot(f.along);
      if (along_i >= 0.0 && along_i <= f.length && along_j >= 0.0 && along_j <= f.length) return false;
    }
    return true;
  }

 private:
  struct Frame {
    Vector<D> along, normal;
    double length = 0.0;
  };
  void frame(std::size_t k) {
    const Vector<D> along = plates_[k].b - plates_[k].a;
    Frame& f = frames_[k];
    f.length = along.norm();
    f.along = along / f.length;
    f.normal = Vector<D>::Zero();
    if constexpr (D == 2) f.normal = Vector<D>(-f.along[1], f.along[0]);
  }
  int face(GlobalIndex id) const {
    return id >= 0 && static_cast<std::size_t>(id) < face_of_id_.size() ? face_of_id_[static_cast<std::size_t>(id)] : 0;
  }

  std::vector<Plate> plates_, start_;
  std::vector<Frame> frames_;
  std::vector<std::int8_t> face_of_id_;
};

}  // namespace sph
