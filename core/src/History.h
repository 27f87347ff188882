#pragma once

// Incremental rendering: what the previous render drew, and which path the next one needs.
// Scene inputs are compared by value (camera, size, lights, materials, background, rules),
// arrays by identity and version (MeshView::version, colorVersion): geometry that changed,
// or that is unversioned, needs a full render; shading inputs alone a re-shade of the kept
// polygon ids and flags; the background alone a resolve.

#include <cstdint>
#include <vector>

#include "MeshCache.h"
#include "facet/Camera.h"
#include "facet/Framebuffer.h"
#include "facet/RenderPlan.h"
#include "facet/Renderer.h"
#include "facet/Scene.h"

namespace facet::detail {

struct EstimateHook;  // EstimateHook.h

// What a render is asked to draw.
struct FrameInputs {
  const Scene& scene;
  const Camera& camera;
  const FramebufferView& target;
  Visibility visibility;
  bool twoSidedLighting;
  Rgba8 background;
  bool depthOutput;
  const RenderRules& rules;
  EstimateHook* estimate = nullptr;  // QualityRenderer's, for shade and resolve (not compared)
  // Renderer::ResolvedRowsCallback, called by the resolve; null or empty: none.
  const Renderer::ResolvedRowsCallback* resolvedRows = nullptr;
};

struct PathChoice {
  RenderPath path;
  const char* reason;
};

class FrameHistory {
 public:
  // The path a render of these inputs may take after the one remembered.
  PathChoice choosePath(const FrameInputs& inputs) const;
  // Remembers a render that completed, with the counts of the frame it left.
  void remember(const FrameInputs& inputs, const RenderStats& stats);
  // The next render is a full one (a render stopped early, or the caller asked).
  void forget() { valid_ = false; }
  // The counts of the frame remembered.
  const RenderStats& stats() const { return stats_; }

 private:
  struct MeshRecord {
    MeshIdentity geometry;
    bool closedSurface = false;
    const Rgba8* colors = nullptr;
    std::size_t colorCount = 0;
    std::uint64_t colorVersion = 0;
    Material material;
  };
  const char* geometryChange(const FrameInputs& inputs) const;
  const char* shadingChange(const FrameInputs& inputs) const;

  bool valid_ = false;
  FramebufferView target_;
  Camera camera_;
  Visibility visibility_ = Visibility::ZBuffer;
  bool twoSidedLighting_ = true;
  Rgba8 background_;
  bool depthOutput_ = true;
  RenderRules rules_;
  LightSet lights_;
  std::vector<MeshRecord> meshes_;
  RenderStats stats_;
};

}  // namespace facet::detail
