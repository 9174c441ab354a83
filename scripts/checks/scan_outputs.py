#!/usr/bin/env python3
"""Scan a run's output directory for NaN and Inf: text tables
(statistics.txt, grain_forces.txt, saved packs), PVD/PVTU records and the
VTU files deal.II writes (base64, zlib-compressed or not, or ASCII).

  python3 scripts/checks/scan_outputs.py DIR [DIR ...]

Prints one line per problem and exits 1 if any; used by
scripts/checks/extremes_suite.py.
"""
import base64
import math
import os
import re
import struct
import sys
import zlib

TOKEN = re.compile(r'(?<![A-Za-z_])([+-]?(?:nan|inf(?:inity)?))(?![A-Za-z_])',
                   re.IGNORECASE)
FORMATS = {'Float32': ('f', 4), 'Float64': ('d', 8)}


def _b64(text):
    return base64.b64decode(text + '=' * (-len(text) % 4))


def _decode_binary(body, compressed):
    """The raw bytes of one base64 DataArray as deal.II writes it: a UInt32
    header (zlib: number of blocks, block size, last block size, compressed
    sizes; otherwise the byte count), base64-encoded apart from the data."""
    body = ''.join(body.split())
    if compressed:
        n_blocks = struct.unpack('<I', _b64(body[:8])[:4])[0]
        header_bytes = 4 * (3 + n_blocks)
        header_chars = 4 * ((header_bytes + 2) // 3)
        header = struct.unpack('<%dI' % (3 + n_blocks),
                               _b64(body[:header_chars])[:header_bytes])
        data = _b64(body[header_chars:])
        out, pos = b'', 0
        for size in header[3:]:
            out += zlib.decompress(data[pos:pos + size])
            pos += size
        return out
    header_chars = 8  # one UInt32 -> 4 bytes -> 8 base64 characters
    size = struct.unpack('<I', _b64(body[:header_chars])[:4])[0]
    return _b64(body[header_chars:])[:size]


def scan_vtu(path):
    """Problems in the floating-point arrays of a .vtu file."""
    problems = []
    with open(path, errors='replace') as f:
        text = f.read()
    compressed = 'compressor=' in text[:2000]
    for m in re.finditer(r'<DataArray([^>]*)>(.*?)</DataArray>', text, re.S):
        attrs, body = m.group(1), m.group(2)
        kind = re.search(r'type="(\w+)"', attrs)
        name = re.search(r'Name="([^"]*)"', attrs)
        name = name.group(1) if name else 'points'
        if not kind or kind.group(1) not in FORMATS:
            continue
        fmt = re.search(r'format="(\w+)"', attrs)
        fmt = fmt.group(1) if fmt else 'ascii'
        if fmt == 'ascii':
            bad = TOKEN.findall(body)
            if bad:
                problems.append('%s: array %s holds %s' % (path, name, bad[0]))
            continue
        try:
            raw = _decode_binary(body, compressed)
        except (ValueError, zlib.error, struct.error) as e:
            problems.append('%s: array %s unreadable (%s)' % (path, name, e))
            continue
        code, size = FORMATS[kind.group(1)]
        values = struct.unpack('<%d%s' % (len(raw) // size, code),
                               raw[:len(raw) // size * size])
        n_bad = sum(1 for v in values if not math.isfinite(v))
        if n_bad:
            problems.append('%s: array %s has %d non-finite values of %d' %
                            (path, name, n_bad, len(values)))
    return problems


def scan_text(path):
    """NaN/Inf tokens in a text file (comment lines skipped)."""
    problems = []
    with open(path, errors='replace') as f:
        for number, line in enumerate(f, 1):
            if line.lstrip().startswith('#'):
                continue
            bad = TOKEN.findall(line)
            if bad:
                problems.append('%s:%d: %s' % (path, number, bad[0]))
                break
    return problems


def scan_directory(directory):
    """(number of files scanned, problems) for every output file below."""
    problems, n_files = [], 0
    for root, _, files in os.walk(directory):
        for name in sorted(files):
            path = os.path.join(root, name)
            if name.endswith('.vtu'):
                problems += scan_vtu(path)
            elif name.endswith(('.txt', '.pvtu', '.pvd', '.md')):
                problems += scan_text(path)
            else:
                continue
            n_files += 1
    return n_files, problems


def main():
    bad = False
    for directory in sys.argv[1:]:
        n, problems = scan_directory(directory)
        for p in problems:
            print(p)
        print('%s: %d files scanned, %d problems' % (directory, n,
                                                      len(problems)))
        bad = bad or bool(problems)
    sys.exit(1 if bad else 0)


if __name__ == '__main__':
    main()
