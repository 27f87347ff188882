#!/usr/bin/env bash
# Checks that the core's software prefetches are in the object code (section 67 of
# bench/core-frame-issue11.md). GCC takes a function or lambda whose only statements are
# __builtin_prefetch for one without effects (IPA pure-const) and drops its calls unless it is
# inlined (sections 51 and 64): a prefetch helper that is not forced inline can vanish without
# any test noticing, as section 47's next-block prefetch likely did.
#
#   check_prefetches.sh FILE...   (a binary linking facet_core, e.g. facet_core_tests, or the
#                                  core's objects; a GCC Release build)
#
# Prints each function holding prefetch instructions (count, name) and fails when one of the
# expected places holds none. Each line below: an extended regular expression on the demangled
# function name, and how many functions matching it must hold a prefetch (one per
# instantiation or Highway target).
set -u
expected=(
  # setUpRun (Setup.cpp): PolygonSetup::load's prefetchAhead, in each <skip, defer> x points x index
  'setUpRun<false, false, facet::detail::Points<'  4
  'setUpRun<true, false, facet::detail::Points<'   4
  'setUpRun<false, true, facet::detail::Points<'   4
  # setUpBackRun (Setup.cpp): prefetchRunsNow in the function, prefetchBlockScan and
  # prefetchRunsAhead in takeBlock (a lambda of its own)
  '^unsigned long facet::detail::\(anonymous namespace\)::setUpBackRun<' 4
  'setUpBackRun<.*\{lambda\(\)#[0-9]+\}::operator\(\)' 4
  # Raster.cpp: the bins' prefetchAhead
  'paintFrontOfTile\(' 1
  'paintBackOfTile\(' 1
  'paintTile<' 3
  # Resolve.cpp: prefetchColors and the row after next, each target
  '::N_[A-Z0-9]+::ResolveColors\(' 5
  # TransformBatch.cpp: projectTyped's lane groups, each target x float/double
  '::N_[A-Z0-9]+::projectTyped<' 10
  # Transform.cpp: transformRange's prefetchRun
  'withTypedMesh<.*transformRange' 1
  # ShadeLit.h: shadeTrianglesCopied (material colors, diffuse), centers and directions
  'shadeTrianglesInBatches<true, \(facet::detail::shading::ColorSource\)0' 4
  'shadeTrianglesInBatches<false, \(facet::detail::shading::ColorSource\)0' 4
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
for ((i = 0; i < ${#expected[@]}; i += 2)); do
  pattern=${expected[$i]} want=${expected[$((i + 1))]}
  have=$(printf '%s\n' "$table" | cut -f2- | grep -cE -- "$pattern")
  if ((have < want)); then
    echo "MISSING: $have of $want functions matching '$pattern' hold a prefetch" >&2
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
