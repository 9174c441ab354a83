#!/usr/bin/env pvpython
"""Show a Hele-Shaw run in ParaView: the grains as spheres coloured by
speed over a slice of the fluid at mid-gap coloured by pressure (left), and
the fracture map (right: grey the gap-averaged solid fraction, white the
fracture connected to the inlet), at the run's last (or a chosen) output
step. Writes a screenshot and a ParaView state file that the GUI opens
(File > Load State) for further work.

  xvfb-run -a pvpython scripts/plots/show_hele_shaw.py RUN_DIRECTORY \\
      [--time T] [--png FILE] [--state FILE]

RUN_DIRECTORY is a coupled run's output directory with field output
(`output/write vtu = true`): solution.pvd, grains.pvd and, with
`postprocessing/fracture area/enabled = true`, fracture_map_NNNNN.pgm.
pvpython is Debian's python3-paraview; without a display run it under
xvfb-run -a (apt-get install python3-paraview xvfb).
"""
import argparse
import glob
import os
import sys

import numpy as np
from paraview import simple
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from pgm_to_png import read_pgm  # noqa: E402


def read_fracture_map(path):
    """The fracture map as an array [row j from the bottom, column i]."""
    w, h, data = read_pgm(path)
    rows = np.frombuffer(data, dtype=np.uint8).reshape(h, w)
    return rows[::-1, :]  # the file's first row is the top (largest y)


def timesteps(reader):
    values = reader.TimestepValues
    if values is None:
        return [0.]
    return list(values) if hasattr(values, '__len__') else [values]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument('run', help='the run\'s output directory')
    ap.add_argument('--time', type=float, default=None,
                    help='output time to show (default: the last)')
    ap.add_argument('--png', default=None,
                    help='screenshot (default RUN/hele_shaw_view.png)')
    ap.add_argument('--state', default=None,
                    help='ParaView state (default RUN/hele_shaw_view.pvsm)')
    a = ap.parse_args()
    for name in ('solution.pvd', 'grains.pvd'):
        if not os.path.isfile(os.path.join(a.run, name)):
            raise SystemExit('%s: no %s; run the scene with output/write vtu '
                             '= true' % (a.run, name))
    png = a.png or os.path.join(a.run, 'hele_shaw_view.png')
    state = a.state or os.path.join(a.run, 'hele_shaw_view.pvsm')

    fluid = simple.PVDReader(FileName=os.path.join(a.run, 'solution.pvd'))
    grains = simple.PVDReader(FileName=os.path.join(a.run, 'grains.pvd'))
    times = timesteps(fluid)
    time = times[-1] if a.time is None else a.time
    if not min(times) - 1e-12 <= time <= max(times) + 1e-12:
        raise SystemExit('--time %g: outside the run\'s output times %g-%g s'
                         % (time, min(times), max(times)))
    scene = simple.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = time
    fluid.UpdatePipeline(time)
    grains.UpdatePipeline(time)
    x0, x1, y0, y1, z0, z1 = fluid.GetDataInformation().GetBounds()

    # Left: grains (radius-scaled spheres, speed) over the mid-gap slice.
    left = simple.CreateView('RenderView')
    speed = simple.Calculator(Input=grains, ResultArrayName='speed',
                              Function='mag(velocity)')
    spheres = simple.Glyph(Input=speed, GlyphType='Sphere')
    spheres.ScaleArray = ['POINTS', 'radius']
    spheres.ScaleFactor = 2.0  # the unit glyph has radius 0.5
    spheres.OrientationArray = ['POINTS', 'No orientation array']
    spheres.GlyphMode = 'All Points'
    spheres.GlyphType.ThetaResolution = 16
    spheres.GlyphType.PhiResolution = 16
    shown = simple.Show(spheres, left)
    simple.ColorBy(shown, ('POINTS', 'speed'))
    shown.SetScalarBarVisibility(left, True)
    simple.GetColorTransferFunction('speed').ApplyPreset('Viridis (matplotlib)', True)

    cut = simple.Slice(Input=fluid)
    cut.SliceType = 'Plane'
    cut.SliceType.Origin = [0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1)]
    cut.SliceType.Normal = [0, 0, 1]
    sliced = simple.Show(cut, left)
    simple.ColorBy(sliced, ('POINTS', 'pressure'))
    sliced.SetScalarBarVisibility(left, True)
    left.CameraPosition = [0.5 * (x0 + x1), 0.5 * (y0 + y1), z1 + 3 * (x1 - x0)]
    left.CameraFocalPoint = [0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1)]
    left.CameraViewUp = [0, 1, 0]
    left.ResetCamera()

    # Right: the fracture map of the same output step, placed on the plates'
    # plane with the pixel size of the postprocessor (a quarter of the mean
    # grain diameter).
    right = simple.CreateView('RenderView')
    maps = sorted(glob.glob(os.path.join(a.run, 'fracture_map_*.pgm')))
    if maps:
        index = min(range(len(times)), key=lambda k: abs(times[k] - time))
        path = maps[min(index, len(maps) - 1)]
        pixels = read_fracture_map(path)
        radius = vtk_to_numpy(simple.servermanager.Fetch(grains)
                              .GetPointData().GetArray('radius'))
        pixel = 0.5 * radius.mean()
        image = vtkImageData()
        image.SetDimensions(pixels.shape[1], pixels.shape[0], 1)
        image.SetOrigin(x0 + 0.5 * pixel, y0 + 0.5 * pixel, z0)
        image.SetSpacing(pixel, pixel, 1)
        values = numpy_to_vtk(pixels.ravel().astype(np.float32), deep=True)
        values.SetName('fracture_map')
        image.GetPointData().SetScalars(values)
        producer = simple.TrivialProducer(registrationName=os.path.basename(path))
        producer.GetClientSideObject().SetOutput(image)
        mapped = simple.Show(producer, right)
        mapped.SetRepresentationType('Slice')
        simple.ColorBy(mapped, ('POINTS', 'fracture_map'))
        lut = simple.GetColorTransferFunction('fracture_map')
        lut.ApplyPreset('Grayscale', True)
        lut.RescaleTransferFunction(0., 255.)
        right.CameraPosition = [0.5 * (x0 + x1), 0.5 * (y0 + y1), z1 + 3 * (x1 - x0)]
        right.CameraFocalPoint = [0.5 * (x0 + x1), 0.5 * (y0 + y1), z0]
        right.CameraViewUp = [0, 1, 0]
        right.ResetCamera()
        print('fracture map: %s (%d x %d pixels of %.3g m)' % (
            os.path.basename(path), pixels.shape[1], pixels.shape[0], pixel))
    else:
        print('no fracture_map_*.pgm in %s (postprocessing/fracture area/'
              'enabled = false?): the right view stays empty' % a.run)

    layout = simple.CreateLayout('Hele-Shaw')
    layout.AssignView(0, left)
    layout.SplitHorizontal(0, 0.5)
    layout.AssignView(2, right)
    simple.SaveScreenshot(png, layout, ImageResolution=[1600, 800])
    simple.SaveState(state)
    print('t = %g s: %s, %s' % (time, png, state))


if __name__ == '__main__':
    main()
