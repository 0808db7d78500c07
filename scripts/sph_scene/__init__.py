"""Scenes for `sph -case scene -scene_file FILE`: lattice particles, walls thick enough for the kernel,
and the scene's parameters as field data. scripts/make-scene is the command line over this package.

    import sys; sys.path.insert(0, "scripts")
    from sph_scene import falling_block
    scene = falling_block(nx=40, obstacle_shape="wedge")   # a Scene: x, v, p, kind, params
    scene.params["t_end"] = 2.0
    scene.write("block.vtp")                               # needs vtk (python3-vtk9, scripts/install-deps)

    scene.py   the Scene (particles, kinds FLUID / WALL / MOVING, parameters)
    flows.py   cylinders, cavity (no free surface)
    tanks.py   dam_break, sloshing, falling_block, column_drop, dam_break_block, still_water, and tank()
               for tanks of one's own
    vtp.py     write_vtp: a Scene as VTK XML PolyData
"""
from .flows import cavity, cylinders
from .scene import FLUID, MOVING, WALL, Scene, check_lattice
from .tanks import column_drop, dam_break, dam_break_block, falling_block, sloshing, still_water, tank

__all__ = ["FLUID", "WALL", "MOVING", "Scene", "check_lattice", "tank", "SCENES", "cavity", "cylinders", "column_drop",
           "dam_break", "dam_break_block", "falling_block", "sloshing", "still_water"]

# The scenes by the name the command line gives them.
SCENES = {"dam_break": dam_break, "cylinders": cylinders, "sloshing": sloshing, "cavity": cavity,
          "falling_block": falling_block, "column_drop": column_drop, "dam_break_block": dam_break_block,
          "still_water": still_water}
