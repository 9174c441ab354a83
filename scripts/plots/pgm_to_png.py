#!/usr/bin/env python3
"""Convert the fracture maps (binary PGM, fracture_map_NNNNN.pgm: grey
0..200 the gap-averaged solid fraction 0..1, 255 the fracture connected to
the inlet) to PNG. With matplotlib: axes in mm from the map's extent, the
step and time in the title, a legend and the fracture's area and reach
(maps written since stop 59 carry them in their header comments). Without
it, or with --plain: the pixels scaled up by an integer factor, with the
standard library only.

  python3 scripts/plots/pgm_to_png.py in.pgm out.png [--scale 4] [--plain]
"""
import re
import argparse
import struct
import zlib


def read_pgm(path):
    with open(path, 'rb') as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b'#':
            pos = data.index(b'\n', pos) + 1
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    pos += 1
    assert fields[0] == b'P5', 'binary PGM expected'
    w, h = int(fields[1]), int(fields[2])
    return w, h, data[pos:pos + w * h]


def read_pgm_comments(path):
    """The header comments of a softsand map: step, time (s), pixel (m),
    extent (x0, x1, y0, y1 in m), area (m^2), reach (m); {} if absent."""
    with open(path, 'rb') as f:
        head = f.read(4096).decode('latin-1')
    number = r'([-+0-9.eE]+)'
    found = {}
    for key, pattern in (
            ('step', r'step (\d+), time ' + number + ' s'),
            ('pixel', r'# pixel ' + number + ' m; x from ' + number +
             ' to ' + number + r' m .*?y from ' + number + ' to ' +
             number + ' m'),
            ('area', r'fracture area ' + number + ' m\\^2, reach ' + number)):
        m = re.search(pattern, head)
        if not m:
            continue
        v = [float(g) for g in m.groups()]
        if key == 'step':
            found.update(step=int(v[0]), time=v[1])
        elif key == 'pixel':
            found.update(pixel=v[0], extent=v[1:5])
        else:
            found.update(area=v[0], reach=v[1])
    return found


def plot_png(path, w, h, pix, info):
    """The map with axes in mm (matplotlib)."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch
    rgb = [[(0.86, 0.12, 0.12) if pix[j * w + i] == 255 else
            ((255 - pix[j * w + i]) / 255.,) * 3 for i in range(w)]
           for j in range(h)]
    fig, ax = plt.subplots(figsize=(5.5, 5.5 * h / w + 0.6))
    x0, x1, y0, y1 = [1e3 * v for v in info.get('extent', (0, w, 0, h))]
    ax.imshow(rgb, extent=(x0, x1, y0, y1), interpolation='nearest')
    unit = 'mm' if 'extent' in info else 'pixels'
    ax.set_xlabel('x [%s]' % unit)
    ax.set_ylabel('y [%s]' % unit)
    title = 'fracture map'
    if 'time' in info:
        title += ', step %d, t = %.4g ms' % (info['step'], 1e3 * info['time'])
    if 'area' in info:
        title += '\narea %.3g mm$^2$, reach %.3g mm' % (1e6 * info['area'],
                                                      1e3 * info['reach'])
    ax.set_title(title, fontsize=10)
    ax.legend(handles=[Patch(color=(0.86, 0.12, 0.12),
                             label='fracture (connected to the inlet)'),
                       Patch(color='0.3', label='solid fraction (grey)')],
              loc='upper right', fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=150)


def write_png(path, w, h, rows):
    def chunk(tag, body):
        return (struct.pack('>I', len(body)) + tag + body +
                struct.pack('>I', zlib.crc32(tag + body) & 0xffffffff))
    raw = b''.join(b'\x00' + bytes(r) for r in rows)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n')
        # 8-bit RGB.
        f.write(chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0)))
        f.write(chunk(b'IDAT', zlib.compress(raw, 9)))
        f.write(chunk(b'IEND', b''))


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    a.add_argument('pgm')
    a.add_argument('png')
    a.add_argument('--scale', type=int, default=4)
    a.add_argument('--plain', action='store_true',
                   help='the pixels only (no axes; no matplotlib needed)')
    args = a.parse_args()
    w, h, pix = read_pgm(args.pgm)
    if not args.plain:
        try:
            plot_png(args.png, w, h, pix, read_pgm_comments(args.pgm))
            return
        except ImportError:
            pass
    s = args.scale
    rows = []
    for j in range(h):
        row = []
        for i in range(w):
            v = pix[j * w + i]
            # The fracture in red, the solid fraction in grey (white: void).
            rgb = (220, 30, 30) if v == 255 else (255 - v,) * 3
            row.extend(rgb * s)
        rows.extend([row] * s)
    write_png(args.png, w * s, h * s, rows)


if __name__ == '__main__':
    main()
