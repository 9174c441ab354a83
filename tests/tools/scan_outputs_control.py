#!/usr/bin/env python3
"""Negative control of scripts/checks/scan_outputs.py for the VTU path: write
VTU files whose zlib-compressed, base64-encoded Float32/Float64 arrays (the
layout deal.II writes: a UInt32 header of block count, block size, last
block size and compressed sizes, then the compressed data) hold one NaN or
one Inf, and a clean one; the scanner must flag exactly the first two.

  python3 tests/tools/scan_outputs_control.py WORKDIR
"""
import base64
import math
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..',
                                'scripts', 'checks'))
import scan_outputs  # noqa: E402


def data_array(name, kind, values):
    code = {'Float32': 'f', 'Float64': 'd'}[kind]
    raw = struct.pack('<%d%s' % (len(values), code), *values)
    compressed = zlib.compress(raw)
    header = struct.pack('<4I', 1, len(raw), len(raw), len(compressed))
    body = (base64.b64encode(header).decode() +
            base64.b64encode(compressed).decode())
    return ('<DataArray type="%s" Name="%s" format="binary">\n%s\n'
            '</DataArray>\n' % (kind, name, body))


def vtu(arrays):
    return ('<?xml version="1.0" ?>\n<VTKFile type="UnstructuredGrid" '
            'version="0.1" compressor="vtkZLibDataCompressor">\n'
            '<UnstructuredGrid><Piece>\n<PointData>\n' + ''.join(arrays) +
            '</PointData>\n</Piece></UnstructuredGrid></VTKFile>\n')


def main():
    work = sys.argv[1]
    os.makedirs(work, exist_ok=True)
    good = [0.5 * k for k in range(100)]
    files = {
        'nan.vtu': vtu([data_array('pressure', 'Float32', good),
                        data_array('velocity', 'Float32',
                                   good[:50] + [math.nan] + good[51:])]),
        'inf.vtu': vtu([data_array('void_fraction', 'Float64',
                                   good[:7] + [-math.inf] + good[8:])]),
        'clean.vtu': vtu([data_array('pressure', 'Float64', good)]),
    }
    flagged = {}
    for name, text in files.items():
        path = os.path.join(work, name)
        with open(path, 'w') as f:
            f.write(text)
        flagged[name] = scan_outputs.scan_vtu(path)
        print(name, flagged[name] or 'clean')
    ok = (len(flagged['nan.vtu']) == 1 and 'velocity' in flagged['nan.vtu'][0]
          and len(flagged['inf.vtu']) == 1 and not flagged['clean.vtu'])
    print('scan_outputs VTU control:', 'passed' if ok else 'FAILED')
    sys.exit(0 if ok else 1)


if __name__ == '__main__':
    main()
