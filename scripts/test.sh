#!/usr/bin/env bash
# Set up (install + build, see setup.sh) and run the whole test suite with
# two concurrent tests; MPI tests use two ranks.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/mpi_env.sh
cd build
ctest -j2 --output-on-failure "$@"
