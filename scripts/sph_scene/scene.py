"""The scene model: particles (position, velocity, pressure, kind) and the parameters that the solver
reads from the file's field data."""

FLUID, WALL, MOVING = 0, 1, 2


def check_lattice(nx, wall_layers=1):
    """Refuses a lattice too coarse to hold a kernel support, or walls without a layer."""
    if nx < 4 or wall_layers < 1:
        raise ValueError("nx must be at least 4 and wall_layers at least 1")


class Scene:
    """Particles and the parameters written as field data.

    x and v hold one 3-tuple per particle (z = 0 in 2D), p one float, kind one of FLUID, WALL, MOVING,
    free_slip one bool (a wall particle without shear; written only when one is set); params maps
    field-data names (dx, box, periodic, gravity, nu, rho0, U, free_surface, t_end) to a number or a
    list of numbers."""

    def __init__(self, dim):
        self.dim = dim
        self.x, self.v, self.p, self.kind, self.free_slip = [], [], [], [], []
        self.params = {}

    def add(self, x, kind, v=None, p=0.0, free_slip=False):
        if free_slip and kind == FLUID:
            raise ValueError("free_slip marks wall particles only")
        self.x.append(tuple(x) + (0.0,) * (3 - len(x)))
        v = v or (0.0,) * self.dim
        self.v.append(tuple(v) + (0.0,) * (3 - len(v)))
        self.p.append(p)
        self.kind.append(kind)
        self.free_slip.append(bool(free_slip))

    def __len__(self):
        return len(self.kind)

    def counts(self):
        """(fluid, fixed wall, moving wall) particle counts."""
        return tuple(self.kind.count(k) for k in (FLUID, WALL, MOVING))

    def summary(self):
        fluid, wall, moving = self.counts()
        return (f"{len(self)} particles ({fluid} fluid, {wall} fixed wall, {moving} moving wall), "
                f"dx = {self.params['dx']:g}")

    def write(self, path):
        """Writes the scene as a VTK XML PolyData file; raises OSError when it cannot."""
        from .vtp import write_vtp  # imported here so that building a scene does not need vtk
        write_vtp(self, path)
