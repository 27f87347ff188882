#!/usr/bin/env bash
# Regenerates the seed corpus of a fuzz target (fuzz/corpus/<target>/): fuzz from nothing
# (and from any corpus directories given) for RUNS executions with a fixed seed, then keep a
# small set of inputs that covers the same code edges (libFuzzer's greedy set-cover merge on
# edge coverage alone). The merge leaves out any input that crashes, so that every seed
# passes the regression run in make test.
#
# Usage: fuzz/make_corpus.sh FUZZER [RUNS [CORPUS_DIR...]]
#   e.g. fuzz/make_corpus.sh build-fuzz/bin/facet_fuzz_core 5000 build-fuzz/fuzzing/corpus/facet_fuzz_core
#   (a build with coverage feedback: make fuzz-build, not make test's build-sanitize)
set -euo pipefail
fuzzer="$1"
runs="${2:-5000}"
shift $(($# < 2 ? $# : 2))
corpus="$(dirname "$0")/corpus/$(basename "$fuzzer")"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/found" "$scratch/seed"
printf '' > "$scratch/seed/empty"
"$fuzzer" -seed=1 -runs="$runs" -max_len=4096 -len_control=0 -timeout=60 \
  -artifact_prefix="$scratch/" \
  "$scratch/found" "$scratch/seed" "$@" > "$scratch/fuzz.log" 2>&1 || {
  tail -n 40 "$scratch/fuzz.log"
  exit 1
}
rm -rf "$corpus"
mkdir -p "$corpus"
"$fuzzer" -set_cover_merge=1 -use_counters=0 -use_value_profile=0 \
  -timeout=60 -artifact_prefix="$scratch/" "$corpus" "$scratch/found" "$@" > "$scratch/merge.log" 2>&1 || {
  tail -n 40 "$scratch/merge.log"
  exit 1
}
echo "$corpus: $(ls "$corpus" | wc -l) inputs, $(du -sb "$corpus" | cut -f1) bytes"
