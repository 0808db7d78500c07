"""Scenes without a free surface: the periodic array of cylinders and the lid-driven cavity."""
import math

from .scene import FLUID, MOVING, WALL, Scene, check_lattice


def cylinders(nx=30, force=1.0):
    """Periodic square array of cylinders (cell 1, radius 0.2), flow driven by a body force `force` along x,
    at low Reynolds number (Morris, Fox & Zhu 1997); nx particles across the cell."""
    check_lattice(nx)
    # nu = 1 and g = 1: mean speed ~0.03, Re = U L / nu ~ 0.03.
    n, cell, radius, nu, g = nx, 1.0, 0.2, 1.0, force
    dx = cell / n
    s = Scene(2)
    for j in range(n):
        for i in range(n):
            x = ((i + 0.5) * dx, (j + 0.5) * dx)
            inside = math.hypot(x[0] - 0.5 * cell, x[1] - 0.5 * cell) <= radius
            s.add(x, WALL if inside else FLUID)
    # U: a few times the mean speed of Sangani & Acrivos (1982) at this solid fraction.
    s.params = {"dx": dx, "box": [0.0, cell, 0.0, cell], "periodic": [1, 1], "gravity": [g, 0.0], "nu": nu,
                "rho0": 1.0, "U": 0.1 * g * cell * cell / nu, "free_surface": 0, "t_end": 0.5 * cell * cell / nu}
    return s


def cavity(nx=50, wall_layers=4, re=100.0, dim=2):
    """Unit cavity (dim 2 or 3) under a lid sliding at U = 1 along x (moving-wall particles), Re = U / nu;
    nx particles across."""
    check_lattice(nx, wall_layers)
    # As -case lid_driven_cavity: the corner block above the upstream wall moves with the lid (why:
    # cases/lid_driven_cavity).
    n, L, U = nx, wall_layers, 1.0
    dx = 1.0 / n
    s = Scene(dim)
    rng = range(-L, n + L)
    for k in rng if dim == 3 else [0]:
        for j in rng:
            for i in rng:
                x = ((i + 0.5) * dx, (j + 0.5) * dx) + (((k + 0.5) * dx,) if dim == 3 else ())
                up = (j if dim == 2 else k)  # the lid's normal axis: y in 2D, z in 3D
                inside = all(0 <= c < n for c in ((i, j, k) if dim == 3 else (i, j)))
                if inside:
                    s.add(x, FLUID)
                elif up >= n and i < n:
                    s.add(x, MOVING, v=(U,) + (0.0,) * (dim - 1))
                else:
                    s.add(x, WALL)
    s.params = {"dx": dx, "box": [-L * dx, 1.0 + L * dx] * dim, "periodic": [0] * dim, "nu": U / re,
                "rho0": 1.0, "U": U, "free_surface": 0, "t_end": 40.0}
    return s
