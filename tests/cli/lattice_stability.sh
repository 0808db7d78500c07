#!/usr/bin/env bash
# scripts/lattice-stability (docs/verification/free_surface.md, "What moves WCSPH's lattice"):
# its linearised dynamical matrix D(k) against the pair forces of a displaced square lattice summed
# directly (central differences in the displacement; only the first derivative of the kernel), and the signs the page relies on: a growing
# mode at a support of 3 dx in 2D and 3D, none at 2.77 dx in 2D and 2.84 dx in 3D; on the hexagonal
# lattice none with Wendland C4 at 3 dx, one with Wendland C2; the quintic spline holds the square and
# simple cubic lattices at 2.79 dx, not at 3.
#   usage: lattice_stability.sh <sph executable (unused)> <source dir>
set -u
src="$2"
/usr/bin/python3 - "$src/scripts/lattice-stability" <<'PY'
import sys
from importlib.machinery import SourceFileLoader
import numpy as np

ls = SourceFileLoader("lattice_stability", sys.argv[1]).load_module()
fail = False

# Direct sum: displace site j by eps e cos(k.r_j), sum phi(r) (x_0 - x_j) / r on site 0.
support, h = 3.0, 1.5
phi = lambda r: -ls.wendland_c2_derivatives(r / h)[0] / h  # its second derivative is what D(k) adds
for k, e in [((0.0, 1.41), (1.0, 0.0)), ((0.9, 0.4), (0.6, 0.8))]:
    k, e = np.array(k), np.array(e)
    def force(eps):
        f = np.zeros(2)
        x0 = eps * e
        for v, _, _ in ls.neighbours(support, 2):
            d = x0 - (v + eps * e * np.cos(k @ v))
            r = np.linalg.norm(d)
            f += phi(r) * d / r
        return f
    eps = 1e-5
    direct = (force(eps) - force(-eps)) / (2 * eps)
    linear = -ls.dynamical(ls.neighbours(support, 2), k) @ e
    err = np.linalg.norm(direct - linear) / np.linalg.norm(linear)
    ok = err < 1e-5
    fail |= not ok
    print(("ok" if ok else "FAIL") + f": D(k) e against the direct sum at k = {k}: relative difference {err:.1e}")

for dim, stable, unstable in [(2, 2.77, 3.0), (3, 2.84, 3.0)]:
    m = 48 if dim == 2 else 12
    lo = ls.smallest_eigenvalue(ls.neighbours(stable, dim), dim, m)
    hi = ls.smallest_eigenvalue(ls.neighbours(unstable, dim), dim, m)
    ok = lo >= 0.0 and hi < -1e-3
    fail |= not ok
    print(("ok" if ok else "FAIL") + f": {dim}D smallest eigenvalue {lo:+.4f} at {stable} dx, {hi:+.4f} at {unstable} dx")
# The other kernels' derivatives by finite differences: checked on Wendland C2 against its analytic ones.
q = np.linspace(0.05, 1.95, 39)
W = ls.KERNELS["wendland_c2"][0]
e = 1e-4
d1 = (W(q - 2 * e) - 8 * W(q - e) + 8 * W(q + e) - W(q + 2 * e)) / (12 * e)
d2 = (-W(q - 2 * e) + 16 * W(q - e) - 30 * W(q) + 16 * W(q + e) - W(q + 2 * e)) / (12 * e * e)
a1, a2 = ls.wendland_c2_derivatives(q)
err = max(np.max(np.abs(d1 - a1)), np.max(np.abs(d2 - a2))) / np.max(np.abs(a2))
ok = err < 1e-6
fail |= not ok
print(("ok" if ok else "FAIL") + f": finite-difference kernel derivatives against Wendland C2's: {err:.1e}")

# The hexagonal lattice (2D, one particle per dx^2): Wendland C4 holds at 3 dx, Wendland C2 does not.
for kernel, want_stable in [("wendland_c4", True), ("wendland_c2", False)]:
    lam = ls.smallest_eigenvalue(ls.neighbours(3.0, 2, kernel, "hexagonal"), 2, 48, "hexagonal")
    ok = (lam >= 0.0) if want_stable else (lam < -1e-3)
    fail |= not ok
    print(("ok" if ok else "FAIL") + f": hexagonal lattice, {kernel}, 3 dx: smallest eigenvalue {lam:+.4f}")

# The quintic spline's stable window: at 2.79 dx (h = 0.93 dx) it holds the square and simple cubic
# lattices, at 3 dx (h = 1) it does not (docs/verification/free_surface.md).
for dim, support, want_stable in [(2, 2.79, True), (3, 2.79, True), (2, 3.0, False)]:
    lam = ls.smallest_eigenvalue(ls.neighbours(support, dim, "quintic_spline"), dim, 48 if dim == 2 else 13)
    ok = (lam >= 0.0) if want_stable else (lam < -1e-3)
    fail |= not ok
    print(("ok" if ok else "FAIL") + f": square lattice, quintic_spline, {dim}D, {support} dx: smallest eigenvalue {lam:+.4f}")

# The same flatness of the kernel sum that leaves the window's lattice without shear stiffness leaves a
# wall of particles without a barrier: the quintic spline's corrugation at 2.79 dx is under a tenth of
# Wendland C2's at 3 dx (the fluid leaked through a sloshing tank's corner with it).
wc2, q = ls.wall_corrugation(3.0, "wendland_c2"), ls.wall_corrugation(2.79, "quintic_spline")
ok = wc2 > 0 and abs(q) < 0.1 * wc2
fail |= not ok
print(("ok" if ok else "FAIL") + f": wall corrugation, Wendland C2 at 3 dx {wc2:+.1e}, quintic spline at 2.79 dx {q:+.1e}")
sys.exit(1 if fail else 0)
PY
