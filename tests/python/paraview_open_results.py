# SPDX-License-Identifier: GPL-3.0-or-later
"""Run by ParaView's pvbatch (under xvfb-run) from test_paraview.py: opens a femdem run's
results.xdmf with ParaView's default reader (what File > Open picks), both Xdmf3 readers and the
legacy XDMF reader, and checks what each shows against the expectations in EXPECTED_JSON
(written by test_paraview.py from results.h5): the time steps, every field with its range in the
last frame, quadratic tetrahedra. Renders the last frame, warped by its displacement, to PNG.

    pvbatch paraview_open_results.py RESULTS_XDMF EXPECTED_JSON OUT_PNG [WALLS_XDMF WALLS]
With WALLS_XDMF, also opens that walls.xdmf with the default reader: WALLS quadrilaterals with
the cell fields `wall` and `force`, drawn beside the bodies in the PNG.
Prints one line per reader and exits 1 on the first reader that does not show everything.
"""
import json
import sys

from paraview import servermanager
from paraview.simple import (ColorBy, GetActiveViewOrCreate, OpenDataFile, Render,
                             ResetCamera, SaveScreenshot, Show, WarpByVector, XDMFReader,
                             Xdmf3ReaderS, Xdmf3ReaderT)

VTK_QUADRATIC_TETRA = 24
VTK_QUAD = 9


def first_grid(data):
    """The unstructured grid of a reader's output (the readers differ in wrapping it)."""
    if data.IsA("vtkUnstructuredGrid"):
        return data
    if data.IsA("vtkCompositeDataSet"):
        it = data.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            block = it.GetCurrentDataObject()
            if block is not None and block.IsA("vtkUnstructuredGrid"):
                return block
            it.GoToNextItem()
    raise RuntimeError(f"no unstructured grid in a {data.GetClassName()}")


def check(label, reader, expected):
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    if times != expected["times"]:
        raise RuntimeError(f"{label}: time steps {times}, expected {expected['times']}")
    reader.UpdatePipeline(times[-1])
    grid = first_grid(servermanager.Fetch(reader))
    if grid.GetNumberOfCells() != expected["elements"]:
        raise RuntimeError(f"{label}: {grid.GetNumberOfCells()} cells")
    if grid.GetCellType(0) != VTK_QUADRATIC_TETRA:
        raise RuntimeError(f"{label}: cell type {grid.GetCellType(0)}, not a quadratic tetra")
    for centre, arrays in (("point", grid.GetPointData()), ("cell", grid.GetCellData())):
        for name, (lo, hi, comps) in expected[centre].items():
            a = arrays.GetArray(name)
            if a is None:
                raise RuntimeError(f"{label}: no {centre} array {name}")
            if a.GetNumberOfComponents() != comps:
                raise RuntimeError(f"{label}: {name} has {a.GetNumberOfComponents()} components")
            got = a.GetRange(0)  # first component, last frame
            tol = 1e-6 * max(abs(lo), abs(hi), 1e-300)
            if abs(got[0] - lo) > tol or abs(got[1] - hi) > tol:
                raise RuntimeError(f"{label}: {name} range {got}, expected {(lo, hi)}")
    print(f"{label}: {len(times)} steps, {grid.GetNumberOfCells()} quadratic tetra, "
          f"point {sorted(expected['point'])}, cell {sorted(expected['cell'])}: as in results.h5",
          flush=True)
    return times[-1]


def check_walls(xdmf, count, times):
    reader = OpenDataFile(xdmf)
    reader.UpdatePipelineInformation()
    if list(reader.TimestepValues) != times:
        raise RuntimeError(f"walls: time steps {list(reader.TimestepValues)}, expected {times}")
    reader.UpdatePipeline(times[-1])
    grid = first_grid(servermanager.Fetch(reader))
    if grid.GetNumberOfCells() != count or grid.GetCellType(0) != VTK_QUAD:
        raise RuntimeError(f"walls: {grid.GetNumberOfCells()} cells of type {grid.GetCellType(0)}")
    for name, comps in (("wall", 1), ("force", 3)):
        a = grid.GetCellData().GetArray(name)
        if a is None or a.GetNumberOfComponents() != comps:
            raise RuntimeError(f"walls: no cell array {name} of {comps} components")
    print(f"walls ({reader.GetXMLName()}): {len(times)} steps, {count} quadrilaterals, "
          "cell wall and force", flush=True)
    return reader


def main():
    xdmf, expected_json, png = sys.argv[1:4]
    with open(expected_json) as f:
        expected = json.load(f)
    default = OpenDataFile(xdmf)
    print(f"default reader: {default.GetXMLName()}", flush=True)
    last = check("default (" + default.GetXMLName() + ")", default, expected)
    check("Xdmf3ReaderS", Xdmf3ReaderS(FileName=[xdmf]), expected)
    check("Xdmf3ReaderT", Xdmf3ReaderT(FileName=[xdmf]), expected)
    check("XDMFReader (legacy)", XDMFReader(FileNames=[xdmf]), expected)
    warp = WarpByVector(Input=default, Vectors=["POINTS", "displacement"])
    view = GetActiveViewOrCreate("RenderView")
    view.ViewTime = last
    shown = Show(warp, view)
    ColorBy(shown, ("POINTS", "velocity", "Magnitude"))
    shown.RescaleTransferFunctionToDataRange(True)
    if len(sys.argv) > 5:
        walls = check_walls(sys.argv[4], int(sys.argv[5]), expected["times"])
        Show(walls, view).Opacity = 0.3
    view.CameraPosition = [5.0, -20.0, 8.0]
    view.CameraFocalPoint = [5.0, 0.5, 0.5]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    ResetCamera(view)
    Render(view)
    SaveScreenshot(png, view, ImageResolution=[640, 480])
    print(f"rendered t = {last} to {png}", flush=True)


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # pvbatch exits 0 on an uncaught exception: say it and fail
        print(f"FAILED: {e}", flush=True)
        sys.exit(1)
