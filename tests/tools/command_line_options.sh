#!/usr/bin/env bash
# Test 'command_line_options': the executable's options. --version names
# the version and the git commit of the sources (or "unknown" outside git);
# --set without its value, an option softsand does not know and a second
# parameter file are refused with a message, not dropped.
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
echo "command_line_options: passed"
