#include "History.h"

namespace facet::detail {
namespace {

bool sameTarget(const FramebufferView& a, const FramebufferView& b) {
  return a.width == b.width && a.height == b.height && a.depth == b.depth &&
         a.polygonId == b.polygonId;
}

// The rules that change what the geometry phases leave behind (closed surfaces change
// depths at silhouettes; the others only which work runs, but a full render is cheap to
// reason about).
bool sameGeometryRules(const RenderRules& a, const RenderRules& b) {
  return a.geometryOutsideView == b.geometryOutsideView && a.hiddenGeometry == b.hiddenGeometry &&
         a.closedSurfaces == b.closedSurfaces;
}

bool sameShadingRules(const RenderRules& a, const RenderRules& b) {
  return a.lightsThatReachNothing == b.lightsThatReachNothing &&
         a.lightTolerance == b.lightTolerance && a.ambientOnly == b.ambientOnly &&
         a.oneColor == b.oneColor;
}

}  // namespace

PathChoice FrameHistory::choosePath(const FrameInputs& in) const {
  if (!in.rules.incremental) return {RenderPath::Full, "incremental rendering is off"};
  if (!valid_) return {RenderPath::Full, "no previous frame to reuse"};
  if (const char* why = geometryChange(in)) return {RenderPath::Full, why};
  if (const char* why = shadingChange(in)) return {RenderPath::Reshade, why};
  if (!(in.background == background_)) return {RenderPath::Resolve, "the background changed"};
  return {RenderPath::Resolve, "nothing changed"};
}

const char* FrameHistory::geometryChange(const FrameInputs& in) const {
  if (!sameTarget(in.target, target_)) return "another framebuffer or size";
  if (!(in.camera == camera_)) return "the camera changed";
  if (in.visibility != visibility_ || in.depthOutput != depthOutput_ ||
      !sameGeometryRules(in.rules, rules_)) {
    return "the visibility, depth output or geometry rules changed";
  }
  if (in.scene.meshes.size() != meshes_.size()) return "meshes were added or removed";
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const SceneMesh& mesh = in.scene.meshes[m];
    const MeshRecord& record = meshes_[m];
    if (mesh.mesh.version == 0) return "a mesh is unversioned (MeshView::version 0)";
    if (!(MeshIdentity::of(mesh.mesh) == record.geometry)) return "a mesh's geometry changed";
    if (mesh.mesh.closedSurface != record.closedSurface ||
        mesh.material.backfaceCulling != record.material.backfaceCulling) {
      return "a mesh's back-face handling changed";
    }
  }
  return nullptr;
}

const char* FrameHistory::shadingChange(const FrameInputs& in) const {
  if (!(in.scene.lights == lights_)) return "the lights changed";
  if (in.twoSidedLighting != twoSidedLighting_) return "two-sided lighting changed";
  if (!sameShadingRules(in.rules, rules_)) return "the shading rules changed";
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const SceneMesh& mesh = in.scene.meshes[m];
    const MeshRecord& record = meshes_[m];
    if (!(mesh.material == record.material)) return "a material changed";
    const std::span<const Rgba8> colors = mesh.mesh.polygonColors;
    if (colors.data() != record.colors || colors.size() != record.colorCount ||
        mesh.mesh.colorVersion != record.colorVersion) {
      return "a mesh's colors changed";
    }
    if (!colors.empty() && mesh.mesh.colorVersion == 0) {
      return "a mesh's colors are unversioned (MeshView::colorVersion 0)";
    }
  }
  return nullptr;
}

void FrameHistory::remember(const FrameInputs& in, const RenderStats& stats) {
  valid_ = true;
  target_ = in.target;
  camera_ = in.camera;
  visibility_ = in.visibility;
  twoSidedLighting_ = in.twoSidedLighting;
  background_ = in.background;
  depthOutput_ = in.depthOutput;
  rules_ = in.rules;
  lights_ = in.scene.lights;
  meshes_.resize(in.scene.meshes.size());
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    const SceneMesh& mesh = in.scene.meshes[m];
    meshes_[m] = {MeshIdentity::of(mesh.mesh),    mesh.mesh.closedSurface,
                  mesh.mesh.polygonColors.data(), mesh.mesh.polygonColors.size(),
                  mesh.mesh.colorVersion,         mesh.material};
  }
  stats_ = stats;
}

}  // namespace facet::detail
