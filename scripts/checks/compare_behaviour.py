#!/usr/bin/env python3
"""Capture the outputs of a fixed set of scenes with one softsand binary, and
compare two such captures: a check that a refactoring left the behaviour
unchanged.

Usage (from anywhere; the scenes run with the repository root as the working
directory, so that the relative paths in the .prm files resolve):

  python3 scripts/checks/compare_behaviour.py capture --binary BIN --out DIR \
      [--ranks N] [--scenes a,b,...] [--vtu]
  python3 scripts/checks/compare_behaviour.py compare DIR_A DIR_B \
      [--tolerance REL] [--abs-tolerance ABS] [--scenes a,b,...]
  python3 scripts/checks/compare_behaviour.py list

capture: for every scene, writes DIR/<scene>/scene.prm (the scene's .prm with
override blocks appended: output/directory = DIR/<scene>, output/write vtu =
false unless --vtu, and the scene's own overrides below), runs BIN on it
(mpirun -np N for --ranks N > 1), and keeps in DIR/<scene>/
  screen.txt      stdout; stderr.txt: stderr
  results.txt     the "Results (...)" block(s) of stdout: each line starting
                  with "Results (" and the lines after it that begin with two
                  spaces
  statistics.txt  (and run-K/statistics.txt, convergence.txt of a
                  convergence study, pack files written by dem/save pack)
  run.json        command, exit code, wall seconds
DIR/<scene>/ is emptied first. DIR/capture_summary.txt lists the seconds per
scene.

compare: for every scene, compares every *.txt file of DIR_A/<scene> with its
counterpart in DIR_B/<scene> (except screen.txt and stderr.txt):
  * tables (statistics.txt, convergence.txt, pack files): by column name. The
    header is a first line that is not a comment and not numbers (statistics
    since stop 22, followed by '# k: name (unit)' lines; a deal.II
    TableHandler text table), else the last line starting with '#' before
    the data (statistics before stop 22: '# name1 name2 ...'; pack files).
    Row counts must match. Columns present in one
    capture only are printed as added / removed and are not failures by
    themselves. Timing and resource columns are not compared (see
    is_timing()): wall_time, loop_time, grain_steps_per_second, wall_s,
    cpu_s, memory_MB, ... -- but the physical 'time' and 'coupling_time_step'
    are.
  * results.txt: entry by entry, by block and name (timing entries skipped).
  * run.json: the exit codes must agree.
By default a value must be the same text (the printed digits); a value whose
text differs is also passed to numdiff (/usr/bin/numdiff, -a 0 -r 0) to say
whether it is numerically equal (a formatting change only -- still reported
as a difference). With --tolerance / --abs-tolerance, numdiff with those
thresholds decides instead (-r REL -a ABS: equal if within either).
It prints one line per scene, "identical" or "DIFFERS" with the first
difference (file, column, row, both values), and exits 1 if any value, row
count, exit code or compared file differs or is missing.

The scenes (all in SCENES below) and what was cut to keep each capture short
on 1 rank:
  hele_shaw_small    parameters/hele_shaw_small.prm, as
                     scripts/studies/hele_shaw_sweep.py --pressures 8000 --steps 2
                     --linear-tolerance 3e-5 sets it (inlet pressure 8 kPa, 2
                     coupling steps, linear tolerance 3e-5), plus dem/save
                     pack = pack_end.txt as the sweep does (the final grains).
  settling_sphere    parameters/settling_sphere.prm as is.
  pour               parameters/pour.prm as is (writes pack.txt).
  pour_and_compact   parameters/pour_and_compact.prm as is (writes pack.txt).
  drag_sphere        parameters/drag_sphere.prm as is (steady Stokes).
  theta_convergence  parameters/theta_convergence.prm as is.
  free_sphere        parameters/free_sphere.prm, cut to simulation
                     control/max time steps = 5 (of 10).
  drag_sphere_refinement
                     parameters/studies/drag_sphere_refinement.prm as is (5
                     runs; run-K/ and convergence.txt are compared).
  channel_time_step_study
                     the BDF2 time-step study of tests/convergence_study.cc
                     (2D disc in a channel, 4 runs): a cheap convergence
                     study of a transient 2D scene.
No scene needed more cutting than that: on 1 rank of a 2-core machine that
was also compiling, the capture took about 6 minutes in all (settling_sphere
2.4 min, drag_sphere_refinement 1 min, free_sphere, theta_convergence,
hele_shaw_small under 1 min each, the rest seconds). Each scene is
deterministic on 1 rank (two captures compare identical); with more ranks,
check that before relying on it.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from prm_tools import is_number  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
NUMDIFF = '/usr/bin/numdiff'

# The 2D channel of tests/convergence_study.cc (a disc with rigid nodes,
# inflow ramping up smoothly), as its BDF2 time-step study.
CHANNEL_TIME_STEP_STUDY = """\
set dimension = 2
subsection mesh
  set lower corner = 0, 0
  set upper corner = 4e-3, 2e-3
  set cells per diameter = 8
