"""Helpers shared by the ParaView plugin tests (run under pvbatch / pvpython)."""
import argparse
import sys


def check(condition, message):
    if not condition:
        print("FAILED:", message)
        sys.exit(1)


def compare_images(test_png, baseline_png):
    """Fails when more than 1% of the pixels differ by more than 40 in a color channel."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy

    def load(path):
        r = vtkPNGReader()
        r.SetFileName(path)
        r.Update()
        img = r.GetOutput()
        dims = img.GetDimensions()
        a = vtk_to_numpy(img.GetPointData().GetScalars()).astype(numpy.int32)
        return a.reshape(dims[1], dims[0], -1)[:, :, :3]

    a, b = load(test_png), load(baseline_png)
    check(a.shape == b.shape, "image size %s differs from baseline %s" % (a.shape, b.shape))
    diff = numpy.abs(a - b).max(axis=2)
    changed = float((diff > 40).mean())
    print("image comparison: %.3f%% of the pixels differ" % (100 * changed))
    check(changed < 0.01, "image differs from baseline %s in %.2f%% of the pixels"
          % (baseline_png, 100 * changed))


def check_documented(proxy, names):
    """Every property in `names` exists and has a documentation paragraph."""
    for name in names:
        prop = proxy.GetProperty(name)
        check(prop is not None, "property " + name)
        doc = prop.SMProperty.GetDocumentation()
        check(doc is not None and len(doc.GetDescription().strip()) > 20,
              "documentation of " + name)


def parse_args():
    """The command line every plugin test takes (see the tests' docstrings)."""
    p = argparse.ArgumentParser()
    p.add_argument("--plugin", required=True)
    p.add_argument("--input", required=True)
    p.add_argument("--outdir", required=True)
    p.add_argument("--render", action="store_true")
    p.add_argument("--baseline")
    p.add_argument("--update-baseline", action="store_true")
    return p.parse_args()
