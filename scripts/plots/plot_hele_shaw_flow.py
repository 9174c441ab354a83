#!/usr/bin/env python3
"""The pressure field and the flow paths of a Hele-Shaw injection in the
mid-plane of the gap, from softsand's field output (.pvtu), with the grains'
cross-sections in that plane.

  /usr/bin/python3 scripts/plots/plot_hele_shaw_flow.py \
    --solution output/RUN/solution_00001.pvtu --grains output/RUN/pack_end.txt \
    --title '32 kPa, 7 ms' --out doc/hele_shaw_flow_small_p32000.png

Left: the pressure (kPa; colours from its 1st to 99th percentile). Right: the in-plane fluid speed (m/s, log scale)
with streamlines of the in-plane velocity. Both are sampled on a regular
grid (--resolution points across) by linear interpolation of the output
points that lie in the mid-plane (z = --mid-plane, default: halfway between
the lowest and highest output point). A grain cut by the plane is drawn as
the circle of its cut. Reads the XML VTU that deal.II writes (base64,
zlib-compressed or raw); needs numpy, scipy and matplotlib
(/usr/bin/python3 on this machine).
"""
import argparse
import base64
import os
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402
from scipy.interpolate import griddata  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from prm_tools import read_grains  # noqa: E402

NUMPY_TYPES = {'Float32': '<f4', 'Float64': '<f8', 'Int32': '<i4',
               'Int64': '<i8', 'UInt8': '<u1', 'UInt32': '<u4',
               'UInt64': '<u8'}


def decode_binary(text, dtype, compressed, header_type):
    """A base64 DataArray of a VTU file: a header (block count and sizes,
    compressed) or a byte count (raw), then the data."""
    text = ''.join(text.split())
    hsize = 8 if header_type == 'UInt64' else 4
    hfmt = '<Q' if hsize == 8 else '<I'
    if not compressed:
        raw = base64.b64decode(text)
        n = struct.unpack(hfmt, raw[:hsize])[0]
        return np.frombuffer(raw[hsize:hsize + n], dtype=dtype)
    # The header is encoded on its own: decode its first field to learn its
    # length, then the rest.
    first = base64.b64decode(text[:8 if hsize == 4 else 12])
    n_blocks = struct.unpack(hfmt, first[:hsize])[0]
    header_bytes = hsize * (3 + n_blocks)
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = base64.b64decode(text[:header_chars])
    sizes = struct.unpack('<%d%s' % (3 + n_blocks, hfmt[1]), header)
    compressed_sizes = sizes[3:]
    data = base64.b64decode(text[header_chars:])
    out, offset = [], 0
    for c in compressed_sizes:
        out.append(zlib.decompress(data[offset:offset + c]))
        offset += c
    return np.frombuffer(b''.join(out), dtype=dtype)


def read_vtu(path, names):
    root = ET.parse(path).getroot()
    compressed = root.get('compressor') is not None
    header_type = root.get('header_type', 'UInt32')
    piece = root.find('.//Piece')

    def array(element):
        dtype = NUMPY_TYPES[element.get('type')]
        if element.get('format') == 'ascii':
            values = np.array(element.text.split(), dtype=dtype)
        else:
            values = decode_binary(element.text, dtype, compressed,
                                   header_type)
        n = int(element.get('NumberOfComponents', '1'))
        return values.reshape(-1, n) if n > 1 else values

    points = array(piece.find('Points/DataArray'))
    data = {}
    for element in piece.findall('PointData/DataArray'):
        if element.get('Name') in names:
            data[element.get('Name')] = array(element)
    missing = [n for n in names if n not in data]
    if missing:
        sys.exit('%s has no point data %s' % (path, ', '.join(missing)))
    return points, data


def read_pvtu(path, names):
    root = ET.parse(path).getroot()
    pieces = [p.get('Source') for p in root.findall('.//Piece')]
    if not pieces:
        sys.exit('%s lists no pieces' % path)
    points, data = [], {n: [] for n in names}
    for source in pieces:
        p, d = read_vtu(os.path.join(os.path.dirname(path), source), names)
        points.append(p)
        for n in names:
            data[n].append(d[n])
    return (np.concatenate(points),
            {n: np.concatenate(v) for n, v in data.items()})


