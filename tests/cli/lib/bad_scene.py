#!/usr/bin/python3
"""Writes a damaged copy of a good scene file, for the refusal tests.

usage: bad_scene.py GOOD.vtp OUT.vtp DEFECT   (DEFECT: no_kind, kind_5, nan, outside, no_fluid, no_dx,
       Velocity, velocity_text, velocity_1, lid_normal, dx_inf, t_end_negative, free_slip_fluid,
       free_slip_2, dx_tiny, kind_3)
"""
import sys

import vtk

good, out, defect = sys.argv[1:4]
r = vtk.vtkXMLPolyDataReader()
r.SetFileName(good)
r.Update()
poly = r.GetOutput()
kind = poly.GetPointData().GetArray("kind")
if defect == "no_kind":
    poly.GetPointData().RemoveArray("kind")
elif defect == "kind_5":
    kind.SetValue(3, 5)
elif defect == "nan":
    poly.GetPoints().SetPoint(7, float("nan"), 0.5, 0.0)
elif defect == "outside":
    poly.GetPoints().SetPoint(7, 100.0, 0.5, 0.0)
elif defect == "no_fluid":
    for i in range(kind.GetNumberOfTuples()):
        kind.SetValue(i, 1)
elif defect == "no_dx":
    poly.GetFieldData().RemoveArray("dx")
elif defect == "Velocity":
    poly.GetPointData().GetArray("velocity").SetName("Velocity")
elif defect in ("velocity_text", "velocity_1"):
    n = kind.GetNumberOfTuples()
    a = vtk.vtkStringArray() if defect == "velocity_text" else vtk.vtkDoubleArray()
    a.SetNumberOfValues(n)
    for i in range(n):
        a.SetValue(i, "1" if defect == "velocity_text" else 1.0)
    poly.GetPointData().RemoveArray("velocity")
    a.SetName("velocity")
    poly.GetPointData().AddArray(a)
elif defect == "lid_normal":  # the lid pushed down into the fluid instead of sliding
    v = poly.GetPointData().GetArray("velocity")
    for i in range(kind.GetNumberOfTuples()):
        if kind.GetValue(i) == 2:
            v.SetTuple3(i, 0.0, -1.0, 0.0)
elif defect in ("dx_inf", "t_end_negative", "dx_tiny"):
    name, value = {"dx_inf": ("dx", float("inf")), "dx_tiny": ("dx", 1e-6), "t_end_negative": ("t_end", -1.0)}[defect]
    poly.GetFieldData().RemoveArray(name)
    a = vtk.vtkDoubleArray()
    a.SetName(name)
    a.InsertNextValue(value)
    poly.GetFieldData().AddArray(a)
elif defect in ("free_slip_fluid", "free_slip_2"):  # a slip flag on a fluid particle, or not 0 or 1
    a = vtk.vtkIntArray()
    a.SetName("free_slip")
    for i in range(kind.GetNumberOfTuples()):
        a.InsertNextValue(0)
    fluid = next(i for i in range(kind.GetNumberOfTuples()) if kind.GetValue(i) == 0)
    wall = next(i for i in range(kind.GetNumberOfTuples()) if kind.GetValue(i) == 1)
    a.SetValue(fluid, 1) if defect == "free_slip_fluid" else a.SetValue(wall, 2)
    poly.GetPointData().AddArray(a)
elif defect == "kind_3":  # kind as a vector, e.g. written by a tool that pads every array to 3
    a = vtk.vtkDoubleArray()
    a.SetNumberOfComponents(3)
    for i in range(kind.GetNumberOfTuples()):
        a.InsertNextTuple3(kind.GetValue(i), 0.0, 0.0)
    poly.GetPointData().RemoveArray("kind")
    a.SetName("kind")
    poly.GetPointData().AddArray(a)
else:
    sys.exit(f"bad_scene.py: unknown defect {defect}")
w = vtk.vtkXMLPolyDataWriter()
w.SetFileName(out)
w.SetInputData(poly)
sys.exit(0 if w.Write() == 1 else 1)
