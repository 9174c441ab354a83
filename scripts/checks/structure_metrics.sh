#!/usr/bin/env bash
# Structure metrics of the driver code of a softsand source tree, to compare
# before and after a restructuring:
#   bash scripts/checks/structure_metrics.sh [TREE]     (default: the repository root)
# prints
#   1. the longest functions of the driver files (source/core/*.cc and
#      source/drivers/*.cc): name, file, line count from the line naming the
#      function to its closing brace (Universal Ctags' end: field; lambdas
#      are counted inside their enclosing function);
#   2. the number of 'if constexpr (dim == 3)' / 'if constexpr (dim != 3)'
#      guards in source/core and source/drivers (and their headers in
#      include/softsand/core, include/softsand/drivers), per file;
#   3. include cycles at the file level: X.cc and X.h are one node (a module,
#      named like core/simulator), an edge A -> B when A.h or A.cc includes
#      <softsand/B.h> (source/ and include/softsand/; tests excluded); every
#      elementary cycle is listed (mutual pairs and longer ones);
#   4. the files in source/{fluid,dem,coupling,postprocess,io} and
#      include/softsand/{fluid,dem,coupling,postprocess,io} that include
#      <softsand/core/...>, with what they include;
#   5. the pairs that the 'duplicates' tool finds within the driver files
#      (run on source/ so that pairs between core/ and drivers/ count; rows
#      with both sides in core/*.cc or drivers/*.cc are kept).
# Needs python3 and ctags (Universal Ctags); 'duplicates' if on PATH.
set -euo pipefail
tree="${1:-$(cd "$(dirname "$0")/../.." && pwd)}"
tree="$(cd "$tree" && pwd)"
cd "$tree"

echo "# structure metrics of $tree"
if git -C "$tree" rev-parse --git-dir >/dev/null 2>&1; then
  echo "# git HEAD $(git -C "$tree" rev-parse --short HEAD)," \
       "$(git -C "$tree" status --porcelain -- source include | wc -l)" \
       "changed/untracked paths under source/ include/"
fi

