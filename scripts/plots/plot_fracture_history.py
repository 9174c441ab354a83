#!/usr/bin/env python3
"""Fracture growth against injection time for one or more Hele-Shaw runs
(a resolution or model comparison at one inlet pressure): the fracture area
of each statistics row minus the run's first, in mm^2, against t in ms.

  /usr/bin/python3 scripts/plots/plot_fracture_history.py \
    --run output/hs2000_developed_2cells/p16000 --label '2 cells per mean d' \
    --run output/hs2000_developed_4cells/p16000 --label '4 cells per mean d' \
    --out FILE.png [--table]

A run is a coupled run's output directory whose statistics have the
`fracture_area` column (postprocessing/fracture area/enabled = true); an
unfinished run plots up to its last row. --table also prints the growth of
every run at the times of the first run's rows that all runs reached ('-'
before a run's first row).
Needs matplotlib (/usr/bin/python3 on this machine).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# prm_tools.py, the shared module, is one folder up
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import prm_tools  # noqa: E402


def growth_history(run):
    """[(t in ms, growth in mm^2)] of a run directory."""
    if not os.path.isfile(os.path.join(run, 'statistics.txt')):
        sys.exit('--run %s: no statistics.txt there (a coupled run\'s output '
                 'directory is expected)' % run)
    rows = prm_tools.read_statistics(run)
    if not rows:
        sys.exit('--run %s: statistics.txt has no rows yet' % run)
    if 'fracture_area' not in rows[0]:
        sys.exit('--run %s: no fracture_area column (run with '
                 'postprocessing/fracture area/enabled = true)' % run)
    start = rows[0]['fracture_area']
    return [(r['time'] * 1e3, (r['fracture_area'] - start) * 1e6) for r in rows]


def growth_at(history, t):
    """Growth at time t (ms): the last row at or before t."""
    value = None
    for time, growth in history:
        if time <= t * (1 + 1e-9):
            value = growth
    return value


def main():
    a = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    a.add_argument('--run', action='append', required=True,
                   help='a run directory (repeat for each run)')
    a.add_argument('--label', action='append', default=[],
                   help='one label per --run (default: the directory)')
    a.add_argument('--out', help='the PNG to write')
    a.add_argument('--table', action='store_true',
                   help='print growth at common times')
    args = a.parse_args()
    if args.label and len(args.label) != len(args.run):
        sys.exit('--label: %d labels for %d runs (give one per --run, or none)'
                 % (len(args.label), len(args.run)))
    if not args.out and not args.table:
        sys.exit('nothing to do: give --out FILE.png and/or --table')
    labels = args.label or args.run
    histories = [growth_history(run) for run in args.run]

    if args.table:
        end = min(h[-1][0] for h in histories)
        print('| t [ms] | ' + ' | '.join('%s: growth [mm^2]' % l for l in labels) + ' |')
        print('|---|' + '---|' * len(labels))
        for t, _ in histories[0]:
            if t <= end * (1 + 1e-9):
                # '-': a run whose first row comes after t.
                print('| %.3f | ' % t + ' | '.join(
                    '-' if g is None else '%.3f' % g
                    for g in (growth_at(h, t) for h in histories)) + ' |')

    if args.out:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        for history, label in zip(histories, labels):
            ax.step([t for t, _ in history], [g for _, g in history],
                    where='post', label=label)
        ax.set_xlabel('injection time t [ms]')
        ax.set_ylabel('fracture growth [mm$^2$]')
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.out, dpi=120)
        print('wrote %s' % args.out)


if __name__ == '__main__':
    main()
