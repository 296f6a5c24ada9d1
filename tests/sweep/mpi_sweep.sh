#!/usr/bin/env bash
# The MPI path of `snapjump sweep`: two processes share the runs of a two-run sweep, one run
# each, and a second call finds nothing left to do. Usage: mpi_sweep.sh SNAPJUMP MPIEXEC DATA WORK
set -euo pipefail
exe=$1 mpiexec=$2 data=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
cp "$data/tiny.toml" "$work/"
flags=(-n 2)
if "$mpiexec" --help 2>&1 | grep -q -- --oversubscribe; then
  flags+=(--oversubscribe)
fi
if [ "$(id -u)" -eq 0 ]; then  # CI machines run as root; Open MPI wants it said twice
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
"$mpiexec" "${flags[@]}" "$exe" sweep "$work/tiny.toml" > "$work/first.txt" 2>&1 || {
  cat "$work/first.txt"; exit 1; }
cat "$work/first.txt"
grep -q "over 2 MPI processes" "$work/first.txt"
grep -q "^rank 0: run-000. finished" "$work/first.txt"
grep -q "^rank 1: run-000. finished" "$work/first.txt"
table="$work/tiny-out/sweep.csv"
[ "$(grep -c -E '^run-000[01],capped at 0.001 s ' "$table")" -eq 2 ] || { cat "$table"; exit 1; }
"$mpiexec" "${flags[@]}" "$exe" sweep "$work/tiny.toml" > "$work/second.txt" 2>&1 || {
  cat "$work/second.txt"; exit 1; }
cat "$work/second.txt"
grep -q "2 runs, 0 to do" "$work/second.txt"
if grep -q "started" "$work/second.txt"; then echo "a finished run was started again"; exit 1; fi
echo "MPI sweep: both processes ran, nothing redone"
