"""Free-surface scenes: water in tanks under gravity (g = 1, rho0 = 1), with hydrostatic pressure in
the water at rest."""
import math

from .scene import FLUID, WALL, Scene, check_lattice


def dam_break(nx=20, wall_layers=4, re=1000.0, obstacle=True):
    """Water column a x 2a in a 4a tank with a block obstacle on the floor (obstacle=False: the built-in
    -case dam_break, particle for particle); nx particles across the column, Re = sqrt(g a^3) / nu."""
    check_lattice(nx, wall_layers)
    # The same lattice, order and values as cases/dam_break/dam_break.cpp (a = 1, g = 1, rho0 = 1).
    a, g, rho0 = 1.0, 1.0, 1.0
    n, L = nx, wall_layers
    dx = a / n
    tank, height = 4 * n, 3 * n
    s = Scene(2)
    # Obstacle: a block 0.5a wide, 0.5a high on the floor, 2.5a-3a from the left wall.
    block = range(int(2.5 * n), 3 * n) if obstacle else range(0)
    for j in range(-L, height):
        for i in range(-L, tank + L):
            x = ((i + 0.5) * dx, (j + 0.5) * dx)
            wall = j < 0 or i < 0 or i >= tank or (i in block and j < n // 2)
            fluid = not wall and i < n and j < 2 * n
            if not wall and not fluid:
                continue
            p = rho0 * g * (2.0 * a - x[1]) if fluid else 0.0
            s.add(x, WALL if wall else FLUID, p=p)
    # Room beside and below the tank for the run-up that flies over a side wall, as -case dam_break.
    box = [-L * dx - 20.0 * a, (tank + L) * dx + 20.0 * a, -L * dx - 100.0 * a, 20.0 * a]
    s.params = {"dx": dx, "box": box, "periodic": [0, 0],
                "gravity": [0.0, -g], "nu": math.sqrt(g * a * a * a) / re, "rho0": rho0,
                "U": math.sqrt(2.0 * g * 2.0 * a), "free_surface": 1, "t_end": 3.0 * math.sqrt(a / (2.0 * g))}
    return s


def sloshing(nx=40, wall_layers=4, re=1000.0, tilt=math.degrees(math.atan(0.1))):
    """Tank 1 wide with water 0.5 deep, its surface tilted by `tilt` degrees (default atan 0.1: +-0.05 at
    the walls) and released from rest: the first sloshing mode; nx particles across the tank."""
    check_lattice(nx, wall_layers)
    # Side walls 1.5 high.
    n, L, g, depth, slope = nx, wall_layers, 1.0, 0.5, math.tan(math.radians(tilt))
    dx = 1.0 / n
    s = Scene(2)
    for j in range(-L, int(1.5 * n)):
        for i in range(-L, n + L):
            x = ((i + 0.5) * dx, (j + 0.5) * dx)
            surface = depth + slope * (x[0] - 0.5)
            wall = j < 0 or i < 0 or i >= n
            if wall:
                s.add(x, WALL)
            elif x[1] < surface:
                s.add(x, FLUID, p=g * (surface - x[1]))
    # First mode: omega^2 = g k tanh(k h), k = pi / width; four periods.
    k = math.pi
    period = 2 * math.pi / math.sqrt(g * k * math.tanh(k * depth))
    s.params = {"dx": dx, "box": [-20.0 - L * dx, 21.0 + L * dx, -150.0, 20.0], "periodic": [0, 0], "gravity": [0.0, -g],
                "nu": math.sqrt(g) / re, "rho0": 1.0, "U": math.sqrt(g * depth), "t_end": 4 * period}
    return s


def tank(n, L, width, wall_height, inside_solid, fluid_at, pressure_at, params, roof=False):
    """A tank `width` wide with floor and side walls of L layers up to `wall_height`, open at the top (or
    closed by a roof of L layers), n particles per unit length; a lattice point is wall where
    inside_solid(x) (obstacles), fluid where fluid_at(x) with pressure pressure_at(x)."""
    check_lattice(n, L)
    dx = 1.0 / n
    s = Scene(2)
    cols, rows = int(round(width * n)), int(round(wall_height * n))
    for j in range(-L, rows + (L if roof else 0)):
        for i in range(-L, cols + L):
            x = ((i + 0.5) * dx, (j + 0.5) * dx)
            if j < 0 or j >= rows or i < 0 or i >= cols or inside_solid(x):
                s.add(x, WALL)
            elif fluid_at(x):
                s.add(x, FLUID, p=pressure_at(x))
    # Room for what splashes over the walls of an open tank: 20 tank widths on either side and far below,
    # where a drop thrown out falls freely until the end of the run (a fluid particle leaving the box stops
    # it). The box costs nothing: the neighbour search is a tree over the particles, not a grid over the box.
    if roof:
        box = [-L * dx, width + L * dx, -L * dx, wall_height + L * dx]
    else:
        box = [-L * dx - 20.0 * width, 21.0 * width + L * dx, -100.0 * wall_height, 20.0 * wall_height]
    s.params = {"dx": dx, "box": box, "periodic": [0, 0], "free_surface": 1}
    s.params.update(params)
    return s


def falling_block(nx=40, wall_layers=4, re=500.0, obstacle_shape="cylinder"):
    """Block of water 0.4 x 0.3 at rest above a fixed obstacle ("cylinder" of radius 0.12 at (0.5, 0.45),
    or "wedge" with its apex up), over a pool 0.15 deep in a tank 1 wide and 1.3 tall."""
    g, pool = 1.0, 0.15
    if obstacle_shape == "cylinder":
        def solid(x):
            return math.hypot(x[0] - 0.5, x[1] - 0.45) <= 0.12
    elif obstacle_shape == "wedge":  # apex (0.5, 0.55), base 0.3 wide at y = 0.35
        def solid(x):
            return 0.35 <= x[1] <= 0.55 and abs(x[0] - 0.5) <= 0.75 * (0.55 - x[1])
    else:
        raise ValueError(f"obstacle_shape must be 'cylinder' or 'wedge', not {obstacle_shape!r}")

    def block(x):
        return 0.3 <= x[0] <= 0.7 and 0.75 <= x[1] <= 1.05
    return tank(nx, wall_layers, 1.0, 1.3, solid, lambda x: x[1] < pool or block(x),
                lambda x: g * (pool - x[1]) if x[1] < pool else 0.0,
                {"gravity": [0.0, -g], "nu": 1.0 / re, "rho0": 1.0, "t_end": 4.0})


def column_drop(nx=40, wall_layers=4, re=500.0):
    """Column of water 0.2 wide and 0.4 tall, its foot 0.2 above a pool 0.3 deep, in a tank 1 wide, 1.2 tall."""
    g, pool = 1.0, 0.3

    def column(x):
        return abs(x[0] - 0.5) <= 0.1 and 0.5 <= x[1] <= 0.9
    return tank(nx, wall_layers, 1.0, 1.2, lambda x: False, lambda x: x[1] < pool or column(x),
                lambda x: g * (pool - x[1]) if x[1] < pool else 0.0,
                {"gravity": [0.0, -g], "nu": 1.0 / re, "rho0": 1.0, "t_end": 4.0})


def dam_break_block(nx=40, wall_layers=4, re=500.0):
    """Column 0.5 wide and 1 tall at the left of a closed tank 2 wide and 1.5 tall (as the tank of Kleefsman
    et al. 2005), rushing onto a tall block (0.2 wide, 0.4 tall) on the floor at x = 1.2-1.4."""
    g = 1.0

    def solid(x):
        return 1.2 <= x[0] <= 1.4 and x[1] <= 0.4
    return tank(nx, wall_layers, 2.0, 1.5, solid, lambda x: x[0] < 0.5 and x[1] < 1.0,
                lambda x: g * (1.0 - x[1]), {"gravity": [0.0, -g], "nu": 1.0 / re, "rho0": 1.0, "t_end": 6.0},
                roof=True)


def still_water(nx=40, wall_layers=4, re=500.0, side_walls=True, lattice="square"):
    """Tank 1 wide with water 0.5 deep at rest under hydrostatic pressure; the walls 0.7 high. Without
    side walls: a strip about 1 wide, periodic in x, on the same floor. The fluid on a square lattice,
    or a hexagonal one (strip only: its rows do not fit square side walls) with the same area per particle."""
    g, depth = 1.0, 0.5
    params = {"gravity": [0.0, -g], "nu": 1.0 / re, "rho0": 1.0, "U": math.sqrt(2.0 * g * depth), "t_end": 20.0}
    if side_walls and lattice == "square":
        return tank(nx, wall_layers, 1.0, 0.7, lambda x: False, lambda x: x[1] < depth,
                    lambda x: g * (depth - x[1]), params)
    if side_walls:
        raise ValueError("a hexagonal lattice needs the strip without side walls (--no-side-walls)")
    check_lattice(nx, wall_layers)
    dx = 1.0 / nx
    if lattice == "hexagonal":
        a = dx * math.sqrt(2.0 / math.sqrt(3.0))  # spacing along a row: dx^2 per particle
        b = a * math.sqrt(3.0) / 2.0              # between rows
        cols, rows = int(round(1.0 / a)), int(round((depth - 0.5 * dx) / b)) + 1
        width, level = cols * a, 0.5 * dx + (rows - 0.5) * b
        fluid = [((i + 0.25 + 0.5 * (j % 2)) * a, 0.5 * dx + j * b) for j in range(rows) for i in range(cols)]
    elif lattice == "square":
        cols, rows = nx, int(round(depth * nx))
        width, level = 1.0, rows * dx
        fluid = [((i + 0.5) * dx, (j + 0.5) * dx) for j in range(rows) for i in range(cols)]
    else:
        raise ValueError(f"lattice must be 'square' or 'hexagonal', not {lattice!r}")
    s = Scene(2)
    floor = int(round(width / dx))  # the floor's spacing along x fits the periodic width
    for j in range(-wall_layers, 0):
        for i in range(floor):
            s.add(((i + 0.5) * width / floor, (j + 0.5) * dx), WALL)
    for x in fluid:
        s.add(x, FLUID, p=g * (level - x[1]))
    s.params = {"dx": dx, "box": [0.0, width, -wall_layers * dx, 20.0 * depth], "periodic": [1, 0], "free_surface": 1}
    s.params.update(params)
    return s
