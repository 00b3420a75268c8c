"""ParaView test of the plugin's readers, display defaults and failures (pvbatch / pvpython).

    pvbatch TestGPUDelaunayReaders.py --plugin <GPUDelaunayRefinement.so> --input <Data dir>
            --outdir <dir>     (PYTHONPATH=<build>/python for gpudelaunay.update_pipeline)

OpenDataFile opens Triangle and TetGen files with the plugin's readers (a .poly is 2D or 3D
by its content), the file's holes and regions reach the filters, the 2D mesh is shown as
Surface With Edges coloured by MinAngle, and a failed run raises in the script while
UpdatePipeline alone returns quietly.
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plugin_test_support import check, check_documented, parse_args  # noqa: E402


def total(proxy, name, port=0):
    data = servermanager.Fetch(proxy, idx=port) if port else servermanager.Fetch(proxy)
    array = data.GetCellData().GetArray(name)
    return sum(array.GetValue(i) for i in range(array.GetNumberOfTuples()))


def main():
    args = parse_args()
    data = args.input
    LoadPlugin(args.plugin, remote=False, ns=globals())
    import gpudelaunay

    # Triangle .poly: a PSLG with its hole; the 2D filter honours the hole from the file.
    pslg = OpenDataFile(os.path.join(data, "square_hole.poly"))
    check(pslg is not None and pslg.GetXMLName() == "TriangleTetGenReader",
          "a .poly opens with the plugin's reader")
    pslg.UpdatePipeline()
    check(pslg.GetDataInformation().GetNumberOfCells() == 8, "8 segments")
    mesh = GPUConstrainedDelaunay2D(Input=pslg)
    mesh.RemoveExterior = 1
    mesh.Backend = "CPU"
    gpudelaunay.update_pipeline(mesh)
    check(abs(total(mesh, "Area") - 12.0) < 1e-9, "meshed area 16 - 4 (the file's hole)")

    # Properties of the panel: off-centres and CDT only, documented.
    check_documented(mesh, ("OffCenters", "CDTOnly"))
    mesh.CDTOnly = 1
    gpudelaunay.update_pipeline(mesh)
    check(mesh.GetDataInformation().GetNumberOfPoints() == 8, "CDT only: no Steiner point")
    mesh.CDTOnly = 0

    # Shown as a mesher's user wants to see it: edges, coloured by MinAngle.
    view = CreateView("RenderView")
    controller = servermanager.vtkSMParaViewPipelineControllerWithRendering()
    controller.Show(mesh.SMProxy, 0, view.SMProxy)
    display = GetDisplayProperties(mesh, view)
    check(display.Representation == "Surface With Edges",
          "representation %s" % display.Representation)
    check(list(display.ColorArrayName) == ["CELLS", "MinAngle"],
          "colored by %s" % list(display.ColorArrayName))

    # TetGen .poly through the same reader: its region (attribute 7, maximum volume 0.001)
    # reaches the 3D filter.
    box = OpenDataFile(os.path.join(data, "..", "Testing", "CLI", "data", "box_region_volume.poly"))
    check(box.GetXMLName() == "TriangleTetGenReader", "TetGen .poly reader")
    tets = GPUQualityTetMesh(Input=box)
    tets.Backend = "CPU"
    gpudelaunay.update_pipeline(tets)
    check(tets.CellData["Region"].GetRange() == (7.0, 7.0), "Region 7 from the file")
    check(tets.CellData["Volume"].GetRange()[1] <= 0.001, "the region's volume bound")

    # .ele with the .node beside it.
    ele = OpenDataFile(os.path.join(data, "lshape_tetgen.ele"))
    check(ele.GetXMLName() == "TriangleTetGenMeshReader", ".ele reader")
    ele.UpdatePipeline()
    check(ele.GetDataInformation().GetNumberOfCells() == 12, "12 tetrahedra")

    # Failures: gpudelaunay.update_pipeline raises with the core's status and message;
    # UpdatePipeline alone returns quietly with an empty output, and the error code says
    # that the run failed.
    mesh.MinimumAngle = 40
    try:
        gpudelaunay.update_pipeline(mesh)
        check(False, "MinimumAngle 40 did not raise")
    except gpudelaunay.MeshingError as e:
        check(e.status == "InvalidInput" and "out of range" in e.message, str(e))
    mesh.UpdatePipeline()
    check(mesh.GetDataInformation().GetNumberOfCells() == 0, "empty after a failure")
    check(mesh.GetClientSideObject().GetErrorCode() != 0, "error code")
    broken = OpenDataFile(os.path.join(data, "broken_truncated.poly"))
    try:
        gpudelaunay.update_pipeline(broken)
        check(False, "a malformed file did not raise")
    except gpudelaunay.MeshingError as e:
        check(e.status == "IoError", str(e))
    print("reader test passed")


if __name__ == "__main__":
    main()
