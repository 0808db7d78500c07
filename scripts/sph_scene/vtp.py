"""Writing a Scene as the .vtp file that `sph -case scene -scene_file FILE` reads: point arrays kind,
velocity and pressure (and free_slip when a wall particle is free-slip), and the parameters as field
data."""
import vtk


def _point_arrays(scene):
    kind = vtk.vtkIntArray()
    kind.SetName("kind")
    velocity = vtk.vtkDoubleArray()
    velocity.SetName("velocity")
    velocity.SetNumberOfComponents(3)
    pressure = vtk.vtkDoubleArray()
    pressure.SetName("pressure")
    for v, p, k in zip(scene.v, scene.p, scene.kind):
        velocity.InsertNextTuple3(*v)
        pressure.InsertNextValue(p)
        kind.InsertNextValue(k)
    arrays = [kind, velocity, pressure]
    if any(scene.free_slip):
        free_slip = vtk.vtkIntArray()
        free_slip.SetName("free_slip")
        for f in scene.free_slip:
            free_slip.InsertNextValue(1 if f else 0)
        arrays.append(free_slip)
    return arrays


def _field_array(name, values):
    a = vtk.vtkDoubleArray()
    a.SetName(name)
    for value in values if isinstance(values, (list, tuple)) else [values]:
        a.InsertNextValue(float(value))
    return a


def _poly_data(scene):
    points = vtk.vtkPoints()
    points.SetDataTypeToDouble()
    verts = vtk.vtkCellArray()
    for i, x in enumerate(scene.x):
        points.InsertNextPoint(x)
        verts.InsertNextCell(1)
        verts.InsertCellPoint(i)
    poly = vtk.vtkPolyData()
    poly.SetPoints(points)
    poly.SetVerts(verts)
    for a in _point_arrays(scene):
        poly.GetPointData().AddArray(a)
    for name, values in scene.params.items():
        poly.GetFieldData().AddArray(_field_array(name, values))
    return poly


def write_vtp(scene, path):
    """Writes scene to path (binary VTK XML PolyData); raises OSError when VTK cannot write it."""
    poly = _poly_data(scene)
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(path)
    w.SetInputData(poly)
    w.SetDataModeToBinary()
    if w.Write() != 1:
        raise OSError(f"cannot write {path}; check that its folder exists and is writable")
