#!/usr/bin/env pvpython
"""Open a softsand run's output in ParaView (pvpython) and check it: every
time step of a PVD collection (or one PVTU/VTU file) loads through
ParaView's own readers, the expected fields are there with the right
number of components, every value is finite, and each field lies in its
range.

  pvpython scripts/checks/check_paraview.py output/drag_sphere/solution.pvd
  pvpython scripts/checks/check_paraview.py RUN/solution.pvd RUN/grains.pvd
  pvpython scripts/checks/check_paraview.py RUN/solution.pvd \\
      --range pressure=-10:10 --range velocity=0:1e-3

Fields checked by default (by file name):
  solution*: velocity (3 components), pressure (1), void_fraction in
             [0, 1], subdomain >= 0, refinement_level >= 0; at least one
             cell and one point.
  grains*:   radius > 0, density > 0, velocity (3), id >= 0 (a run whose
             grains have all left writes empty files: allowed).
--range NAME=LOW:HIGH adds or tightens a range (the magnitude for vectors);
for a field a file does not hold by default, only where it is present.

Prints one line per file and time step and exits 1 on any failure, 0 if
all pass. The test 'paraview_client' (tests/CMakeLists.txt) runs it on a
small coupled run when pvpython is installed.
"""
import argparse
import math
import os
import sys

from paraview import servermanager
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy
import numpy as np

# name -> (components, low, high); None: unbounded.
SOLUTION = {'velocity': (3, None, None), 'pressure': (1, None, None),
            'void_fraction': (1, -1e-6, 1 + 1e-6),
            'subdomain': (1, 0, None), 'refinement_level': (1, 0, None)}
GRAINS = {'radius': (1, 1e-300, None), 'density': (1, 1e-300, None),
          'velocity': (3, None, None), 'id': (1, 0, None)}


def expected_fields(path):
    name = os.path.basename(path)
    if name.startswith('grains'):
        return dict(GRAINS), True
    if name.startswith('solution'):
        return dict(SOLUTION), False
    return {}, True


def unstructured(data):
    """The dataset behind a fetched object (a multiblock from some
    readers: its first leaf)."""
    if data.IsA('vtkMultiBlockDataSet'):
        it = data.NewIterator()
        it.InitTraversal()
        return None if it.IsDoneWithTraversal() else it.GetCurrentDataObject()
    return data


def check_dataset(data, fields, may_be_empty, label):
    problems = []
    data = unstructured(data)
    if data is None or data.GetNumberOfPoints() == 0:
        if not may_be_empty:
            problems.append('no points')
        return problems, 'empty'
    if data.GetNumberOfCells() == 0 and not may_be_empty:
        problems.append('no cells')
    pd = data.GetPointData()
    summary = []
    for name, (ncomp, low, high) in sorted(fields.items()):
        array = pd.GetArray(name)
        if array is None:
            if ncomp != -1:
                problems.append('field %s missing' % name)
            continue
        if ncomp > 0 and array.GetNumberOfComponents() != ncomp:
            problems.append('%s has %d components, expected %d' % (
                name, array.GetNumberOfComponents(), ncomp))
        values = vtk_to_numpy(array).astype(float)
        if not np.all(np.isfinite(values)):
            problems.append('%s: %d non-finite values' % (
                name, int(np.sum(~np.isfinite(values)))))
            continue
        if values.ndim > 1:
            values = np.linalg.norm(values, axis=1)
        lo, hi = float(values.min()), float(values.max())
        summary.append('%s [%.3g, %.3g]' % (name, lo, hi))
        if low is not None and lo < low:
            problems.append('%s = %.6g below %.6g' % (name, lo, low))
        if high is not None and hi > high:
            problems.append('%s = %.6g above %.6g' % (name, hi, high))
    # Every other point array must be finite too.
    for k in range(pd.GetNumberOfArrays()):
        name = pd.GetArrayName(k)
        if name in fields:
            continue
        values = vtk_to_numpy(pd.GetArray(k))
        if not np.all(np.isfinite(values)):
            problems.append('%s: non-finite values' % name)
    text = '%d points, %d cells; %s' % (data.GetNumberOfPoints(),
                                        data.GetNumberOfCells(),
                                        ', '.join(summary))
    return problems, text


def check_file(path, extra):
    fields, may_be_empty = expected_fields(path)
    # A --range of a field this kind of file does not hold by default
    # applies where the field is present (ncomp -1: optional).
    for name, (low, high) in extra.items():
        ncomp = fields.get(name, (-1, None, None))[0]
        fields[name] = (ncomp, low, high)
    reader = simple.OpenDataFile(path)
    if reader is None:
        print('FAIL %s: ParaView has no reader for it' % path)
        return 1
    times = list(getattr(reader, 'TimestepValues', None) or [])
    if not times:
        times = [None]
    failures = 0
    for t in times:
        if t is None:
            reader.UpdatePipeline()
        else:
            reader.UpdatePipeline(t)
        data = servermanager.Fetch(reader)
        problems, text = check_dataset(data, fields, may_be_empty, path)
        label = path if t is None else '%s t = %g' % (path, t)
        if problems:
            failures += 1
            print('FAIL %s: %s' % (label, '; '.join(problems)))
        else:
            print('ok   %s: %s' % (label, text))
    simple.Delete(reader)
    return failures


def parse_range(text):
    name, bounds = text.split('=', 1)
    low, high = bounds.split(':', 1)
    return name, (float(low) if low else None, float(high) if high else None)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('files', nargs='+', help='.pvd, .pvtu or .vtu files')
    ap.add_argument('--range', action='append', default=[],
                    help='NAME=LOW:HIGH (either side may be empty)')
    a = ap.parse_args()
    extra = dict(parse_range(r) for r in a.range)
    failures = 0
    for path in a.files:
        if not os.path.exists(path):
            print('FAIL %s: no such file' % path)
            failures += 1
            continue
        failures += check_file(path, extra)
    print('%s: %d failure(s)' % ('FAIL' if failures else 'ok', failures))
    sys.exit(1 if failures else 0)


if __name__ == '__main__':
    main()