driver_cc=$(ls source/core/*.cc source/drivers/*.cc 2>/dev/null || true)

echo
echo "## 1. longest functions in the driver files (top 8)"
if command -v ctags >/dev/null; then
  # shellcheck disable=SC2086
  ctags --languages=C++ --c++-kinds=f --fields=+ne -o - $driver_cc |
  python3 -c '
import re, sys
rows = []
for line in sys.stdin:
    parts = line.rstrip("\n").split("\t")
    name, path = parts[0], parts[1]
    if name.startswith("__anon"):
        continue
    f = dict(p.split(":", 1) for p in parts[3:] if ":" in p)
    if "line" not in f or "end" not in f:
        continue
    scope = f.get("class", f.get("namespace", ""))
    scope = scope.split("::")[-1] + "::" if scope else ""
    rows.append((int(f["end"]) - int(f["line"]) + 1, scope + name, path,
                 int(f["line"])))
rows.sort(key=lambda r: (-r[0], r[1]))
for n, name, path, line in rows[:8]:
    print("%5d lines  %s  (%s:%d)" % (n, name, path, line))
if rows:
    print("longest: %s, %d lines" % (rows[0][1], rows[0][0]))
'
else
  echo "ctags not found"
fi

echo
echo "## 2. if constexpr (dim == 3) / (dim != 3) guards in source/{core,drivers}, include/softsand/{core,drivers}"
python3 - <<'EOF'
import glob, re
pat = re.compile(r'if\s+constexpr\s*\(\s*dim\s*(==|!=)\s*3\s*\)')
total = {'==': 0, '!=': 0}
for path in sorted(glob.glob('source/core/*') + glob.glob('source/drivers/*') +
                   glob.glob('include/softsand/core/*') +
                   glob.glob('include/softsand/drivers/*')):
    if not path.endswith(('.cc', '.h')):
        continue
    c = {'==': 0, '!=': 0}
    for m in pat.finditer(open(path, errors='replace').read()):
        c[m.group(1)] += 1
    if c['=='] or c['!=']:
        print('  %-40s dim == 3: %d  dim != 3: %d' % (path, c['=='], c['!=']))
    for k in c:
        total[k] += c[k]
print('total: dim == 3: %d, dim != 3: %d, both: %d'
      % (total['=='], total['!='], total['=='] + total['!=']))
EOF

echo
echo "## 3. include cycles between modules (X.cc + X.h = one node)"
python3 - <<'EOF'
import os, re, sys
inc = re.compile(r'^\s*#\s*include\s*<softsand/([^>]+)\.h>', re.M)
edges = {}
for top, strip in (('source', 'source/'), ('include/softsand', 'include/softsand/')):
    for root, _, files in os.walk(top):
        for fn in files:
            if not fn.endswith(('.cc', '.h')):
                continue
            path = os.path.join(root, fn)
            node = os.path.splitext(path[len(strip):])[0]
            targets = edges.setdefault(node, set())
            for m in inc.finditer(open(path, errors='replace').read()):
                if m.group(1) != node:
                    targets.add(m.group(1))
nodes = sorted(set(edges) | set(t for ts in edges.values() for t in ts))
index = {n: i for i, n in enumerate(nodes)}
adj = {n: sorted(edges.get(n, ())) for n in nodes}
# Every elementary cycle, once, starting at its smallest node.
cycles, limit = [], 500
def dfs(start, node, path, on_path):
    for t in adj[node]:
        if index[t] < index[start] or len(cycles) >= limit:
            continue
        if t == start:
            cycles.append(list(path))
        elif t not in on_path:
            on_path.add(t); path.append(t)
            dfs(start, t, path, on_path)
            path.pop(); on_path.discard(t)
for s in nodes:
    dfs(s, s, [s], {s})
cycles.sort(key=lambda c: (len(c), c))
n_edges = sum(len(v) for v in adj.values())
print('%d modules, %d include edges, %d cycle(s)%s'
      % (len(nodes), n_edges, len(cycles),
         ' (stopped at %d)' % limit if len(cycles) >= limit else ''))
for c in cycles:
    kind = 'pair ' if len(c) == 2 else 'cycle'
    print('  %s %s' % (kind, ' -> '.join(c + [c[0]])))
EOF

echo
echo "## 4. non-driver files that include <softsand/core/...>"
n=0
for f in $(ls -d source/{fluid,dem,coupling,postprocess,io} \
              include/softsand/{fluid,dem,coupling,postprocess,io} 2>/dev/null |
           xargs -I{} find {} -type f \( -name '*.cc' -o -name '*.h' \) | sort); do
  hits=$(grep -oE '^\s*#\s*include\s*<softsand/core/[^>]+>' "$f" |
         sed -E 's/.*<softsand\/(core\/[^>]+)>/\1/' | tr '\n' ' ' || true)
  if [ -n "$hits" ]; then
    echo "  $f: $hits"
    n=$((n + 1))
  fi
done
echo "total: $n file(s)"

echo
echo "## 5. duplicates pairs within the driver files"
if command -v duplicates >/dev/null; then
  out=$(duplicates --repo source --most 200 --seconds 120)
  echo "$out" | head -1 | sed 's/^/  (all of source\/: /; s/$/)/'
  rows=$(echo "$out" | grep -E '^D[0-9]+ ' |
         grep -E '^D[0-9]+ (core|drivers)/[^/ ]+\.cc:[0-9-]+ ~ (core|drivers)/[^/ ]+\.cc:' || true)
  if [ -n "$rows" ]; then
    echo "$rows" | sed 's/^/  /'
    echo "total: $(echo "$rows" | wc -l) pair(s)" \
         "($(echo "$rows" | grep -vc ' shape' || true) identical," \
         "$(echo "$rows" | grep -c ' shape' || true) by shape," \
         "$(echo "$rows" | grep -c 'boilerplate' || true) of those boilerplate)"
  else
    echo "total: 0 pair(s)"
  fi
  echo "$out" | grep -E '^\(\+[0-9]+ more pairs\)|^left out:|^incomplete:' |
    sed 's/^/  /' || true
else
  echo "duplicates not on PATH"
fi
