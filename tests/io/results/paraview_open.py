# SPDX-License-Identifier: GPL-3.0-or-later
# Run by pvbatch from tests/io/results/test_paraview.cpp: opens a femdem results.xdmf with ParaView's XDMF
# reader and prints what a user would see: time steps, cell type, fields and their ranges.
import sys

from paraview import servermanager
from paraview.simple import XDMFReader

r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipelineInformation()
ts = list(r.TimestepValues)
r.UpdatePipeline(ts[-1])
d = servermanager.Fetch(r)
print("timesteps", len(ts))
print("last_time", ts[-1])
print("cells", d.GetNumberOfCells())
print("points", d.GetNumberOfPoints())
print("cell_type", d.GetCellType(0))
for data in (d.GetPointData(), d.GetCellData()):
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        print("array", a.GetName(), a.GetNumberOfComponents(), a.GetRange(-1)[1])
