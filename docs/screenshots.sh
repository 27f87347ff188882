#!/bin/bash
# Remakes the ParaView pictures in docs/ (not part of the tests): the GUI under Xvfb, driven
# by a ParaView Python script and xdotool, captured with xwd. Needs `make plugin` and
#   apt-get install --no-install-recommends x11-apps xdotool imagemagick
# Run from the repository root: docs/screenshots.sh
set -euo pipefail
root=$PWD
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export PYTHONPATH=$root/build-plugin/python3-paraview/usr/lib/python3/dist-packages
export PV_PLUGIN_PATH=$root/build-plugin/lib/paraview-5.11/plugins/FacetRender
export FACET_PLUGIN=$PV_PLUGIN_PATH/FacetRender.so

# Facet Render applied to a Sphere, a second light switched on.
cat > "$work/panel.py" <<'PY'
from paraview.simple import *
sphere = Sphere(ThetaResolution=32, PhiResolution=16)
render = FacetRender(Input=sphere)
render.Light1Intensity = 0.7
render.Light2Switch = 1
render.Light2Color = [1.0, 0.55, 0.2]
render.Light2Intensity = 0.6
render.Light2Position = [1.0, 1.0, 0.5]
view = GetActiveViewOrCreate("RenderView")
Show(render, view)
Hide(sphere, view)
view.InteractionMode = "2D"
view.OrientationAxesVisibility = 0
ResetCamera(view)
SetActiveSource(render)
Render(view)
PY
echo 'from paraview.simple import *; Sphere(); Show(); Render()' > "$work/menu.py"

# $1: script; $2: what to do once ParaView is up (runs inside xvfb-run).
cat > "$work/session.sh" <<'SH'
#!/bin/bash
shot() { xwd -root -silent | convert xwd:- "$1"; }
paraview --dr -geometry 1600x1200+0+0 --script="$1" > "$(dirname "$1")/paraview.log" 2>&1 &
pid=$!
sleep 35
eval "$2"
kill $pid
wait $pid || true
SH
chmod +x "$work/session.sh"
# The Properties panel: widen the left dock, shrink the pipeline browser, then scroll.
xvfb-run -a -s "-screen 0 1600x1200x24" "$work/session.sh" "$work/panel.py" '
  xdotool mousemove 296 700 mousedown 1
  for x in 310 350 400 450 500 550 600 650 700; do xdotool mousemove $x 700; sleep 0.1; done
  xdotool mouseup 1; sleep 1
  xdotool mousemove 150 506 mousedown 1 sleep 0.3 mousemove 150 400 sleep 0.3 mousemove 150 260 sleep 0.3 mouseup 1
  sleep 2; shot docs/paraview-properties-panel.png
  xdotool mousemove 300 800; for i in $(seq 1 12); do xdotool click 5; sleep 0.1; done
  sleep 1; shot docs/paraview-properties-panel-lower.png'

# Filters > Facet > Facet Render.
export work
xvfb-run -a -s "-screen 0 1600x1200x24" "$work/session.sh" "$work/menu.py" '
  xdotool mousemove 215 10 click 1; sleep 1; xdotool mousemove 240 286; sleep 1
  xdotool mousemove 245 287; sleep 1; shot "$work/menu.png"'
convert "$work/menu.png" -crop 760x460+0+0 docs/paraview-filters-menu.png

# The README's picture: the pvbatch example.
pvbatch examples/paraview/render_mesh.py ../shared/data/meshes/spot.obj \
  docs/paraview-render-mesh-spot.png --view -0.7 0.4 -1
