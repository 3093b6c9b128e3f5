#!/usr/bin/env bash
# Sums bench/fuzz_runs.tsv (written by bench/fuzz_run.sh) per target: runs,
# seconds and executions in all, and the runs that left an artifact (crash,
# leak, timeout, out-of-memory). docs/RELIABILITY.md quotes this table.
# Usage: bench/fuzz_totals.sh [LEDGER]
set -euo pipefail
ledger=${1:-$(dirname "$0")/fuzz_runs.tsv}
awk -F'\t' 'NR > 1 {
    runs[$2]++; secs[$2] += $3; execs[$2] += $4
    if ($8 ~ /artifact/) found[$2]++
  }
  END {
    printf "%-20s %5s %8s %14s %9s\n", "target", "runs", "seconds", "executions", "artifacts"
    for (t in runs) printf "%-20s %5d %8d %14d %9d\n", t, runs[t], secs[t], execs[t], found[t]
  }' "$ledger" | { read -r head; echo "$head"; sort; }
