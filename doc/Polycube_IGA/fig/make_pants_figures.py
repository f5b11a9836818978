#!/usr/bin/python3
# Copyright (c) 2026 Polycube_IGA contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Figures of the manual's pants section: `polycube_iga pants MESH --vtk OUT.vtu` on
# eight.off and 3holes.obj, rendered off screen with Debian's python3-vtk9 (faces coloured
# by pants, handle loops red, cuts yellow, input boundary loops blue).
#
#   /usr/bin/python3 doc/Polycube_IGA/fig/make_pants_figures.py [build/bin/polycube_iga]
#
# Without a display it runs itself again under xvfb-run (Debian package xvfb). Not used by
# the tests.

import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
DATA = os.path.join(ROOT, "test", "Polycube_IGA", "data")
# (mesh, figure, direction from the centre to the camera, view up)
FIGURES = [("eight.off", "pants_eight.png", (0.35, -1.0, 0.25), (1, 0, 0)),
           ("3holes.obj", "pants_3holes.png", (0.4, -1.0, 1.4), (0, 0, 1))]
PANTS_COLOURS = [(0.55, 0.71, 0.86), (0.96, 0.65, 0.45), (0.60, 0.82, 0.55), (0.80, 0.62, 0.85),
                 (0.93, 0.85, 0.50), (0.62, 0.85, 0.85), (0.90, 0.60, 0.65), (0.75, 0.75, 0.75)]
KIND_COLOURS = {0: (0.1, 0.2, 0.9), 1: (0.85, 0.05, 0.05), 2: (1.0, 0.85, 0.0)}


def render(vtu, png, view, up):
    import vtk
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(vtu)
    reader.Update()
    grid = reader.GetOutput()
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)

    def part(array, lo, hi):
        t = vtk.vtkThreshold()
        t.SetInputData(grid)
        t.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS, array)
        t.SetLowerThreshold(lo)
        t.SetUpperThreshold(hi)
        t.SetThresholdFunction(vtk.vtkThreshold.THRESHOLD_BETWEEN)
        s = vtk.vtkGeometryFilter()
        s.SetInputConnection(t.GetOutputPort())
        s.Update()
        return s

    pants = part("pants", 0, 1e9)
    count = int(grid.GetCellData().GetArray("pants").GetRange()[1]) + 1
    table = vtk.vtkLookupTable()
    table.SetNumberOfTableValues(count)
    table.SetTableRange(0, count - 1)
    for k in range(count):
        table.SetTableValue(k, *PANTS_COLOURS[k % len(PANTS_COLOURS)], 1.0)
    table.Build()
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputConnection(pants.GetOutputPort())
    normals.SetFeatureAngle(60)
    surface = vtk.vtkPolyDataMapper()
    surface.SetInputConnection(normals.GetOutputPort())
    surface.SetScalarModeToUseCellFieldData()
    surface.SelectColorArray("pants")
    surface.SetLookupTable(table)
    surface.SetScalarRange(0, count - 1)
    surface.SetColorModeToMapScalars()
    actor = vtk.vtkActor()
    actor.SetMapper(surface)
    renderer.AddActor(actor)

    bounds = grid.GetBounds()
    diagonal = sum((bounds[2 * i + 1] - bounds[2 * i]) ** 2 for i in range(3)) ** 0.5
    for kind, colour in KIND_COLOURS.items():
        lines = part("kind", kind, kind)
        if lines.GetOutput().GetNumberOfCells() == 0:
            continue
        tube = vtk.vtkTubeFilter()
        tube.SetInputConnection(lines.GetOutputPort())
        tube.SetRadius(0.006 * diagonal)
        tube.SetNumberOfSides(12)
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputConnection(tube.GetOutputPort())
        mapper.ScalarVisibilityOff()
        a = vtk.vtkActor()
        a.SetMapper(mapper)
        a.GetProperty().SetColor(*colour)
        renderer.AddActor(a)

    camera = renderer.GetActiveCamera()
    centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    camera.SetFocalPoint(*centre)
    camera.SetPosition(*[centre[i] + view[i] * diagonal for i in range(3)])
    camera.SetViewUp(*up)
    renderer.ResetCamera()
    camera.Zoom(1.3)

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.AddRenderer(renderer)
    window.SetSize(800, 600)
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    image.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(png)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()


def main():
    if not os.environ.get("DISPLAY") and not os.environ.get("POLYCUBE_IGA_FIG_NO_XVFB"):
        env = dict(os.environ, POLYCUBE_IGA_FIG_NO_XVFB="1")
        sys.exit(subprocess.call(["xvfb-run", "-a", "-s", "-screen 0 1024x768x24", sys.executable] + sys.argv, env=env))
    cli = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "bin", "polycube_iga")
    with tempfile.TemporaryDirectory() as tmp:
        for mesh, png, view, up in FIGURES:
            vtu = os.path.join(tmp, os.path.splitext(png)[0] + ".vtu")
            subprocess.run([cli, "pants", os.path.join(DATA, mesh), "--vtk", vtu], check=True, stdout=subprocess.DEVNULL)
            render(vtu, os.path.join(HERE, png), view, up)
            print(os.path.join(HERE, png))


if __name__ == "__main__":
    main()
