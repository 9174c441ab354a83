#!/usr/bin/env python3
"""The paper's Fig. 9 from Hele-Shaw sweeps: growth of the fracture area
against the inlet pressure p_i, one series per sweep table, the critical
pressure's bracket (between the highest pressure that did not fracture and
the lowest that did) shaded, and optionally the growth threshold that
decides "fractured" (--threshold).

  /usr/bin/python3 scripts/plots/plot_fracture_area.py \
    --sweep output/hs2000_developed_2cells/sweep.txt \
    --label '2,000 grains, 2 cells per mean d, transient' \
    --out doc/hele_shaw_fig9.png

--sweep and --label may be repeated (one label per table); with --sigma
(one per table, the pistons' confining pressure in Pa) the pressure axis is
p_i / sigma, the dimensionless form of injection experiments. A table is the
`sweep.txt` that scripts/studies/hele_shaw_sweep.py writes (or rewrites with
--summarize): columns p_i[Pa] ... growth_max[mm^2] ... fractured ...; its
header line names them. Growth is plotted on a symmetric-log axis (runs
that did not fracture grow by a pixel or two, 0.1-0.2 mm^2). Needs
matplotlib (/usr/bin/python3 on this machine).
"""
import argparse
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402


def read_sweep(path):
    """Rows of a sweep table as dicts keyed by its header's column names."""
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith('# p_i[Pa]'):
                names = line[1:].split()
            elif line.strip() and not line.startswith('#'):
                if names is None:
                    sys.exit('%s: no header line "# p_i[Pa] ..." before the '
                             'rows (not a hele_shaw_sweep.py table?)' % path)
                values = line.split()
                if len(values) != len(names):
                    sys.exit('%s: a row has %d values, the header %d names: %s'
                             % (path, len(values), len(names), line.strip()))
                rows.append(dict(zip(names, values)))
    if not rows:
        sys.exit('%s: no finished pressure in the table' % path)
    return sorted(rows, key=lambda r: float(r['p_i[Pa]']))


def bracket(rows):
    """(highest p_i that did not fracture, lowest that did), None if open."""
    below = [float(r['p_i[Pa]']) for r in rows if r['fractured'] == 'no']
    above = [float(r['p_i[Pa]']) for r in rows if r['fractured'] == 'yes']
    return (max(below) if below else None, min(above) if above else None)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--sweep', action='append', required=True,
                        help='a sweep.txt table (repeat for more series)')
    parser.add_argument('--label', action='append', default=[],
                        help='legend entry of each --sweep, in order')
    parser.add_argument('--out', required=True, help='PNG file to write')
    parser.add_argument('--threshold', type=float, default=None,
                        help='growth (mm^2) above which a run counts as '
                        'fractured, drawn as a dashed line (the sweep\'s '
                        '--open-area in mm^2)')
    parser.add_argument('--sigma', action='append', type=float, default=[],
                        help="the pistons' confining pressure (Pa) of each "
                        '--sweep, in order: plot against p_i / sigma')
    parser.add_argument('--title', default='Fracture area against inlet '
                        'pressure')
    args = parser.parse_args()
    if args.sigma and len(args.sigma) != len(args.sweep):
        sys.exit('--sigma given %d times for %d --sweep tables: give one '
                 'per table or none' % (len(args.sigma), len(args.sweep)))
    if any(not v > 0 for v in args.sigma):
        sys.exit('--sigma must be > 0 Pa, got %s' % args.sigma)
    if args.label and len(args.label) != len(args.sweep):
        sys.exit('--label given %d times for %d --sweep tables: give one '
                 'per table or none' % (len(args.label), len(args.sweep)))
    labels = args.label or args.sweep

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    markers = 'osd^v<>'
    for k, (path, label) in enumerate(zip(args.sweep, labels)):
        rows = read_sweep(path)
        # p_i = 0 (a control run without flow) has no place on a log axis.
        shown = [r for r in rows if float(r['p_i[Pa]']) > 0]
        scale = args.sigma[k] if args.sigma else 1e3
        p = [float(r['p_i[Pa]']) / scale for r in shown]
        growth = [float(r['growth_max[mm^2]']) for r in shown]
        line, = ax.plot(p, growth, marker=markers[k % len(markers)],
                        label=label)
        low, high = bracket(rows)
        if low is not None and high is not None and 0 < low < high:
            ax.axvspan(low / scale, high / scale, color=line.get_color(),
                       alpha=0.15)
            ax.text((low * high) ** 0.5 / scale, 0.05 + 0.12 * k,
                    ('p_c / sigma %.2g-%.2g' if args.sigma else
                     'p_c %g-%g kPa') % (low / scale, high / scale),
                    transform=ax.get_xaxis_transform(), ha='center',
                    color=line.get_color(), fontsize=8)
        print('%s: %d pressures, critical bracket %s-%s Pa'
              % (path, len(rows), low, high))
    ax.set_xscale('log')
    ax.set_yscale('symlog', linthresh=1.0)
    ax.set_ylim(bottom=0)
    if args.threshold is not None:
        ax.axhline(args.threshold, color='k', ls='--', lw=0.8,
                   label='fracture threshold (%g mm^2)' % args.threshold)
    ax.set_xlabel('inlet pressure over confining pressure, p_i / sigma'
                  if args.sigma else 'inlet pressure p_i [kPa]')
    ax.set_ylabel('growth of the fracture area [mm^2]')
    ax.set_title(args.title, fontsize=10)
    ax.grid(True, which='both', alpha=0.3)
    ax.legend(fontsize=8, loc='best')
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print('wrote', args.out)


if __name__ == '__main__':
    main()
