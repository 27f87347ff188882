#!/usr/bin/env bash
# cmake --install into a fresh prefix laid out like /usr/local, then use it from there:
# the Python package from Debian's python3 (PYTHONPATH standing in for /usr/local's
# dist-packages, which Debian's sys.path holds) and the installed facet-render.
set -euo pipefail
build_dir="$1"
python_destination="$2"
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
echo "install tree ok"
