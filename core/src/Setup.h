#pragma once

// Phase 2: set-up. Every polygon becomes triangles in window space: which side the viewer
// sees, culling, triangulation, clipping; each triangle then goes to binning (Binning.h).
// Lighting waits for the shade phase, which lights only the polygons that won a pixel.

#include <cstdint>
#include <span>
#include <vector>

#include "Frame.h"
#include "PhaseRunner.h"
#include "TileGrid.h"
#include "facet/RenderPlan.h"

namespace facet::detail {

// Which polygons a set-up pass takes. A two-pass frame (every face drawn with the depth test,
// Raster.h) sets up the front faces first and puts the back-facing polygons of the meshes that
// draw them off (Chunk::deferredBack); once the tiles' front faces are painted, it sets those
// up, dropping those whose blocks or runs lose everywhere behind them (HiddenBlocks.h).
enum class SetupPass { All, Front, Back };

struct SetupContext {
  std::span<const FrameMesh> meshes;
  const FrameTransform& transform;
  const WindowVertex* vertices;  // every mesh's points, projected (Transform.h)
  const DrawOrder& order;
  const TileGrid& grid;
  std::uint8_t* backFacing;  // out, per polygon id: set for every polygon drawn
  // The depth test is on: back-facing polygons are binned in the chunks' backBins, which the
  // tiles paint after the front faces (Chunk::backBins); painter's order keeps one order.
  bool backFacesLast;
  SetupPass pass = SetupPass::All;
  // SetupPass::Back: the blocks of the front faces painted, which the deferred back faces'
  // blocks and runs are tested against (HiddenBlocks.h); null: none dropped.
  const FrontDepthBlocks* front = nullptr;
  // SetupPass::Front: a back-face block that BackFaceTest proves all back faces (the
  // block's polygons would all be deferred) is deferred whole, none of its polygons loaded or
  // classified (Setup.cpp). Off when the margin or the skipping is off for tests
  // (ScopedBackBlockSettings) or frontPassConeSkipEnabled() is false.
  bool deferCertainBackBlocks = false;
};

// Whether a two-pass frame's front pass defers the back-face blocks that are certainly all
// back faces whole (SetupContext::deferCertainBackBlocks): on unless FACET_FRONT_PASS_CONE=0
// in the environment or enableFrontPassConeSkip(false) (tests, measurements).
void enableFrontPassConeSkip(bool on);
bool frontPassConeSkipEnabled();

// The set-up's chunks (its output) and their ranges.
struct SetupBuffers {
  std::vector<MeshRange> ranges;
  std::vector<Chunk> chunks;
};

// The name of the set-up routine a mesh gets (FrameMesh::skipBackFaces), for the plan.
const char* setupRoutineName(bool skipBackFaces);

// Sets up every polygon, in chunks of draw positions (aligned with meshes unless painter's
// order interleaves them) sized for `threads`.
bool setUpPolygons(PhaseRunner& runner, const SetupContext& context, int threads,
                   SetupBuffers& buffers);

// SetupPass::Back: sets up every chunk's deferred back faces (SetupPass::Front put them off)
// into its back bins, after what the front pass binned.
bool setUpBackFaces(PhaseRunner& runner, const SetupContext& context, SetupBuffers& buffers);

// A two-pass frame's back-face blocks dropped behind the front faces, into `plan`.
void reportHiddenBlocks(std::span<const Chunk> chunks, RenderPlan& plan);

// Adds what the set-up counted (polygons drawn, culled, ...; triangles) to `stats`.
void addSetupCounts(std::span<const Chunk> chunks, RenderStats& stats);

// Tests and measurements: `watch`, when not null, is called on the rendering thread with the
// chunks after each set-up pass (a two-pass frame's front pass, then its back pass), to read
// what their records hold and the storage they keep (Chunk; AppendBuffer::restart).
using SetupWatch = void (*)(std::span<const Chunk> chunks);
void watchSetup(SetupWatch watch);

}  // namespace facet::detail
