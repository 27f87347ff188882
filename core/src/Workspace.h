#pragma once

// The renderer's state between renders: the plan, every phase's buffers (kept so that
// re-rendering the same scene at the same size allocates nothing), and what the previous
// frame was (History.h). The members that run the phases are in Renderer.cpp, the list of
// phases; the bookkeeping around them (the planes, the plan, the counts, the history) is in
// Workspace.cpp.

#include <memory>
#include <optional>
#include <vector>

#include "Frame.h"
#include "History.h"
#include "MeshCache.h"
#include "PhaseRunner.h"
#include "Plan.h"
#include "Raster.h"
#include "Setup.h"
#include "Shade.h"
#include "ThreadPool.h"
#include "TileGrid.h"
#include "Transform.h"
#include "ViewCulling.h"
#include "facet/Renderer.h"

namespace facet {

struct Renderer::Workspace {
  std::unique_ptr<detail::ThreadPool> pool;
  RenderPlan plan;
  detail::ShadingChoice shading;
  std::optional<detail::FrameTransform> transform;
  detail::TileGrid grid;
  detail::MeshCache cache;
  std::vector<detail::Box> bounds;  // per mesh, for the lights
  std::vector<detail::FrameMesh> meshes;
  detail::ViewCulling viewCulling;
  detail::PointRanges pointRanges;
  HugePageVector<detail::WindowVertex> vertices;
  std::vector<detail::MeshRange> sortRanges;
  detail::DrawOrder order;
  detail::SetupBuffers setup;
  detail::PolygonBuffers polygons;
  std::vector<detail::PaintCounts> tiles;
  detail::FrontDepthBlocks frontBlocks;    // a two-pass frame's (Raster.h)
  std::vector<std::uint8_t> coveredCells;  // scratch: detail::estimateCoveredPixels
  std::vector<detail::MeshRange> deferredBlockRanges, latePointRanges;  // scratch
  detail::ShadeBuffers shadeBuffers;
  HugePageVector<float> ownDepth;  // the depth plane of a caller without one
  detail::FrameHistory history;

  // The phases (Renderer.cpp). Each returns false when the progress callback asked to stop.
  bool twoPassesMayPay(const detail::FrameInputs& in);
  bool backPointsMayWait(const detail::FrameInputs& in);
  bool frontPassDefersCertainBlocks() const;
  void transformWaitingPoints(detail::PhaseRunner& runner, const detail::FrontDepthBlocks* front);
  detail::RasterContext rasterContext(const detail::FrameInputs& in, const FramebufferView& planes);
  bool rasterInOnePass(const detail::FrameInputs& in, const FramebufferView& planes,
                       detail::PhaseRunner& runner, RenderStats& stats);
  bool rasterInTwoPasses(const detail::FrameInputs& in, const FramebufferView& planes,
                         detail::SetupContext setupContext, detail::PhaseRunner& runner,
                         RenderStats& stats);
  bool renderFull(const detail::FrameInputs& in, const detail::PathChoice& path, int threads,
                  const FramebufferView& planes, detail::PhaseRunner& runner, RenderStats& stats);
  bool renderAgain(const detail::FrameInputs& in, const detail::PathChoice& path, int threads,
                   const FramebufferView& planes, detail::PhaseRunner& runner, RenderStats& stats);
  bool renderGeometry(const detail::FrameInputs& in, const FramebufferView& planes,
                      detail::PhaseRunner& runner, RenderStats& stats);
  bool shadeAndResolve(const detail::FrameInputs& in, const FramebufferView& planes,
                       detail::PhaseRunner& runner, RenderStats& stats);
  bool resolve(const detail::FrameInputs& in, const FramebufferView& planes,
               detail::PhaseRunner& runner);

  // The bookkeeping (Workspace.cpp).
  FramebufferView startFrame(const detail::FrameInputs& in);
  RenderStats statsToStartFrom(const detail::PathChoice& path) const;
  bool lightsNeedBounds(const detail::FrameInputs& in) const;
  void planShading(const detail::FrameInputs& in, const detail::PathChoice& path, int threads);
  void keepPreviousPlan(const detail::PathChoice& path, int threads);
  void prepareMeshes(const Scene& scene);
  void reportViewCulling();
  void countShaded(RenderStats& stats);
  void countGeometry(RenderStats& stats);
  void finishFrame(const detail::FrameInputs& in, const FramebufferView& planes, bool completed,
                   RenderStats& stats);
};

}  // namespace facet
