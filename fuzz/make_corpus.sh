#!/usr/bin/env bash
# Regenerates the seed corpus of a fuzz target (fuzz/corpus/<target>/), reproducibly: fuzz
# from nothing for RUNS executions with a fixed seed, then keep the few inputs that cover
# the same code edges (libFuzzer's merge on edge coverage alone). The merge runs without
# FACET_FUZZ_AVOID, and leaves out any input that crashes, so that every seed passes the
# regression run in make test.
#
# Usage: fuzz/make_corpus.sh build-sanitize/bin/facet_fuzz_core [RUNS, default 5000]
set -euo pipefail
fuzzer="$1"
runs="${2:-5000}"
corpus="$(dirname "$0")/corpus/$(basename "$fuzzer")"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/found" "$scratch/seed"
printf '' > "$scratch/seed/empty"
# Step around the open defects while exploring, so that a crash does not end the run early.
FACET_FUZZ_AVOID="${FACET_FUZZ_AVOID:-huge-coordinates,extreme-zoom,bad-ids-with-point-colors}" \
  "$fuzzer" -seed=1 -runs="$runs" -max_len=4096 -timeout=60 \
  "$scratch/found" "$scratch/seed" > "$scratch/fuzz.log" 2>&1 || {
  tail -n 40 "$scratch/fuzz.log"
  exit 1
}
rm -rf "$corpus"
mkdir -p "$corpus"
env -u FACET_FUZZ_AVOID "$fuzzer" -merge=1 -use_counters=0 -use_value_profile=0 -timeout=60 \
  "$corpus" "$scratch/found" > "$scratch/merge.log" 2>&1 || {
  tail -n 40 "$scratch/merge.log"
  exit 1
}
echo "$corpus: $(ls "$corpus" | wc -l) inputs, $(du -sh "$corpus" | cut -f1)"
