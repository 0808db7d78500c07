// Smoothing kernels: normalisation (integral over R^D is one, by a radial quadrature independent of
// the closed-form constants in kernel.cpp), positivity, compact support, monotonicity, dW/dr against
// finite differences of W, and the antisymmetry/direction of the kernel gradient. Every kernel type
// in 1D, 2D and 3D.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/kernels/kernel.hpp"

namespace {

using namespace sph;

constexpr double kH = 0.7;  // a smoothing length that is not one, so the h scaling is exercised

std::vector<KernelType> all_types() {
  std::vector<KernelType> t;
  for (std::size_t k = 0; k < kernel_names().size(); ++k) t.push_back(static_cast<KernelType>(k));
  return t;
}

// Surface measure of the unit sphere in D dimensions: 2, 2 pi, 4 pi.
double sphere_area(int D) { return D == 1 ? 2.0 : D == 2 ? 2.0 * M_PI : 4.0 * M_PI; }

// Composite Simpson rule for g on [a, b] with n (even) intervals.
template <class G> double simpson(G&& g, double a, double b, int n) {
  const double dr = (b - a) / n;
  double s = g(a) + g(b);
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4.0 : 2.0) * g(a + k * dr);
  return s * dr / 3.0;
}

// Points where a kernel's pieces join (q = r/h); the quadrature and finite differences split there.
bool near_breakpoint(double q, double tol) {
  for (double b : {1.0, 2.0, 3.0})
    if (std::abs(q - b) < tol) return true;
  return false;
}

template <int D> void integrates_to_one() {
  SCOPED_TRACE("D = " + std::to_string(D));
  for (KernelType t : all_types()) {
    const Kernel<D> K(t, kH);
    const double R = K.support_radius();
    // Integrate S_D r^(D-1) W(r) piecewise between the joins at r = h, 2h, 3h, so that Simpson's rule
    // sees a smooth integrand on each piece (the truncated Gaussian jumps at its cut-off, R = 3h).
    auto g = [&](double r) { return sphere_area(D) * std::pow(r, D - 1) * K.W(r); };
    double integral = 0.0;
    double a = 0.0;
    for (double b : {kH, 2.0 * kH, 3.0 * kH}) {
      if (a >= R) break;
      const double bb = std::min(b, R);
      // Evaluate just inside the right end: W(R) itself is 0 (the support is open) even where the
      // kernel's limit from inside is not (the truncated Gaussian).
      const double right = bb == R ? bb * (1.0 - 1e-15) : bb;
      integral += simpson(g, a, right, 20000);
      a = bb;
    }
    EXPECT_NEAR(integral, 1.0, 1e-6) << K.name() << " D=" << D;
  }
}

template <int D> void positive_with_compact_support() {
  SCOPED_TRACE("D = " + std::to_string(D));
  for (KernelType t : all_types()) {
    const Kernel<D> K(t, kH);
    const double R = K.support_radius();
    EXPECT_DOUBLE_EQ(R, Kernel<D>::support_factor(t) * kH);
    EXPECT_GT(K.W(0.0), 0.0) << K.name();
    EXPECT_EQ(K.dWdr(0.0), 0.0) << K.name() << ": kernel must be flat at r = 0";
    for (int k = 0; k < 2000; ++k) {
      const double r = R * k / 2000.0;
      EXPECT_GT(K.W(r), 0.0) << K.name() << " r/h=" << r / kH;
      EXPECT_LE(K.dWdr(r), 0.0) << K.name() << " r/h=" << r / kH;
    }
    for (double r : {R, std::nextafter(R, 2.0 * R), 1.0001 * R, 1.5 * R, 10.0 * R}) {
      EXPECT_EQ(K.W(r), 0.0) << K.name() << " r/R=" << r / R;
      EXPECT_EQ(K.dWdr(r), 0.0) << K.name() << " r/R=" << r / R;
    }
  }
}

template <int D> void decreasing_in_r() {
  SCOPED_TRACE("D = " + std::to_string(D));
  for (KernelType t : all_types()) {
    const Kernel<D> K(t, kH);
    const double R = K.support_radius();
    double prev = K.W(0.0);
    for (int k = 1; k <= 5000; ++k) {
      const double w = K.W(R * k / 5000.0);
      EXPECT_LT(w, prev) << K.name() << " r/h=" << R * k / 5000.0 / kH;
      prev = w;
    }
  }
}

