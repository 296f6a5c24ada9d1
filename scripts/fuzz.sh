#!/usr/bin/env bash
# Runs every fuzz target of fuzz/targets.cpp for SECONDS each (make fuzz). Usage:
#   scripts/fuzz.sh BUILD_DIR SECONDS [TARGET ...]
# Each target starts from its kept inputs (tests/data/fuzz/<target>/) and grows its own corpus in
# BUILD_DIR/corpus/<target>/; whatever crashes, hangs, leaks or throws what the reader does not
# document is written to BUILD_DIR/findings/<target>/ (kept from run to run; a run reports the new
# ones). Exits 1 when a target has a new finding.
set -uo pipefail
build=${1:?build folder}
seconds=${2:?seconds per target}
shift 2
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(case series table sweep checkpoint vtu pvd msh)
here=$(cd "$(dirname "$0")/.." && pwd)
# Leaks inside udunits2 and gmsh are theirs (scripts/lsan.supp); any other leak is a finding.
export LSAN_OPTIONS="suppressions=$here/scripts/lsan.supp:print_suppressions=0"
found=0
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t" "$build/findings/$t"
  before=$(find "$build/findings/$t" -type f | wc -l)
  echo "fuzz: $t for ${seconds} s"
  SNAPJUMP_FUZZ_TARGET=$t OMP_NUM_THREADS=1 "$build/snapjump_fuzz" \
    -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix="$build/findings/$t/" "$build/corpus/$t" "$here/tests/data/fuzz/$t" \
    > "$build/findings/$t.log" 2>&1
  status=$?
  n=$(( $(find "$build/findings/$t" -type f | wc -l) - before ))
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$build/findings/$t.log" | grep -o '[0-9]*$')
  if [ "$n" -gt 0 ] || [ $status -ne 0 ]; then
    found=1
    echo "fuzz: $t: FINDING (exit $status), see $build/findings/$t.log and $build/findings/$t/"
  else
    echo "fuzz: $t: nothing found in ${runs:-?} inputs"
  fi
done
if [ $found -ne 0 ]; then
  echo "fuzz: once a finding is fixed, copy its input into tests/data/fuzz/<target>/: make test replays it"
fi
exit $found
