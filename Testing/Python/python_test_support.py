"""Helpers shared by the Python tests (run with the test's own directory on sys.path)."""
import sys


def check(condition, message):
    if not condition:
        print("FAILED:", message)
        sys.exit(1)


def write_and_read(data, path, writer, reader):
    """Writes `data` with `writer` to `path` and reads it back with `reader`."""
    writer.SetFileName(path)
    writer.SetInputData(data)
    check(writer.Write() == 1, "write " + path)
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()