template <int D> void derivative_matches_finite_difference() {
  SCOPED_TRACE("D = " + std::to_string(D));
  for (KernelType t : all_types()) {
    const Kernel<D> K(t, kH);
    const double R = K.support_radius();
    double scale = 0.0;  // max |dW/dr|, for a relative tolerance
    for (int k = 0; k <= 1000; ++k) scale = std::max(scale, std::abs(K.dWdr(R * k / 1000.0)));
    ASSERT_GT(scale, 0.0);
    const double delta = 1e-5 * kH;
    double worst = 0.0;
    for (int k = 1; k < 997; ++k) {
      const double r = R * (k + 0.37) / 1000.0;
      if (near_breakpoint(r / kH, 1e-3) || r + delta >= R) continue;
      const double fd = (K.W(r + delta) - K.W(r - delta)) / (2.0 * delta);
      worst = std::max(worst, std::abs(fd - K.dWdr(r)) / scale);
    }
    EXPECT_LT(worst, 1e-7) << K.name() << " D=" << D;
  }
}

template <int D> void gradient_antisymmetric_and_radial() {
  SCOPED_TRACE("D = " + std::to_string(D));
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (KernelType t : all_types()) {
    const Kernel<D> K(t, kH);
    const double R = K.support_radius();
    EXPECT_EQ(K.gradient(Vector<D>::Zero(), 0.0).norm(), 0.0) << K.name();
    for (int k = 0; k < 200; ++k) {
      Vector<D> dir;
      for (int a = 0; a < D; ++a) dir[a] = u(gen);
      if (dir.norm() < 1e-3) continue;
      dir.normalize();
      const double r = 1.1 * R * (k + 0.5) / 200.0;  // some pairs beyond the support
      const Vector<D> rij = r * dir;
      const Vector<D> g = K.gradient(rij, r);
      const Vector<D> gm = K.gradient(Vector<D>(-rij), r);
      const double tol = 1e-14 * std::max(1.0, g.norm());
      EXPECT_LT((g + gm).norm(), tol) << K.name() << ": grad_i W_ij = -grad_j W_ij";
      // Radial: parallel to r_ij with magnitude |dW/dr|, pointing from i towards j (W decreases).
      EXPECT_NEAR(g.dot(dir), K.dWdr(r), tol) << K.name();
      EXPECT_LT((g - g.dot(dir) * dir).norm(), tol) << K.name();
      if (r < R) {
        EXPECT_LT(g.dot(rij), 0.0) << K.name();
      } else {
        EXPECT_EQ(g.norm(), 0.0) << K.name();
      }
    }
  }
}

TEST(KernelProperties, IntegratesToOne) {
  integrates_to_one<1>();
  integrates_to_one<2>();
  integrates_to_one<3>();
}

TEST(KernelProperties, PositiveDecreasingWithCompactSupport) {
  positive_with_compact_support<1>();
  positive_with_compact_support<2>();
  positive_with_compact_support<3>();
  decreasing_in_r<1>();
  decreasing_in_r<2>();
  decreasing_in_r<3>();
}

TEST(KernelProperties, DerivativeMatchesFiniteDifference) {
  derivative_matches_finite_difference<1>();
  derivative_matches_finite_difference<2>();
  derivative_matches_finite_difference<3>();
}

TEST(KernelProperties, GradientAntisymmetricAndRadial) {
  gradient_antisymmetric_and_radial<1>();
  gradient_antisymmetric_and_radial<2>();
  gradient_antisymmetric_and_radial<3>();
}

