#!/usr/bin/python3
"""Writes a damaged copy of a good scene file, for the refusal tests.

usage: bad_scene.py GOOD.vtp OUT.vtp DEFECT   (DEFECT: no_kind, kind_5, nan, outside, no_fluid, no_dx)
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
else:
    sys.exit(f"bad_scene.py: unknown defect {defect}")
w = vtk.vtkXMLPolyDataWriter()
w.SetFileName(out)
w.SetInputData(poly)
sys.exit(0 if w.Write() == 1 else 1)
