#!/usr/bin/env bash
# Runs a Google Test binary as N shards at once (GTEST_TOTAL_SHARDS / GTEST_SHARD_INDEX: every
# test in exactly one shard), each into its own log; prints every shard's log and fails if any
# shard failed. For a suite that runs as one process (the thread-sanitized core tests), whose
# tests mostly keep one core busy: two shards on two cores take ~0.6 of its time.
#
#   run_gtest_shards.sh SHARDS BINARY [ARGS...]
set -u
shards=$1
shift
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
pids=()
for ((index = 0; index < shards; ++index)); do
  GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$index "$@" > "$logs/$index.log" 2>&1 &
  pids+=($!)
done
failed=0
for ((index = 0; index < shards; ++index)); do
  if ! wait "${pids[$index]}"; then
    failed=1
    echo "== shard $index of $shards FAILED"
  fi
  cat "$logs/$index.log"
done
exit $failed
