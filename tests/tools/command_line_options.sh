#!/usr/bin/env bash
# Test 'command_line_options': the executable's options. --version names
# the version and the git commit of the sources (or "unknown" outside git);
# --set without its value, an option softsand does not know and a second
# parameter file are refused with a message, not dropped. An error in a
# scene's set-up is the last line on stderr and is written to log.txt.
# Usage: command_line_options.sh SOURCE_DIR SOFTSAND WORKDIR
set -euo pipefail
src=$1 softsand=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$work"
version=$("$softsand" --version)
echo "$version"
commit=$(git -C "$src" rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
case "$version" in
  "softsand "*" (commit $commit"*")") ;;
  *) echo "FAIL: --version does not name the commit $commit"; exit 1 ;;
esac
refused() { # expected-message arguments...
  local expected=$1
  shift
  if "$softsand" "$@" > out.log 2>&1; then
    echo "FAIL: softsand $* ran"; exit 1
  fi
  grep -q -e "$expected" out.log ||
    { echo "FAIL: softsand $*: no '$expected'"; cat out.log; exit 1; }
  echo "softsand $*: refused ($expected)"
}
refused "--set needs" "$src/parameters/drag_sphere.prm" --set
refused "unexpected argument '--sett'" "$src/parameters/drag_sphere.prm" --sett x
refused "unexpected argument 'b.prm' after the parameter file" a.prm b.prm
refused "is not of the form" "$src/parameters/drag_sphere.prm" --set viscosity
# An error found while the scene is set up (issue 55): the last line on
# stderr (no TimerOutput banner after it), and the last line of log.txt.
if "$softsand" "$src/parameters/free_sphere.prm" --set "output/directory=grain_outside" \
     --set "grains/list=0, 0, 0.5, 5e-4" > stdout.log 2> stderr.log; then
  echo "FAIL: a grain outside the domain ran"; exit 1
fi
last=$(tail -n 1 stderr.log)
case "$last" in
  "softsand: error: grains/list: grain 1"*) ;;
  *) echo "FAIL: the error is not the last line on stderr:"; cat stderr.log; exit 1 ;;
esac
grep -qF "$last" grain_outside/log.txt ||
  { echo "FAIL: log.txt lacks the error:"; cat grain_outside/log.txt; exit 1; }
echo "grain outside the domain: the error ends stderr and log.txt"
echo "command_line_options: passed"