end
subsection grains
  set source = list
  set list = 1.5e-3, 1e-3, 2.5e-4
end
subsection fluid
  set density = 1000
  set viscosity = 1e-3
  set solid model = rigid nodes
end
subsection boundary conditions
  subsection x min
    set type = function
    set function = 4e-5*sin(pi*t/0.2)^2; 0
  end
  subsection x max
    set type = pressure
  end
  subsection y min
    set type = symmetry
  end
  subsection y max
    set type = symmetry
  end
end
subsection simulation control
  set mode = transient
  set end time = 0.1
  set time scheme = BDF2
end
subsection convergence study
  set knob = time step
  set values = 0.02, 0.01, 0.005, 0.0025
  set quantity = grain_force_x
end
"""

# name -> (the .prm file relative to the repository root, or its text;
#          [(entry path, value), ...] appended as override blocks)
SCENES = {
    'hele_shaw_small': ('parameters/hele_shaw_small.prm', [
        ('boundary conditions/inlet region/pressure', '8000'),
        ('simulation control/max time steps', '2'),
        ('fluid solver/linear tolerance', '3e-5'),
        ('dem/save pack', 'pack_end.txt')]),
    'settling_sphere': ('parameters/settling_sphere.prm', []),
    'pour': ('parameters/pour.prm', []),
    'pour_and_compact': ('parameters/pour_and_compact.prm', []),
    'drag_sphere': ('parameters/drag_sphere.prm', []),
    'theta_convergence': ('parameters/theta_convergence.prm', []),
    'free_sphere': ('parameters/free_sphere.prm', [
        ('simulation control/max time steps', '5')]),
    'drag_sphere_refinement': (
        'parameters/studies/drag_sphere_refinement.prm', []),
    'channel_time_step_study': (CHANNEL_TIME_STEP_STUDY, []),
}

# Files of a capture that are not compared (they hold wall times).
NOT_COMPARED = {'screen.txt', 'stderr.txt'}


def is_timing(name):
    """A column or results entry that measures the run, not the physics."""
    # Not 'wall' alone: wall_xmin_pressure, max_wall_overlap_ratio are DEM
    # walls.
    n = name.lower()
    if n in ('wall_time', 'loop_time', 'grain_steps_per_second', 'wall_s',
             'cpu_s', 'memory_mb', 'peak_memory'):
        return True
    return any(w in n for w in ('wall_time', 'wallclock', 'wall_clock',
                                'cpu_time', 'cpu_s', 'per_second', 'elapsed',
                                'memory', 'seconds', 'loop_time'))


# ----------------------------------------------------------------- capture

def override_block(path, value):
    """'a/b/key' -> 'subsection a / subsection b / set key = value / end
    end' (deal.II's ParameterHandler accepts a subsection entered again; the
    later 'set' wins)."""
    parts = path.split('/')
    lines = []
    for i, sec in enumerate(parts[:-1]):
        lines.append('  ' * i + 'subsection ' + sec)
    lines.append('  ' * (len(parts) - 1) + 'set %s = %s' % (parts[-1], value))
    for i in reversed(range(len(parts) - 1)):
        lines.append('  ' * i + 'end')
    return '\n'.join(lines) + '\n'


def scene_text(source):
    if '\n' in source:
        return source
    with open(os.path.join(REPO, source)) as f:
        return f.read()


def extract_results(screen):
    """The "Results (...)" blocks of the screen output."""
    out, inside = [], False
    for line in screen.splitlines():
        if line.startswith('Results ('):
            out.append(line)
            inside = True
        elif inside and line.startswith('  '):
            out.append(line)
        else:
            inside = False
    return '\n'.join(out) + ('\n' if out else '')


def capture(args):
    names = select(args.scenes)
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    env = dict(os.environ)
    env.update(OMP_NUM_THREADS='1', DEAL_II_NUM_THREADS='1',
               OMPI_ALLOW_RUN_AS_ROOT='1', OMPI_ALLOW_RUN_AS_ROOT_CONFIRM='1',
               OMPI_MCA_rmaps_base_oversubscribe='1')
    binary = os.path.abspath(args.binary)
    # A copied binary finds the library copied next to it (also if its
    # RUNPATH still names the build directory).
    here = os.path.dirname(binary)
    if any(f.startswith('libsoftsand.so') for f in os.listdir(here)):
        env['LD_LIBRARY_PATH'] = here + (
            ':' + env['LD_LIBRARY_PATH'] if env.get('LD_LIBRARY_PATH') else '')
    summary = []
    for name in names:
        source, overrides = SCENES[name]
        d = os.path.join(out, name)
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        text = scene_text(source).rstrip('\n') + '\n\n# compare_behaviour.py\n'
        entries = list(overrides) + [
            ('output/directory', d),
            ('output/write vtu', 'true' if args.vtu else 'false')]
        for path, value in entries:
            text += override_block(path, value)
        prm = os.path.join(d, 'scene.prm')
        with open(prm, 'w') as f:
            f.write(text)
        cmd = [binary, prm]
        if args.ranks > 1:
            cmd = ['mpirun', '-np', str(args.ranks)] + cmd
        print('%-24s ... ' % name, end='', flush=True)
        start = time.time()
        proc = subprocess.run(cmd, cwd=REPO, env=env, capture_output=True,
                              text=True)
        seconds = time.time() - start
        with open(os.path.join(d, 'screen.txt'), 'w') as f:
            f.write(proc.stdout)
        with open(os.path.join(d, 'stderr.txt'), 'w') as f:
            f.write(proc.stderr)
        with open(os.path.join(d, 'results.txt'), 'w') as f:
            f.write(extract_results(proc.stdout))
        with open(os.path.join(d, 'run.json'), 'w') as f:
            json.dump(dict(command=cmd, cwd=REPO, returncode=proc.returncode,
                           seconds=round(seconds, 1)), f, indent=1)
        # Fields for ParaView are not compared; keep the capture small.
        if not args.vtu:
            for root, _, files in os.walk(d):
                for fn in files:
                    if fn.endswith(('.vtu', '.pvtu', '.pvd', '.pgm')):
                        os.remove(os.path.join(root, fn))
        status = 'ok' if proc.returncode == 0 else \
            'FAILED (exit %d: %s)' % (proc.returncode,
                                      ' '.join(proc.stderr.split())[-200:])
        print('%6.1f s  %s' % (seconds, status), flush=True)
        summary.append('%-24s %7.1f s  exit %d' % (name, seconds,
                                                   proc.returncode))
    with open(os.path.join(out, 'capture_summary.txt'), 'a') as f:
        f.write('# %s, %d rank(s), %s\n' % (binary, args.ranks,
                                            time.strftime('%F %T')))
        f.write('\n'.join(summary) + '\n')
    return 0


# ----------------------------------------------------------------- compare

def read_table(path):
    """(header comment lines, column names, rows of value texts)."""
    with open(path) as f:
        lines = [l.rstrip('\n') for l in f if l.strip()]
    comments = []
    i = 0
    while i < len(lines) and lines[i].lstrip().startswith('#'):
        comments.append(lines[i])
        i += 1
    if i < len(lines) and not is_number(lines[i].split()[0]):
        # A names line not commented (statistics tables since stop 22).
        names = lines[i].split()
        i += 1
    elif comments:
        names = comments[-1].lstrip().lstrip('#').split()
        comments = comments[:-1]
    else:
        names = []
    # Since stop 22 the unit comments follow the names line.
    comments += [l for l in lines[i:] if l.lstrip().startswith('#')]
    rows = [l.split() for l in lines[i:] if not l.lstrip().startswith('#')]
    return comments, names, rows


def read_results(path):
    """[(key, value text)], key = 'Results (3D) #K: name' (block K)."""
    entries, block = [], ''
    count = 0
    with open(path) as f:
        for line in f:
            if line.startswith('Results ('):
                count += 1
                block = '%s #%d' % (line.strip().rstrip(':'), count)
            elif line.strip():
                parts = line.split()
                entries.append(('%s: %s' % (block, parts[0]),
                                ' '.join(parts[1:])))
    return entries


class Cells:
    """The value pairs whose text differs, judged by one numdiff call."""

    def __init__(self, rel, abs_):
        self.rel, self.abs = rel, abs_
        self.items = []  # (where, a, b)
        self.count = 0   # values compared

    def add(self, where, a, b):
        self.count += 1
        if a != b:
            self.items.append((where, a, b))

    def judge(self):
        """[(where, a, b, numerically_equal)] in the order added."""
        if not self.items:
            return []
        with tempfile.TemporaryDirectory() as tmp:
            fa, fb = os.path.join(tmp, 'a'), os.path.join(tmp, 'b')
            with open(fa, 'w') as f:
                f.write(''.join(a + '\n' for _, a, _ in self.items))
            with open(fb, 'w') as f:
                f.write(''.join(b + '\n' for _, _, b in self.items))
            proc = subprocess.run(
                [NUMDIFF, '-a', repr(self.abs), '-r', repr(self.rel), fa, fb],
                capture_output=True, text=True)
        bad = set(int(m.group(1)) for m in
                  re.finditer(r'^##(\d+)\s', proc.stdout, re.M))
        if proc.returncode not in (0, 1):
            raise SystemExit('numdiff failed: ' + proc.stderr)
        return [(w, a, b, (k + 1) not in bad)
                for k, (w, a, b) in enumerate(self.items)]


def compare_table(fa, fb, cells, notes):
    """Queue the compared cells of two tables; return a structural failure
    (row count) or None. Added/removed columns go to notes."""
    ca, na, ra = read_table(fa)
    cb, nb, rb = read_table(fb)
    rel = os.path.basename(fa)
    if ca != cb:
        for x, y in zip(ca + [''] * len(cb), cb + [''] * len(ca)):
            if x != y:
                cells.add('%s header line' % rel, x, y)
                break
    added = [n for n in nb if n not in na]
    removed = [n for n in na if n not in nb]
    if added:
        notes.append('%s: added columns: %s' % (rel, ' '.join(added)))
    if removed:
        notes.append('%s: removed columns: %s' % (rel, ' '.join(removed)))
    if len(ra) != len(rb):
        return '%s: %d rows vs %d rows' % (rel, len(ra), len(rb))
    ia = {n: k for k, n in enumerate(na)}
    ib = {n: k for k, n in enumerate(nb)}
    common = [n for n in na if n in ib and not is_timing(n)]
    label = next((n for n in ('step', 'time') if n in ia), None)
    for r, (xa, xb) in enumerate(zip(ra, rb)):
        where_row = 'row %d' % (r + 1)
        if label is not None and ia[label] < len(xa):
            where_row += ' (%s %s)' % (label, xa[ia[label]])
        if len(xa) != len(na) or len(xb) != len(nb):
            cells.add('%s %s: number of fields' % (rel, where_row),
                      str(len(xa)), str(len(xb)))
        for n in common:
            a = xa[ia[n]] if ia[n] < len(xa) else '<missing>'
            b = xb[ib[n]] if ib[n] < len(xb) else '<missing>'
            cells.add('%s column %s %s' % (rel, n, where_row), a, b)
    return None


def compare_results(fa, fb, cells, notes):
    ea, eb = read_results(fa), read_results(fb)
    da, db = dict(ea), dict(eb)
    added = [k for k, _ in eb if k not in da]
    removed = [k for k, _ in ea if k not in db]
    if added:
        notes.append('results.txt: added entries: %s' % ' '.join(added))
    if removed:
        notes.append('results.txt: removed entries: %s' % ' '.join(removed))
    blocks_a = sorted(set(k.split(': ')[0] for k, _ in ea))
    blocks_b = sorted(set(k.split(': ')[0] for k, _ in eb))
    if len(blocks_a) != len(blocks_b):
        return 'results.txt: %d vs %d Results blocks' % (len(blocks_a),
                                                         len(blocks_b))
    for k, a in ea:
        if k in db and not is_timing(k.split(': ')[-1]):
            cells.add('results.txt %s' % k, a, db[k])
    return None


TIMING = re.compile(
    r'[-+]?\d+(\.\d*)?([eE][-+]?\d+)?\s*(s\b|MB\b|grain-steps/s)')


def screen_lines(path):
    """The screen output without its timings (numbers followed by s, MB or
    grain-steps/s; a convergence table's columns from wall_s on), white
    space and table rules folded."""
    try:
        text = open(path, errors='replace').read()
    except OSError:
        return []
    out, cut = [], None
    for line in text.splitlines():
        # A convergence table: drop its timing columns (wall_s, cpu_s, ...).
        words = line.split()
        if 'wall_s' in words:
            cut = words.index('wall_s')
        elif not words:
            cut = None
        if cut is not None:
            line = ' '.join(words[:cut])
        line = TIMING.sub('<t>', line)
        line = re.sub(r'-{2,}', '--', line)
        out.append(' '.join(line.split()))
    return out


def compare_screen(da, db):
    """A note (not a failure) where the screen output differs beyond its
    timings: a changed message, a timer section renamed or called a different
    number of times."""
    la = screen_lines(os.path.join(da, 'screen.txt'))
    lb = screen_lines(os.path.join(db, 'screen.txt'))
    if la == lb:
        return None
    n = sum(1 for x, y in zip(la, lb) if x != y) + abs(len(la) - len(lb))
    first = next((k for k, (x, y) in enumerate(zip(la, lb)) if x != y),
                 min(len(la), len(lb)))
    show = lambda l: l[first] if first < len(l) else '<end>'
    return ('screen.txt (informational, timings masked): %d line(s) differ, '
            'first line %d: %r vs %r' % (n, first + 1, show(la), show(lb)))


def files_of(d):
    out = []
    for root, _, files in os.walk(d):
        for fn in files:
            rel = os.path.relpath(os.path.join(root, fn), d)
            if fn.endswith('.txt') and rel not in NOT_COMPARED:
                out.append(rel)
    return sorted(out)


def compare_scene(da, db, args):
    """(ok, line, notes)."""
    if not os.path.isdir(da) or not os.path.isdir(db):
        return False, 'missing in %s' % (da if not os.path.isdir(da) else db), []
    notes, failures = [], []
    ja = json.load(open(os.path.join(da, 'run.json')))
    jb = json.load(open(os.path.join(db, 'run.json')))
    if ja['returncode'] != jb['returncode']:
        failures.append('exit code %d vs %d' % (ja['returncode'],
                                                jb['returncode']))
    elif ja['returncode'] != 0:
        notes.append('both runs failed (exit %d)' % ja['returncode'])
    files_a, files_b = files_of(da), files_of(db)
    for f in files_a:
        if f not in files_b:
            failures.append('%s only in A' % f)
    for f in files_b:
        if f not in files_a:
            failures.append('%s only in B' % f)
    cells = Cells(args.tolerance, args.abs_tolerance)
    n_files = 0
    for f in files_a:
        if f not in files_b:
            continue
        n_files += 1
        pa, pb = os.path.join(da, f), os.path.join(db, f)
        sub = Cells(args.tolerance, args.abs_tolerance)
        if os.path.basename(f) == 'results.txt':
            fail = compare_results(pa, pb, sub, notes)
        else:
            fail = compare_table(pa, pb, sub, notes)
        if fail:
            failures.append(fail if '/' not in f
                            else os.path.dirname(f) + '/' + fail)
        prefix = os.path.dirname(f)
        cells.count += sub.count - len(sub.items)
        for where, a, b in sub.items:
            cells.add((prefix + '/' if prefix else '') + where, a, b)
    screen = compare_screen(da, db)
    if screen:
        notes.append(screen)
    judged = cells.judge()
    exact = args.tolerance == 0 and args.abs_tolerance == 0
    differing = [(w, a, b, eq) for w, a, b, eq in judged
                 if exact or not eq]
    if differing:
        w, a, b, eq = differing[0]
        first = '%s: %s vs %s%s' % (w, a, b,
                                    ' (numerically equal: format only)'
                                    if eq and exact else '')
        failures.insert(0, '%d value(s) differ, first %s'
                        % (len(differing), first))
    within = len(judged) - len(differing)
    if failures:
        return False, 'DIFFERS: ' + '; '.join(failures), notes
    return True, 'identical (%d files, %d values%s)' % (
        n_files, cells.count,
        ', %d within tolerance' % within if within else ''), notes


def compare(args):
    names = select(args.scenes)
    ok_all = True
    for name in names:
        ok, line, notes = compare_scene(os.path.join(args.dir_a, name),
                                        os.path.join(args.dir_b, name), args)
        ok_all = ok_all and ok
        print('%-24s %s' % (name, line))
        for n in notes:
            print('%-24s   note: %s' % ('', n))
    print('all identical' if ok_all else 'BEHAVIOUR DIFFERS')
    return 0 if ok_all else 1


# -------------------------------------------------------------------- main

def select(scenes):
    if not scenes:
        return list(SCENES)
    names = [s.strip() for s in scenes.split(',') if s.strip()]
    for n in names:
        if n not in SCENES:
            raise SystemExit('unknown scene %s; the scenes: %s'
                             % (n, ', '.join(SCENES)))
    return names


def main():
    a = argparse.ArgumentParser(
        description=__doc__.split('\n\n')[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog='See the module docstring (head of this file) for details.')
    sub = a.add_subparsers(dest='command', required=True)
    c = sub.add_parser('capture', help='run the scenes with one binary')
    c.add_argument('--binary', required=True, help='the softsand executable')
    c.add_argument('--out', required=True, help='capture directory')
    c.add_argument('--ranks', type=int, default=1)
    c.add_argument('--scenes', default='',
                   help='comma-separated subset (default: all)')
    c.add_argument('--vtu', action='store_true',
                   help='keep output/write vtu of the scenes (default: '
                        'false; VTU files are not compared anyway)')
    d = sub.add_parser('compare', help='compare two captures')
    d.add_argument('dir_a')
    d.add_argument('dir_b')
    d.add_argument('--tolerance', type=float, default=0.,
                   help='relative tolerance for numdiff (default 0: exact '
                        'text match of the printed digits)')
    d.add_argument('--abs-tolerance', type=float, default=0.,
                   help='absolute tolerance for numdiff (default 0)')
    d.add_argument('--scenes', default='')
    sub.add_parser('list', help='print the scenes')
    args = a.parse_args()
    if args.command == 'capture':
        return capture(args)
    if args.command == 'compare':
        return compare(args)
    for name, (source, overrides) in SCENES.items():
        print('%-24s %s %s' % (name, source if '\n' not in source else
                               '(inline: tests/convergence_study.cc channel)',
                               '; '.join('%s = %s' % o for o in overrides)))
    return 0


if __name__ == '__main__':
    sys.exit(main())
