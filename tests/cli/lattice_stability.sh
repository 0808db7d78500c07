#!/usr/bin/env bash
# scripts/lattice-stability (docs/verification/free_surface.md, "What moves WCSPH's lattice"):
# its linearised dynamical matrix D(k) against the pair forces of a displaced square lattice summed
# directly (central differences in the displacement; only the first derivative of the kernel), and the signs the page relies on: a growing
# mode at a support of 3 dx in 2D and 3D, none at 2.77 dx in 2D and 2.84 dx in 3D.
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
sys.exit(1 if fail else 0)
PY
