#!/usr/bin/env python3
"""Convert the fracture maps (binary PGM, fracture_map-NNNNN.pgm: grey
0..200 the gap-averaged solid fraction 0..1, 255 the fracture connected to
the inlet) to PNG, scaled up by an integer factor, with the standard
library only (no matplotlib needed).

  python3 scripts/pgm_to_png.py in.pgm out.png [--scale 4]
"""
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
    args = a.parse_args()
    w, h, pix = read_pgm(args.pgm)
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
