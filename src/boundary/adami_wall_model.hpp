#pragma once
// Adami, Hu & Adams (2012)'s walls as the schemes' wall model (src/boundary/wall_model.hpp). Their
// pressure is continued from the fluid in one of the two forms -wall_pressure names (the relations are
// in src/boundary/adami_wall.hpp): adami, as published, or continued, with the fluid's own pressure
// gradient along the wall. The option sets the form of every wall group that does not choose its own
// (a scene's `wall_pressure:` on a wall or body region, MovingBodies::wall_pressure). The viscous term
// sees the no-slip mirror, or the fluid's own velocity on a free-slip group; a moving body's walls
// take g - a_w.
#include <memory>
#include <string>
#include <vector>

#include "src/boundary/adami_wall.hpp"
#include "src/boundary/wall_model.hpp"

namespace sph {

template <int D> class AdamiWallModel : public WallModel<D> {
 public:
  AdamiWallModel(const MovingBodies<D>& bodies, WallPressure form) : WallModel<D>(bodies), form_(form) {}
  std::string name() const override { return wall_pressure_names[static_cast<int>(form_)]; }

  void extrapolate_pressure(Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                            const Vector<D>& body_force) const override {
    const std::vector<Vector<D>> a = this->accelerations(P);
    const typename AdamiWall<D>::Stencil s = AdamiWall<D>::stencil(P, nh.list(), K);
    AdamiWall<D>::extrapolate_pressure(s, continuation(P, nh, K, P.p, s), P, body_force, &a);
  }
  WallContinuation<D> continuation(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                   const std::vector<double>& pressure) const override {
    return uses(WallPressure::Continued) ? continuation(P, nh, K, pressure, AdamiWall<D>::stencil(P, nh.list(), K))
                                         : WallContinuation<D>();
  }
  std::vector<Vector<D>> viscous_velocity(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                          const std::vector<Vector<D>>& field) const override {
    return AdamiWall<D>::viscous_velocity(nh, K, P, &field, &this->bodies());
  }
  Vector<D> wall_velocity(const Particles<D>& P, std::size_t w, const Vector<D>& u_f,
                          const Vector<D>& r) const override {
    return AdamiWall<D>::mirror_velocity(P, w, u_f, r, &this->bodies());
  }
  std::vector<Vector<D>> normals(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K) const override {
    return AdamiWall<D>::normals(P, nh, K, AdamiWall<D>::stencil(P, nh.list(), K));
  }

 private:
  // The form wall particle i takes: its group's own, else the option's.
  WallPressure form_of(const Particles<D>& P, std::size_t i) const {
    const int own = this->bodies().wall_pressure(P, i);
    return own < 0 ? form_ : static_cast<WallPressure>(own);
  }
  // Whether some wall group may take `form` (the same answer on every rank).
  bool uses(WallPressure form) const {
    return form_ == form || this->bodies().wall_pressure_chosen(static_cast<int>(form));
  }
  // The continued form's relation where some group takes it; Adami's (no normal) on the others.
  WallContinuation<D> continuation(const Particles<D>& P, const Neighbourhood<D>& nh, const Kernel<D>& K,
                                   const std::vector<double>& pressure, const typename AdamiWall<D>::Stencil& s) const {
    if (!uses(WallPressure::Continued)) return {};
    WallContinuation<D> c = AdamiWall<D>::continuation(P, nh, K, pressure, s);
    if (uses(WallPressure::Adami))
      for (std::size_t w = 0; w < c.normal.size(); ++w)
        if (form_of(P, w) == WallPressure::Adami) c.normal[w].setZero();
    return c;
  }

  WallPressure form_;
};

// The wall model of the walls and bodies of `bodies`, its groups' pressure continued by default as
// -wall_pressure chose.
template <int D> std::shared_ptr<const WallModel<D>> make_wall_model(WallPressure form, const MovingBodies<D>& bodies) {
  return std::make_shared<AdamiWallModel<D>>(bodies, form);
}

}  // namespace sph
