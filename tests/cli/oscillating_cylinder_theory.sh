#!/usr/bin/env bash
# scripts/oscillating-cylinder-theory (docs/verification/body_forces.md, "Added mass and damping in
# viscous fluid"): its concentric-cylinder solution against the two limits it must reach, each from a
# formula of its own: Stokes' (1851) cylinder in unbounded fluid, 1 + 4 K1(l) / (l K0(l)), as the outer
# radius grows, and potential flow's (R2^2 + R1^2) / (R2^2 - R1^2) as nu falls; and the value the
# viscous added-mass test takes from it.
#   usage: oscillating_cylinder_theory.sh <sph executable (unused)> <source dir>
set -u
src="$2"
/usr/bin/python3 - "$src/scripts/oscillating-cylinder-theory" <<'PY'
import sys
from importlib.machinery import SourceFileLoader
import numpy as np

th = SourceFileLoader("oscillating_cylinder_theory", sys.argv[1]).load_module()
fail = False
w = 2 * np.pi

def check(what, ok, got):
    global fail
    print(("ok: " if ok else "FAIL: ") + what + ": " + str(got))
    fail |= not ok

for nu in (0.1, 0.01, 0.001):
    far = th.force_coefficient(nu, 0.2, 200.0, w)
    stokes = th.unbounded(nu, 0.2, w)
    check(f"outer radius 1000 R: Stokes' unbounded cylinder at nu {nu}", abs(far - stokes) < 1e-4 * abs(stokes), (far, stokes))
potential = (0.64 + 0.04) / (0.64 - 0.04)
thin = th.force_coefficient(1e-9, 0.2, 0.8, w)
check("nu -> 0: potential flow's C_m, no damping", abs(thin.real - potential) < 1e-3 and abs(thin.imag) < 1e-3, thin)
h = th.force_coefficient(0.01, 0.2, 0.8, w)
check("nu 0.01 (tests/test_moving_bodies.cpp): C_m 1.7787, C_d -0.7842",
      abs(h.real - 1.7787) < 1e-4 and abs(h.imag + 0.7842) < 1e-4, h)
sys.exit(1 if fail else 0)
PY
