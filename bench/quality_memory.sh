#!/usr/bin/env bash
# Peak memory of facet-render at 1920x1080 for 1, 4 and 16 samples per pixel (Phong), from
# /usr/bin/time -v. The supersampled grid is (2x or 4x the side)^2 samples of 12 bytes (RGBA,
# depth, polygon id), allocated at once: 16 samples at 1080p add about 400 MB.
#   bench/quality_memory.sh [BUILD_DIR] [MESH]
set -euo pipefail
build=${1:-build}
mesh=${2:-../shared/data/meshes/stanford-bunny.obj}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '| samples | peak RSS MB | wall s |\n|---:|---:|---:|\n'
for samples in 1 4 16; do
  report=$(/usr/bin/time -v "$build/bin/facet-render" "$mesh" -s 1920x1080 --shading phong \
    --samples "$samples" -o "$out/image.png" -q 2>&1 >/dev/null)
  rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' <<<"$report")
  wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' <<<"$report")
  printf '| %d | %.0f | %s |\n' "$samples" "$(awk -v kb="$rss" 'BEGIN { print kb / 1024 }')" "$wall"
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
