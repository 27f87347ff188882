#!/usr/bin/env bash
# cmake --install into a fresh prefix laid out like /usr/local, then use it from there:
# the Python package from Debian's python3 (PYTHONPATH standing in for /usr/local's
# dist-packages, which Debian's sys.path holds), the installed facet-render, and
# examples/find_package configured and built against the prefix alone.
set -euo pipefail
build_dir="$1"
python_destination="$2"
example_dir="$3"
mesh="$4"
prefix="$(mktemp -d)"
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build_dir" --prefix "$prefix" > /dev/null
cd "$prefix"  # nothing from the build tree or sources on the path
PYTHONPATH="$prefix/$python_destination" /usr/bin/python3 -c "
import facet
from facet import vtkFacetRenderFilter, vtkFacetLight
assert facet.__file__.startswith('$prefix'), facet.__file__
print('import ok from', facet.__file__)
"
"$prefix/bin/facet-render" --help | head -1
test -f "$prefix/include/facet/Renderer.h"
test -f "$prefix/include/facet-vtk/vtkFacetRenderFilter.h"

# find_package(Facet) from another project: only the prefix on CMAKE_PREFIX_PATH.
cmake -S "$example_dir" -B "$prefix/example-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER_LAUNCHER="$(command -v ccache || true)" \
  > "$prefix/example-configure.log" || { cat "$prefix/example-configure.log"; exit 1; }
grep -q "^Facet_DIR:PATH=$prefix/" "$prefix/example-build/CMakeCache.txt" ||
  { echo "find_package(Facet) did not find the installed prefix"; exit 1; }
cmake --build "$prefix/example-build" > "$prefix/example-build.log" ||
  { cat "$prefix/example-build.log"; exit 1; }
"$prefix/example-build/facet-turntable" "$mesh" "$prefix/frame"
for frame in 0 1 2 3 4 5 6 7; do
  test "$(stat -c %s "$prefix/frame-$frame.png")" -gt 1000
done
cmp -s "$prefix/frame-0.png" "$prefix/frame-2.png" && { echo "the turntable did not turn"; exit 1; }
echo "install tree ok"