def grain_cuts(grains, z):
    """Circles (x, y, r) where the plane z cuts the grains."""
    dz = grains[:, 2] - z
    cut = np.abs(dz) < grains[:, 3]
    r = np.sqrt(grains[cut, 3] ** 2 - dz[cut] ** 2)
    return grains[cut, 0], grains[cut, 1], r


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('--solution', required=True, help='a solution .pvtu')
    a.add_argument('--grains', required=True,
                   help='the grains at that time (a softsand pack file)')
    a.add_argument('--mid-plane', type=float, help='z of the plane, m')
    a.add_argument('--half-width', type=float, default=10e-3,
                   help='the plotted square is +-this, m')
    a.add_argument('--resolution', type=int, default=400)
    a.add_argument('--title', default='')
    a.add_argument('--out', required=True)
    args = a.parse_args()
    if args.resolution < 20:
        sys.exit('--resolution must be at least 20, got %d' % args.resolution)
    if args.half_width <= 0:
        sys.exit('--half-width must be > 0, got %g' % args.half_width)

    for name, path in [('--solution', args.solution),
                       ('--grains', args.grains)]:
        if not os.path.isfile(path):
            sys.exit('%s: no file %s' % (name, path))
    points, data = read_pvtu(args.solution, ['velocity', 'pressure'])
    z = points[:, 2]
    z_mid = (args.mid_plane if args.mid_plane is not None
             else 0.5 * (z.min() + z.max()))
    tolerance = 1e-6 * (z.max() - z.min())
    plane = np.abs(z - z_mid) < tolerance
    if plane.sum() < 100:
        sys.exit('only %d output points lie in the plane z = %g: choose '
                 '--mid-plane at a cell face' % (plane.sum(), z_mid))
    xy = points[plane, :2]
    pressure = data['pressure'][plane]
    velocity = data['velocity'][plane]

    w = args.half_width
    g = np.linspace(-w, w, args.resolution)
    X, Y = np.meshgrid(g, g)
    P = griddata(xy, pressure, (X, Y), method='linear')
    U = griddata(xy, velocity[:, 0], (X, Y), method='linear')
    V = griddata(xy, velocity[:, 1], (X, Y), method='linear')
    speed = np.hypot(U, V)

    grains = np.array(read_grains(args.grains))
    if grains.size == 0:
        sys.exit('--grains %s has no grains' % args.grains)
    cx, cy, cr = grain_cuts(grains, z_mid)

    fig, axes = plt.subplots(1, 2, figsize=(13, 6))
    scale = 1e3
    extent = [-w * scale, w * scale, -w * scale, w * scale]
    # The colours span the 1st-99th percentile: penalized grains carry
    # pressure spikes that would flatten the pores' field.
    p_low, p_high = np.nanpercentile(P, [1, 99]) / 1e3
    im = axes[0].imshow(P / 1e3, origin='lower', extent=extent,
                        cmap='viridis', vmin=p_low, vmax=p_high)
    fig.colorbar(im, ax=axes[0], label='pressure [kPa]')
    positive = speed[np.isfinite(speed) & (speed > 0)]
    low = max(np.percentile(positive, 5), 1e-6) if positive.size else 1e-6
    high = max(np.nanmax(speed), 10 * low) if positive.size else 1
    im = axes[1].imshow(np.where(speed > 0, speed, np.nan), origin='lower',
                        extent=extent, cmap='magma',
                        norm=LogNorm(vmin=low, vmax=high))
    fig.colorbar(im, ax=axes[1], label='in-plane fluid speed [m/s]')
    axes[1].streamplot(g * scale, g * scale, np.nan_to_num(U),
                       np.nan_to_num(V), color='c', density=1.6,
                       linewidth=0.6, arrowsize=0.6)
    for ax, name in zip(axes, ['pressure', 'flow paths']):
        circles = [Circle((x * scale, y * scale), r * scale)
                   for x, y, r in zip(cx, cy, cr)]
        ax.add_collection(PatchCollection(circles, facecolor='none',
                                          edgecolor='w', linewidth=0.5))
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        ax.set_aspect('equal')
        ax.set_xlabel('x [mm]')
        ax.set_ylabel('y [mm]')
        ax.set_title('%s, mid-plane z = %.3g mm' % (name, z_mid * 1e3),
                     fontsize=10)
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print('wrote %s: %d points in the plane, pressure %.3g to %.3g kPa, '
          'largest in-plane speed %.3g m/s, %d grains cut'
          % (args.out, plane.sum(), np.nanmin(P) / 1e3, np.nanmax(P) / 1e3,
             np.nanmax(speed), len(cr)))


if __name__ == '__main__':
    main()
