"""ParaView scripting with Facet: read a mesh, render it with the Facet Render filter (a
camera and two lights), save the image as a PNG. Runs in pvbatch (or pvpython):

    PYTHONPATH=build-plugin/python3-paraview/usr/lib/python3/dist-packages \\
        pvbatch examples/paraview/render_mesh.py ../shared/data/meshes/spot.obj spot.png

The plugin is the one loaded from $PV_PLUGIN_PATH if any, else --plugin, else $FACET_PLUGIN,
else the build tree's (`make plugin` builds it in build-plugin/).
"""
import argparse
import os

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting idiom)

HERE = os.path.dirname(os.path.abspath(__file__))
BUILT_PLUGIN = os.path.join(HERE, "..", "..", "build-plugin", "lib", "paraview-5.11",
                            "plugins", "FacetRender", "FacetRender.so")

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("mesh", help="a surface mesh ParaView reads: .obj, .vtp, .ply, .stl...")
parser.add_argument("image", help="the PNG to write")
parser.add_argument("--plugin", default=os.environ.get("FACET_PLUGIN", BUILT_PLUGIN),
                    help="FacetRender.so (default: $FACET_PLUGIN, else the build tree's)")
parser.add_argument("--size", type=int, nargs=2, default=[800, 600], metavar=("W", "H"))
parser.add_argument("--view", type=float, nargs=3, default=[0.6, 0.35, 1.0],
                    metavar=("X", "Y", "Z"), help="direction from the mesh to the camera")
args = parser.parse_args()

if "FacetRender" not in globals():  # else already loaded from $PV_PLUGIN_PATH
    LoadPlugin(args.plugin, remote=False, ns=globals())

# Facet renders polygonal data: any dataset gives its outer surface.
mesh = ExtractSurface(Input=OpenDataFile(args.mesh))

render = FacetRender(Input=mesh)
render.Size = args.size
render.Background = [0.12, 0.13, 0.16]
render.DiffuseColor = [0.92, 0.88, 0.82]

# The camera looks along --view, toward the origin; Fit Camera To Input (on by default)
# keeps that direction and moves the camera so that the mesh fills the image.
render.CameraPosition = args.view
render.CameraFocalPoint = [0.0, 0.0, 0.0]
render.CameraViewUp = [0.0, 1.0, 0.0]

# Two lights that move with the camera (camera lights: positions in the camera's frame,
# where the camera sits at (0, 0, 1) looking at the origin): a warm key light from the
# upper right and a dim, cool fill light from the left. (Light 1 is a headlight by default.)
render.Light1Type = "Camera Light"
render.Light1Positional = "Directional"
render.Light1Position = [1.0, 0.6, 0.7]
render.Light1FocalPoint = [0.0, 0.0, 0.0]
render.Light1Color = [1.0, 0.85, 0.7]
render.Light1Intensity = 1.0
render.Light2Switch = 1
render.Light2Type = "Camera Light"
render.Light2Positional = "Directional"
render.Light2Position = [-1.0, 0.2, 0.4]
render.Light2FocalPoint = [0.0, 0.0, 0.0]
render.Light2Color = [0.55, 0.7, 1.0]
render.Light2Intensity = 0.3
render.AmbientLightColor = [0.08, 0.08, 0.1]

# The RGBA array is the picture; Depth and CellId stay in the dataset (save a .vti for them).
SaveData(args.image, proxy=render)
print("wrote %s (%d x %d)" % (args.image, args.size[0], args.size[1]))