// Kernel::evaluate, which the pair loops use for a whole particle's pairs at once, gives bitwise the
// values of W() and dWdr() one at a time: across the support, at its edge and beyond it.
template <int D> void batch_equals_pointwise() {
  SCOPED_TRACE("D = " + std::to_string(D));
  for (KernelType t : all_types()) {
    const Kernel<D> K(t, kH);
    const double R = K.support_radius();
    std::vector<double> r;
    for (int k = 0; k <= 1000; ++k) r.push_back(1.1 * R * k / 1000.0);
    r.insert(r.end(), {R, std::nextafter(R, 0.0), std::nextafter(R, 2.0 * R), kH, 2.0 * kH, 1e-300});
    std::vector<double> W(r.size()), dWdr(r.size());
    K.evaluate(r.size(), r.data(), W.data(), dWdr.data());
    for (std::size_t k = 0; k < r.size(); ++k) {
      EXPECT_EQ(W[k], K.W(r[k])) << K.name() << " r/R=" << r[k] / R;
      EXPECT_EQ(dWdr[k], K.dWdr(r[k])) << K.name() << " r/R=" << r[k] / R;
    }
  }
}

TEST(KernelProperties, BatchEvaluationEqualsThePointwiseOne) {
  batch_equals_pointwise<1>();
  batch_equals_pointwise<2>();
  batch_equals_pointwise<3>();
}

TEST(KernelNames, RoundTripAndUnknownThrows) {
  const auto& names = kernel_names();
  ASSERT_EQ(names.size(), 5u);
  for (std::size_t k = 0; k < names.size(); ++k) {
    EXPECT_EQ(kernel_type_from_name(names[k]), static_cast<KernelType>(k));
    EXPECT_EQ(Kernel<2>(static_cast<KernelType>(k), 1.0).name(), names[k]);
  }
  EXPECT_THROW(kernel_type_from_name("wendland_c6"), sph::Error);
  EXPECT_THROW(kernel_type_from_name(""), sph::Error);
  EXPECT_THROW(kernel_type_from_name("Cubic_Spline"), sph::Error);
  EXPECT_THROW(Kernel<2>(KernelType::WendlandC2, 0.0), sph::Error);
  EXPECT_THROW(Kernel<3>(KernelType::WendlandC2, -1.0), sph::Error);
}

TEST(KernelProperties, SelfSimilarInH) {
  // W(r, h) = h^-D W(r/h, 1): the same shape at every smoothing length.
  for (KernelType t : all_types()) {
    const Kernel<2> K1(t, 1.0), K2(t, 0.25);
    for (int k = 0; k < 100; ++k) {
      const double q = 3.0 * k / 100.0;
      EXPECT_NEAR(K2.W(0.25 * q), K1.W(q) / (0.25 * 0.25), 1e-12 * K1.W(0.0) / (0.25 * 0.25)) << K1.name();
      EXPECT_NEAR(K2.dWdr(0.25 * q), K1.dWdr(q) / (0.25 * 0.25 * 0.25), 1e-11 * K1.W(0.0) / 0.25 / 0.25 / 0.25)
          << K1.name();
    }
  }
}

}  // namespace

// The kernel sum over a lattice (what -ppe_density_relaxation compares a particle's number density
// with) is a midpoint rule for the kernel's integral, 1: it tends to 1 as the lattice refines against h,
// and equals the sum over explicit lattice points.
TEST(KernelProperties, LatticeSumTendsToTheIntegral) {
  for (KernelType type : all_types()) {
    const Kernel<2> K2(type, kH);
    const Kernel<3> K3(type, kH);
    double previous = 1.0;
    for (double ratio : {1.5, 3.0, 6.0}) {
      const double error = std::abs(lattice_kernel_sum(K2, kH / ratio) - 1.0);
      EXPECT_LT(error, std::max(previous, 1e-12)) << kernel_names()[static_cast<int>(type)] << " h/dx " << ratio;
      previous = error;
    }
    EXPECT_LT(previous, 1e-3) << kernel_names()[static_cast<int>(type)];
    EXPECT_LT(std::abs(lattice_kernel_sum(K3, kH / 6.0) - 1.0), 1e-3) << kernel_names()[static_cast<int>(type)];
    // Against the points themselves, 2D, h = 1.5 dx.
    const double dx = kH / 1.5;
    double sum = 0.0;
    for (int a = -10; a <= 10; ++a)
      for (int b = -10; b <= 10; ++b) sum += K2.W(std::hypot(a * dx, b * dx)) * dx * dx;
    EXPECT_NEAR(lattice_kernel_sum(K2, dx), sum, 1e-14);
  }
}
