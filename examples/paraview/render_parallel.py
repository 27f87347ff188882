"""ParaView in parallel with Facet: a mesh spread over the MPI ranks of pvbatch, each rank
rendering its piece with the Facet Render filter, the pieces composited by depth (IceT) onto
rank 0. The image is the one a single process renders of the whole mesh:

    export PYTHONPATH=build-plugin/python3-paraview/usr/lib/python3/dist-packages
    mpirun -np 4 pvbatch --mpi examples/paraview/render_parallel.py \\
        ../shared/data/meshes/spot.obj spot.png --data spot.pvti
    pvbatch examples/paraview/render_parallel.py ../shared/data/meshes/spot.obj spot1.png

(pvserver works alike: `mpirun -np 4 pvserver`, then connect and apply Facet Render.)
The plugin is the one loaded from $PV_PLUGIN_PATH if any, else --plugin, else $FACET_PLUGIN,
else the build tree's (`make plugin` builds it in build-plugin/).
"""
import argparse
import os

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting idiom)
from vtkmodules.vtkIOImage import vtkPNGWriter

HERE = os.path.dirname(os.path.abspath(__file__))
BUILT_PLUGIN = os.path.join(HERE, "..", "..", "build-plugin", "lib", "paraview-5.11",
                            "plugins", "FacetRender", "FacetRender.so")

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("mesh", help="a surface mesh ParaView reads: .obj, .vtp, .ply, .stl...")
parser.add_argument("image", help="the PNG to write")
parser.add_argument("--data", metavar="PVTI",
                    help="also save the whole output (RGBA, Depth, CellId, RankId) as .pvti")
parser.add_argument("--plugin", default=os.environ.get("FACET_PLUGIN", BUILT_PLUGIN),
                    help="FacetRender.so (default: $FACET_PLUGIN, else the build tree's)")
parser.add_argument("--size", type=int, nargs=2, default=[800, 600], metavar=("W", "H"))
args = parser.parse_args()

if "FacetRender" not in globals():  # else already loaded from $PV_PLUGIN_PATH
    LoadPlugin(args.plugin, remote=False, ns=globals())

# A reader that cannot read pieces gives the whole mesh to rank 0; RedistributeDataSet
# spreads its cells over the ranks in compact spatial pieces (and numbers the cells first:
# global cell ids, which become the output's CellId). A reader of partitioned files
# (.pvtp, .pvtu) gives each rank its piece directly.
mesh = OpenDataFile(args.mesh)
spread = RedistributeDataSet(Input=mesh)
spread.GenerateGlobalCellIds = 1
pieces = ExtractSurface(Input=spread)

# Every rank renders its piece with the same camera (fitted to the bounds of all pieces)
# and lights; the filter composites the images onto rank 0.
render = FacetRender(Input=pieces)
render.Size = args.size
render.Background = [0.12, 0.13, 0.16]
render.DiffuseColor = [0.92, 0.88, 0.82]
render.CameraPosition = [0.6, 0.35, 1.0]
render.CameraFocalPoint = [0.0, 0.0, 0.0]
render.CameraViewUp = [0.0, 1.0, 0.0]

# The other ranks' outputs hold no pixels, so a parallel writer (.pvti) saves rank 0's
# image. ParaView has no parallel PNG writer: the script (on rank 0) fetches the image.
if args.data:
    SaveData(args.data, proxy=render)
png = vtkPNGWriter()
png.SetInputData(servermanager.Fetch(render))
png.SetFileName(args.image)
png.Write()
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("wrote %s (%d x %d) from %d rank%s" % (args.image, args.size[0], args.size[1], ranks,
                                             "" if ranks == 1 else "s"))
