#!/usr/bin/env bash
# Checks that the core's software prefetches are in the object code (section 66 of
# bench/core-frame-issue11.md). GCC takes a function or lambda whose only statements are
# __builtin_prefetch for one without effects (IPA pure-const) and drops its calls unless it is
# inlined (sections 51 and 64): a prefetch helper that is not forced inline can vanish without
# any test noticing, as section 47's next-block prefetch likely did.
#
#   check_prefetches.sh FILE...   (a binary linking facet_core, e.g. facet_core_tests, or the
#                                  core's objects; a GCC Release build)
#
# Prints each function holding prefetch instructions (count, name) and fails when one of the
# expected places holds fewer than it should. Each line of `expected`: an extended regular
# expression on the demangled function name; how many functions matching it (one per
# instantiation or Highway target) must hold at least how many prefetch instructions each (the
# sites inlined there); and how many they must hold in all. A function renamed or restructured
# (a template argument, a lambda inlined) may need its line changed: the printed table shows
# what the build holds. Checked to fail with prefetchAfterGap's and prefetchBlockScan's
# always_inline removed (Setup.cpp: both dropped).
set -u
expected=(
  # setUpRun (Setup.cpp): PolygonSetup::load's prefetchAhead, in each <skip, defer> x points x
  # index (prefetchAfterGap: compared below)
  'setUpRun<false, false, facet::detail::Points<' 4 1 0
  'setUpRun<true, false, facet::detail::Points<'  4 1 0
  'setUpRun<false, true, facet::detail::Points<'  4 1 0
  # setUpBackRun (Setup.cpp), each points x index: prefetchRunsNow (2 lines: one per loop
  # GCC makes of it), and in takeBlock (a lambda GCC keeps out of line, or not) prefetchBlockScan
  # (3) and prefetchRunsAhead (2): 7 each, 28 in all
  'setUpBackRun<' 4 2 28
  # Raster.cpp: the bins' prefetchAhead (5 sites)
  'paintFrontOfTile\(' 1 5 0
  'paintBackOfTile\(' 1 5 0
  'paintTile<' 3 5 0
  # Resolve.cpp: prefetchColors and the row after next, each target
  '::N_[A-Z0-9]+::ResolveColors\(' 5 2 0
  # TransformBatch.cpp: projectTyped's points and vertices, each target x float/double
  '::N_[A-Z0-9]+::projectTyped<' 10 2 0
  # Transform.cpp: transformRange's prefetchRun (points, vertices)
  'withTypedMesh<.*transformRange' 1 2 0
  # ShadeLit.h: shadeTrianglesCopied (material colors, diffuse; normals and connectivity),
  # centers and directions x points x index
  'shadeTrianglesInBatches<true, \(facet::detail::shading::ColorSource\)0' 4 2 0
  'shadeTrianglesInBatches<false, \(facet::detail::shading::ColorSource\)0' 4 2 0
)
table=$(for file in "$@"; do
  objdump -d --no-show-raw-insn -C "$file" | awk '
    /^[0-9a-f]+ <.*>:$/ {
      if (name != "" && n > 0) printf "%d\t%s\n", n, name
      name = $0; sub(/^[0-9a-f]+ </, "", name); sub(/>:$/, "", name); n = 0; next
    }
    /^ *[0-9a-f]+:\tprefetch/ { n++ }
    END { if (name != "" && n > 0) printf "%d\t%s\n", n, name }'
done)
echo "$table"
failed=0
for ((i = 0; i < ${#expected[@]}; i += 4)); do
  pattern=${expected[$i]} functions=${expected[$((i + 1))]}
  each=${expected[$((i + 2))]} total=${expected[$((i + 3))]}
  matching=$(printf '%s\n' "$table" | grep -E -- "$(printf '\t')"".*$pattern")
  have=$(printf '%s\n' "$matching" | awk -F'\t' -v each="$each" '$1 >= each { n++ } END { print n + 0 }')
  sum=$(printf '%s\n' "$matching" | awk -F'\t' '{ s += $1 } END { print s + 0 }')
  if ((have < functions || sum < total)); then
    echo "MISSING: $have functions matching '$pattern' hold $each or more prefetches ($functions" \
      "expected), $sum in all ($total expected)" >&2
    failed=1
  fi
done
# prefetchAfterGap (Setup.cpp): the set-ups that leave out or defer whole blocks hold more
# prefetches than the one that draws every face in one pass, for the same points and index.
count() { printf '%s\n' "$table" | grep -F -- "$1" | cut -f1 | head -1; }
for types in 'Points<float>, facet::detail::Polygons<int>' 'Points<float>, facet::detail::Polygons<long>' \
             'Points<double>, facet::detail::Polygons<int>' 'Points<double>, facet::detail::Polygons<long>'; do
  base=$(count "setUpRun<false, false, facet::detail::$types")
  for gap in 'true, false' 'false, true'; do
    have=$(count "setUpRun<$gap, facet::detail::$types")
    if ((${have:-0} <= ${base:-0})); then
      echo "MISSING: setUpRun<$gap, $types> holds ${have:-0} prefetches, no more than" \
        "setUpRun<false, false, ...>'s ${base:-0} (prefetchAfterGap dropped?)" >&2
      failed=1
    fi
  done
done
exit $failed
