"""Small helpers for the study drivers: override entries of a deal.II .prm
text, run softsand, read its statistics table."""
import os
import re
import shutil
import subprocess
import time



# Open MPI refuses root and more ranks than cores unless told (CI runs as
# root on 2 cores): every script that imports this module starts mpirun
# with the environment of scripts/mpi_env.sh, from any shell.
MPI_ENVIRONMENT = {
    'OMPI_ALLOW_RUN_AS_ROOT': '1',
    'OMPI_ALLOW_RUN_AS_ROOT_CONFIRM': '1',
    'OMPI_MCA_rmaps_base_oversubscribe': '1',
    'OMP_NUM_THREADS': '1',
    'DEAL_II_NUM_THREADS': '1',
}
for _name, _value in MPI_ENVIRONMENT.items():
    os.environ.setdefault(_name, _value)

def _lines(text):
    """Each line of a .prm text with the subsections it lies in and, for a
    'set' line, its key and value (comment removed); else None, None."""
    stack = []
    for line in text.splitlines():
        s = line.split('#')[0].strip()
        m = re.match(r'subsection\s+(.*)$', s)
        key = value = None
        if m:
            stack.append(m.group(1).strip())
        elif s == 'end':
            stack.pop()
        else:
            m = re.match(r'set\s+(.*?)\s*=\s*(.*)$', s)
            if m:
                key, value = m.group(1), m.group(2).strip()
        yield line, stack, key, value


def set_entry(text, path, value):
    """Set 'subsection a/subsection b/set key' in a .prm text; append the
    subsection block at the end if the entry is not there (ParameterHandler
    accepts a subsection entered twice)."""
    parts = path.split('/')
    sections, key = parts[:-1], parts[-1]
    out, done = [], False
    for line, stack, k, _ in _lines(text):
        if k == key and stack == sections and not done:
            line = line[:line.index('set')] + 'set %s = %s' % (key, value)
            done = True
        out.append(line)
    if not done:
        for i, sec in enumerate(sections):
            out.append('  ' * i + 'subsection ' + sec)
        out.append('  ' * len(sections) + 'set %s = %s' % (key, value))
        for i in reversed(range(len(sections))):
            out.append('  ' * i + 'end')
    return '\n'.join(out) + '\n'


def get_entry(text, path):
    """The value of 'subsection a/subsection b/set key' in a .prm text (the
    last one set), or None."""
    parts = path.split('/')
    sections, key = parts[:-1], parts[-1]
    value = None
    for _, stack, k, v in _lines(text):
        if k == key and stack == sections:
            value = v
    return value


def add_set_argument(parser, what):
    """--set PATH=VALUE (repeatable): override an entry of @p what."""
    parser.add_argument('--set', action='append', default=[], metavar='PATH=VALUE',
                        help='override an entry of %s, e.g. '
                             '"mesh/cells per diameter=6" (repeatable)' % what)


def parse_set(values):
    """The --set values as (path, value) pairs for set_entry."""
    pairs = []
    for v in values:
        if '=' not in v:
            raise SystemExit("--set '%s': expected PATH=VALUE, e.g. "
                             "'fluid/theta=1e6'" % v)
        path, value = v.split('=', 1)
        pairs.append((path.strip(), value.strip()))
    return pairs


def is_number(text):
    """Whether @p text reads as a number (nan and inf included)."""
    try:
        float(text)
        return True
    except ValueError:
        return False


def read_table(path):
    """Rows of a softsand table as dicts (name -> float): a names line, '#'
    lines (one per column with its unit) and rows of numbers. Tables of
    earlier versions name the columns in their only '#' line."""
    names, last_comment, rows = None, '', []
    with open(path) as f:
        for line in f:
            if line.startswith('#'):
                last_comment = line
            elif line.strip():
                if names is None and not is_number(line.split()[0]):
                    names = line.split()
                    continue
                if names is None:
                    names = last_comment.lstrip('#').split()
                rows.append(dict(zip(names, map(float, line.split()))))
    return rows


def read_grains(path):
    """(x, y, z, radius) of each grain of a softsand pack file."""
    grains = []
    with open(path) as f:
        for line in f:
            if line.strip() and not line.startswith('#'):
                grains.append(tuple(float(v) for v in line.split()[:4]))
    return grains


def read_statistics(directory):
    """Rows of <directory>/statistics.txt as dicts (name -> float)."""
    return read_table(os.path.join(directory, 'statistics.txt'))


def timer_sections(text, column='max'):
    """Section -> (calls, time over ranks in s) of the timer table in
    @p text (a later table's rows replace an earlier one's); @p column
    'max' or 'avg' picks the time over ranks. 'total': the wall clock."""
    assert column in ('max', 'avg')
    sections = {}
    for line in text.splitlines():
        m = re.match(r'\|\s*([^|]+?)\s*\|\s*(\d+)\s*\|\s*[\d.e+-]+s\s+\d+\s*\|'
                     r'\s*([\d.e+-]+)s\s*\|\s*([\d.e+-]+)s', line)
        if m:
            seconds = m.group(4) if column == 'max' else m.group(3)
            sections[m.group(1)] = (int(m.group(2)), float(seconds))
        m = re.match(r'\|\s*Total wallclock time elapsed\s*\|\s*([\d.e+-]+)s',
                     line)
        if m:
            sections['total'] = (1, float(m.group(1)))
    return sections


def fresh_output(text, directory):
    """Remove @p directory unless @p text restarts from its checkpoint
    (simulation control/restart = true): softsand refuses to start a new
    run in a directory that holds an earlier run's results, and a study
    rerun replaces its own."""
    restart = (get_entry(text, 'simulation control/restart') or '').lower()
    if restart not in ('true', 'yes', '1'):
        shutil.rmtree(directory, ignore_errors=True)


def run(softsand, text, workdir, name, ranks=1, overrides=()):
    """Write <workdir>/<name>.prm with the overrides applied, run it, and
    return (last statistics row, wall time in s)."""
    for path, value in overrides:
        text = set_entry(text, path, value)
    outdir = os.path.join(workdir, name)
    text = set_entry(text, 'output/directory', outdir)
    text = set_entry(text, 'output/write vtu', 'false')
    text = set_entry(text, 'output/verbosity', 'quiet')
    prm = os.path.join(workdir, name + '.prm')
    os.makedirs(workdir, exist_ok=True)
    with open(prm, 'w') as f:
        f.write(text)
    fresh_output(text, outdir)
    cmd = [softsand, prm]
    if ranks > 1:
        cmd = ['mpirun', '-np', str(ranks)] + cmd
    start = time.time()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - start
    if proc.returncode != 0:
        return None, wall, proc.stderr.strip().splitlines()[-1:]
    return read_statistics(outdir)[-1], wall, []


def pyplot():
    """matplotlib.pyplot with the file backend, or None (and a message) where
    matplotlib is missing: the studies print their tables without it."""
    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        return plt
    except ImportError:
        print('(matplotlib not available: no plot; apt-get install python3-matplotlib '
              'and run with /usr/bin/python3)')
        return None
