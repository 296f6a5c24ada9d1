#!/usr/bin/env bash
# The 3D step's thread scaling on this machine: bench_step's BM_StepScaling at 1, 2, 4, ... threads
# up to the core count, for the default cap and the graded one, printed as a table of ms per step,
# particle-steps per second, speed-up over one thread and parallel efficiency. Usage:
#   scripts/thread_scaling.sh [BUILD_DIR] [REPETITIONS]
# (BUILD_DIR defaults to build/, which `make build` makes; REPETITIONS, default 3, are
# alternated by Google Benchmark and the median is taken.) Run it on an otherwise idle machine;
# OMP_PROC_BIND and OMP_PLACES are left to the caller (e.g. OMP_PROC_BIND=close OMP_PLACES=cores).
set -euo pipefail
build=${1:-build}
reps=${2:-3}
bench="$build/bench_step"
[ -x "$bench" ] || { echo "thread_scaling: $bench not found: run make build first" >&2; exit 2; }
json=$(mktemp)
trap 'rm -f "$json"' EXIT
"$bench" --benchmark_filter='BM_StepScaling' --benchmark_repetitions="$reps" \
  --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
  --benchmark_format=json > "$json"
python3 - "$json" <<'PY'
import json, sys
rows = {}
for b in json.load(open(sys.argv[1]))["benchmarks"]:
    if b.get("aggregate_name") != "median":
        continue
    _, threads, graded = b["run_name"].split("/")[:3]
    rows[(int(graded), int(threads))] = (b["real_time"], b["particle_steps_per_s"], b["particles"])
print(f"{'mesh':8} {'particles':>9} {'threads':>7} {'ms/step':>9} {'Mparticle-steps/s':>18} "
      f"{'speed-up':>8} {'efficiency':>10}")
for (graded, threads), (ms, rate, n) in sorted(rows.items()):
    one = rows[(graded, 1)][0]
    print(f"{'graded' if graded else 'default':8} {int(n):9d} {threads:7d} {ms:9.3f} "
          f"{rate / 1e6:18.3f} {one / ms:8.2f} {one / ms / threads:10.2f}")
PY
