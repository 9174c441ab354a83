#!/usr/bin/env python3
"""Run a command and print its peak resident memory on stderr as
'peak_memory_kB <N> rank <R>' (the largest child's ru_maxrss): put it between
mpirun and the program to measure each rank,

  mpirun -np 2 python3 scripts/benchmarks/peak_memory.py build/softsand run.prm
"""
import os
import resource
import subprocess
import sys

if len(sys.argv) < 2:
    raise SystemExit(__doc__)
code = subprocess.call(sys.argv[1:])
rank = os.environ.get('OMPI_COMM_WORLD_RANK', os.environ.get('PMI_RANK', '0'))
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
sys.stderr.write('peak_memory_kB %d rank %s\n' % (peak, rank))
sys.exit(code)
