// Quality modes by visibility-buffer shading (QualityRenderer.h): the Renderer paints the
// sample grid's polygon ids; the passes below read them.
//   1. visible polygons: those the Renderer lit (Renderer::shownPolygons), the ids the
//      samples show;
//   2. per visible polygon: its flat-shading bound (estimate, adaptive) and, for Gouraud,
//      its lit corners;
//   3. the estimate per sample and per pixel (it reads the flat colors, so it runs before
//      the samples are shaded again in place);
//   4. per output pixel: shade its samples again where the mode asks, average, round.
// Each pass writes only its own elements, so every thread count gives the same bytes.
// Flat at one sample per pixel, 2 and 3 are the render's own (EstimateHook.h): its shade
// phase bounds the polygons it lights, its resolve estimates each band of rows it resolves;
// here only what it did not bound (meshes lit without direct light) and the rows' sums.

#include "facet/QualityRenderer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "Assert.h"
#include "EstimateHook.h"
#include "EstimateRows.h"
#include "FlatErrorBoundBatch.h"
#include "FlatErrorBoundOfMesh.h"
#include "MeshAccess.h"
#include "MeshCache.h"
#include "RendererInputs.h"
#include "ShownPolygons.h"
#include "Validate.h"
#include "facet/Conventions.h"
#include "facet/Error.h"
#include "facet/PolygonNormal.h"
#include "facet/Reference.h"

namespace facet {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Color toColor(Rgba8 c) {
  return Color(c.r, c.g, c.b) / 255.0f;
}

int gridSide(int samplesPerPixel) {
  return samplesPerPixel == 16 ? 4 : samplesPerPixel == 4 ? 2 : 1;
}

// Rows per task of the per-pixel passes.
constexpr std::size_t kRowsPerTask = 4;
constexpr std::size_t kPolygonsPerTask = 1 << 12;

// The smallest cosine between a unit axis and the corner normals (−1 for a zero one).
double smallestCosine(const glm::dvec3& axis, std::span<const glm::dvec3> normals) {
  double smallest = 1.0;
  for (const glm::dvec3& n : normals)
    smallest = std::min(smallest, n == glm::dvec3(0.0) ? -1.0 : glm::dot(axis, n));
  return smallest;
}

PolygonShape shapeOf(std::span<const glm::dvec3> corners, std::span<const glm::dvec3> normals) {
  PolygonShape shape;
  const std::optional<glm::dvec3> normal = corners.size() == 3
                                               ? triangleNormal(corners[0], corners[1], corners[2])
                                               : polygonNormal(corners);
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& c : corners)
    sum += c;
  shape.center = sum / static_cast<double>(corners.size());
  for (const glm::dvec3& c : corners)
    shape.radius = std::max(shape.radius, glm::length(c - shape.center));
  if (!normal || !std::isfinite(shape.radius)) return shape;  // degenerate: zero normal
  shape.normal = *normal;
  shape.cosNormalSpread = smallestCosine(*normal, normals);
  return shape;
}

// The range of the corners' colors; idAt(k) is corner k's point id.
template <class IdAt>
void addCornerColors(PolygonShape& shape, std::span<const Rgba8> pointColors, std::size_t count,
                     const IdAt& idAt) {
  shape.pointColors = true;
  shape.cornerColorLow = Color(1.0f);
  shape.cornerColorHigh = Color(0.0f);
  for (std::size_t k = 0; k < count; ++k) {
    const Color c = toColor(pointColors[idAt(k)]);
    shape.cornerColorLow = glm::min(shape.cornerColorLow, c);
    shape.cornerColorHigh = glm::max(shape.cornerColorHigh, c);
  }
}

// With a scalar texture the colors a polygon shows are the texels its corners' coordinates
// span (interpolation stays within their range, and the lookup is monotonic), which may lie
// outside the corner texels. A NaN coordinate interpolates to NaN, which looks up (0, 0).
template <class IdAt>
void addTextureColors(PolygonShape& shape, const ColorTexture& texture, std::size_t count,
                      const IdAt& idAt) {
  shape.pointColors = true;
  std::size_t columns[2] = {SIZE_MAX, 0}, rows[2] = {SIZE_MAX, 0};
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t id = idAt(k);
    const double s = texture.coordinates[2 * id], t = texture.coordinates[2 * id + 1];
    const bool nan = std::isnan(s) || std::isnan(t);
    columns[0] = std::min(columns[0], nan ? 0 : texture.column(s));
    columns[1] = std::max(columns[1], texture.column(s));
    rows[0] = std::min(rows[0], nan ? 0 : ColorTexture::row(t));
    rows[1] = std::max(rows[1], ColorTexture::row(t));
  }
  shape.cornerColorLow = Color(1.0f);
  shape.cornerColorHigh = Color(0.0f);
  for (std::size_t row = rows[0]; row <= rows[1]; ++row) {
    for (std::size_t column = columns[0]; column <= columns[1]; ++column) {
      const Color c = toColor(texture.texels[row * texture.width + column]);
      shape.cornerColorLow = glm::min(shape.cornerColorLow, c);
      shape.cornerColorHigh = glm::max(shape.cornerColorHigh, c);
    }
  }
}

// The colors a polygon's corners can show: the texels of a scalar texture, else the point
// colors; nothing without either.
template <class IdAt>
void addColors(PolygonShape& shape, const MeshView& mesh, std::size_t count, const IdAt& idAt) {
  if (!mesh.scalarTexture.empty()) {
    addTextureColors(shape, mesh.scalarTexture, count, idAt);
  } else if (!mesh.pointColors.empty()) {
    addCornerColors(shape, mesh.pointColors, count, idAt);
  }
}

// One polygon's corners: points, point ids and corner normals (scratch space, reused from
// polygon to polygon).
struct Corners {
  std::vector<glm::dvec3> points, normals;
  std::vector<std::size_t> ids;
};

// Calls each(p, corners) for the polygons p in [begin, end) with their corners read (the
// mesh's types dispatched once, not per polygon).
template <class Each>
void forEachPolygon(const MeshView& mesh, const VertexNormals& normals, std::size_t begin,
                    std::size_t end, const Each& each) {
  Corners corners;
  detail::withTypedMesh(mesh, [&](auto points, auto polygons) {
    for (std::size_t p = begin; p < end; ++p) {
      corners.points.clear();
      corners.normals.clear();
      corners.ids.clear();
      for (std::size_t k = 0; k < polygons.size(p); ++k) {
        corners.ids.push_back(polygons.pointId(p, k));
        corners.points.push_back(points[corners.ids.back()]);
        corners.normals.push_back(normals.normals[normals.cornerNormal[polygons.begin(p) + k]]);
      }
      each(p, corners);
    }
  });
}

// A polygon's shape from its corners.
PolygonShape polygonShape(const MeshView& mesh, const Corners& corners) {
  if (corners.points.size() < 3) return {};
  PolygonShape shape = shapeOf(corners.points, corners.normals);
  addColors(shape, mesh, corners.ids.size(), [&](std::size_t k) { return corners.ids[k]; });
  return shape;
}

using detail::roundedUp;

// The spread is kept as a sine, rounded up: a float cosine near 1 moves in steps of ~3e-4 rad
// of the angle. sin α of a spread with cosine c, or 2 for α ≥ 90° (no bound).
float sineOfSpread(double c) {
  if (!(c > 0.0)) return 2.0f;
  return roundedUp(std::sqrt(std::max(0.0, 1.0 - c * c)));
}
double cosineOfSpread(float sine) {
  return sine >= 1.0f ? 0.0 : std::sqrt(1.0 - static_cast<double>(sine) * sine);
}

// Barycentric weights of the ray's intersection with triangle abc (Möller & Trumbore 1997),
// relative to the ray origin, in double; (1/3, 1/3, 1/3) when the ray runs in its plane.
glm::dvec3 barycentric(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       const Ray& ray) {
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 p = glm::cross(ray.direction, e2);
  const double determinant = glm::dot(e1, p);
  if (determinant == 0.0 || !std::isfinite(determinant)) return glm::dvec3(1.0 / 3.0);
  const glm::dvec3 s = ray.origin - a, q = glm::cross(s, e1);
  const double u = glm::dot(s, p) / determinant, v = glm::dot(ray.direction, q) / determinant;
  return {1.0 - u - v, u, v};
}

// Weights clamped onto the triangle (the ray may pass a rounding outside the triangle the
// rasterizer's fixed-point edges gave the sample to).
glm::dvec3 clampedOnto(glm::dvec3 weights) {
  weights = glm::max(weights, glm::dvec3(0.0));
  const double sum = weights.x + weights.y + weights.z;
  return sum > 0.0 ? weights / sum : glm::dvec3(1.0 / 3.0);
}

// A polygon's part of its bound that does not depend on the camera (EstimateHook.h), about
// the normal flat shading lights it by: the rounded one.
detail::BoundTerms termsOf(const Corners& corners) {
  if (corners.points.size() < 3) return {};
  const std::span<const glm::dvec3> points = corners.points;
  const std::optional<glm::dvec3> normal =
      points.size() == 3 ? triangleNormal(points[0], points[1], points[2]) : polygonNormal(points);
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& c : points)
    sum += c;
  const glm::dvec3 center = sum / static_cast<double>(points.size());
  double radius = 0.0;
  for (const glm::dvec3& c : points)
    radius = std::max(radius, glm::length(c - center));
  if (!normal || !std::isfinite(radius)) return {};  // degenerate: the largest bound
  const glm::vec3 rounded(*normal);
  const double c = smallestCosine(glm::normalize(glm::dvec3(rounded)), corners.normals);
  return {roundedUp(radius), sineOfSpread(c)};
}

// A polygon's center and the normal flat shading lights it by (rounded to float, as the
// Renderer's), from its corners: for the polygons the shade phase did not bound.
struct Placement {
  glm::dvec3 center{0.0}, normal{0.0};
};
template <class PointsT, class PolygonsT>
Placement placementOf(PointsT points, PolygonsT polygons, std::size_t polygon) {
  const std::size_t n = polygons.size(polygon);
  const auto corner = [&](std::size_t k) {
    return glm::dvec3(points[polygons.pointId(polygon, k)]);
  };
  Placement placement;
  for (std::size_t k = 0; k < n; ++k)
    placement.center += corner(k);
  placement.center /= static_cast<double>(n);
  if (const std::optional<glm::dvec3> normal = polygonNormal(n, corner))
    placement.normal = glm::dvec3(glm::vec3(*normal));
  return placement;
}

// The lights as the shade routines without centers see them (EstimateHook.h): when every one
// is directional, the same lights under a parallel view, one-sided (the normal as lit already
// faces the viewer); else nothing.
std::optional<detail::BatchLighting> facingLighting(
    const std::optional<detail::BatchLighting>& lighting) {
  if (!lighting) return std::nullopt;
  for (const detail::BatchLighting::Source& light : lighting->lights) {
    if (!light.directional) return std::nullopt;
  }
  detail::BatchLighting facing = *lighting;
  facing.parallel = true;
  facing.twoSided = false;
  return facing;
}

}  // namespace

const char* toString(Shading shading) {
  switch (shading) {
    case Shading::Flat:
      return "flat";
    case Shading::Gouraud:
      return "gouraud";
    case Shading::Phong:
      return "phong";
  }
  return "unknown";
}

ShadingMesh::ShadingMesh(const MeshView& mesh, const VertexNormalOptions& options,
                         const ParallelFor& parallel) {
  validatePointData(mesh);
  triangles = triangulateMesh(mesh);
  normals = mesh.pointNormals.count > 0 ? fromPointNormals(mesh, mesh.pointNormals)
                                        : computeVertexNormals(mesh, options, parallel);
  firstTriangle.assign(mesh.polygons.count + 1, 0);
  for (const MeshTriangle& t : triangles)
    ++firstTriangle[t.polygon + 1];
  for (std::size_t p = 0; p < mesh.polygons.count; ++p)
    firstTriangle[p + 1] += firstTriangle[p];
  shapes.resize(mesh.polygons.count);
  forEachPolygon(mesh, normals, 0, mesh.polygons.count, [&](std::size_t p, const Corners& corners) {
    shapes[p] = polygonShape(mesh, corners);
  });
}

static_assert(kPolygonsPerTask % detail::kBoundBlock == 0, "updateTerms: whole blocks per task");

// Per scene mesh, its polygons' bound terms for the arrays and version in `key`.
struct QualityRenderer::MeshTerms {
  struct Key {
    detail::MeshIdentity geometry;
    const void* normals = nullptr;  // MeshView::pointNormals
    std::size_t normalCount = 0;
    PointArray::Type normalType = PointArray::Type::Float64;
    friend bool operator==(const Key&, const Key&) = default;
  };
  Key key;
  std::vector<detail::BoundTerms> polygons;
  // The summary-only estimate's (FlatErrorBoundOfMesh.h): per block of kBoundBlock polygons
  // what those with a normal share, and the polygons without one.
  std::vector<detail::MeshBoundExtent> blocks;
  std::vector<std::size_t> degenerate;
};

QualityRenderer::QualityRenderer(Renderer& renderer) : renderer_(renderer) {}

void validate(const QualitySettings& settings) {
  const int s = settings.samplesPerPixel;
  if (s != 1 && s != 4 && s != 16) {
    detail::fail("QualitySettings.samplesPerPixel",
                 "is " + std::to_string(s) + ", must be 1, 4 or 16");
  }
  if (settings.maximumError) {
    detail::requireNonNegative(*settings.maximumError, "QualitySettings.maximumError");
  }
}

namespace {
// Whether the settings shade any sample again (adaptive, or a mesh not flat).
bool reshadesAny(const QualitySettings& settings) {
  const auto smooth = [](Shading s) { return s != Shading::Flat; };
  return settings.maximumError.has_value() ||
         (settings.meshShading.empty()
              ? smooth(settings.shading)
              : std::any_of(settings.meshShading.begin(), settings.meshShading.end(), smooth));
}
}  // namespace

// One render's shared, read-only state for the passes.
struct QualityRenderer::Frame {
  const Scene& scene;
  std::span<const ShadingMesh> meshes;
  const QualitySettings& settings;
  const Camera& camera;
  FramebufferView samples;  // the sample grid the Renderer painted
  int grid;                 // samples per pixel side
  CameraRays rays;          // through the sample grid's pixel centers
  FlatErrorBound bounds;
  Shader shader;
  bool twoSided;
  std::vector<std::size_t> firstPolygon;  // per mesh, and the total
  std::vector<std::size_t> firstCorner;   // per mesh
  std::vector<PreparedMaterial> materials;
  std::span<const MeshTerms> terms;  // per mesh, when `meshes` is empty
  // When `meshes` is empty: the lighting polygons are bounded in batches by, and per mesh
  // its material's terms; nothing for what is bounded one by one (a spot light; point
  // colors, a specular material).
  std::optional<detail::BatchLighting> batchLighting;
  std::vector<std::optional<detail::BatchMaterial>> batchMaterials;
  bool reshading;  // some sample may be shaded again (reshadesAny)

  Frame(const Scene& s, std::span<const ShadingMesh> m, const QualitySettings& q,
        const Camera& view, const FramebufferView& sampleGrid, int side, bool twoSidedLighting)
      : scene(s),
        meshes(m),
        settings(q),
        camera(view),
        samples(sampleGrid),
        grid(side),
        rays(view, sampleGrid.width, sampleGrid.height),
        bounds(s.lights, view, twoSidedLighting),
        shader(s.lights),
        twoSided(twoSidedLighting),
        reshading(reshadesAny(q)) {
    std::size_t polygons = 0, corners = 0;
    for (const SceneMesh& mesh : s.meshes) {
      firstPolygon.push_back(polygons);
      firstCorner.push_back(corners);
      materials.emplace_back(mesh.material);
      polygons += mesh.mesh.polygons.count;
      corners += mesh.mesh.polygons.connectivitySize;
    }
    firstPolygon.push_back(polygons);
  }

  // Flat (no ShadingMeshes): the kept terms, and what the bound's batches take.
  void prepareBatches(std::span<const MeshTerms> meshTerms) {
    terms = meshTerms;
    if (!meshes.empty()) return;
    batchLighting = detail::batchLighting(scene.lights, camera, twoSided);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      const MeshView& mesh = scene.meshes[m].mesh;
      batchMaterials.push_back(mesh.pointColors.empty() && mesh.scalarTexture.empty()
                                   ? detail::batchMaterial(materials[m])
                                   : std::nullopt);
    }
  }

  bool adaptive() const { return settings.maximumError.has_value(); }
  Shading shadingOf(std::size_t mesh) const {
    return settings.meshShading.empty() ? settings.shading : settings.meshShading[mesh];
  }
  bool gouraud(std::size_t mesh) const {
    return !adaptive() && shadingOf(mesh) == Shading::Gouraud;
  }
  bool reshades() const { return reshading; }
  // Adaptive: a polygon whose bound, plus the rounding of its flat color, is within budget.
  bool keepsFlat(float bound) const { return adaptive() && bound + 0.5 <= *settings.maximumError; }
  // Whether a visible polygon of `mesh` (with that bound, when adaptive) is shaded again.
  bool reshadesPolygon(std::size_t mesh, float bound) const {
    return adaptive() ? !keepsFlat(bound) : shadingOf(mesh) != Shading::Flat;
  }

  // (mesh, polygon within it) of a polygon id.
  std::pair<std::size_t, std::size_t> locate(std::size_t id) const {
    const auto next = std::upper_bound(firstPolygon.begin(), firstPolygon.end(), id);
    const std::size_t mesh = static_cast<std::size_t>(next - firstPolygon.begin()) - 1;
    return {mesh, id - firstPolygon[mesh]};
  }

  // Cd of flat shading: the polygon's color, else the material's.
  Color polygonColor(std::size_t mesh, std::size_t polygon) const {
    const auto& colors = scene.meshes[mesh].mesh.polygonColors;
    return colors.empty() ? scene.meshes[mesh].material.color : toColor(colors[polygon]);
  }

  double boundOf(std::size_t mesh, std::size_t polygon, const PolygonShape& shape) const {
    return bounds.bound(shape, materials[mesh], polygonColor(mesh, polygon));
  }
  double boundOf(std::size_t mesh, std::size_t polygon) const {
    return boundOf(mesh, polygon, meshes[mesh].shapes[polygon]);
  }
  // Flat (no ShadingMeshes): a polygon's bound, lit at `center` (null: found from its
  // corners) with `normal`, from its kept terms; rounded up to float.
  float boundOne(std::size_t mesh, std::size_t polygon, const glm::dvec3* center,
                 const glm::dvec3& normal) const {
    const detail::BoundTerms& t = terms[mesh].polygons[polygon];
    if (t.radius < 0.0f) return 255.0f;           // no normal: the largest bound
    if (batchLighting && batchMaterials[mesh]) {  // the shade's float lanes, for their bytes
      const glm::dvec3 at = center ? *center : withPlacement(mesh, polygon).center;
      const float lanes =
          detail::boundOneColumn(*batchLighting, *batchMaterials[mesh], at, normal,
                                 polygonColor(mesh, polygon), t.radius, t.sinNormalSpread);
      if (!std::isnan(lanes)) return lanes;
    }
    PolygonShape shape;
    shape.normal = normal;
    shape.radius = t.radius;
    shape.cosNormalSpread = cosineOfSpread(t.sinNormalSpread);
    const MeshView& view = scene.meshes[mesh].mesh;
    const bool pointColors = !view.pointColors.empty() || !view.scalarTexture.empty();
    if (center && !pointColors) {
      shape.center = *center;
    } else {
      detail::withTypedMesh(view, [&](auto points, auto polygons) {
        shape.center = center ? *center : placementOf(points, polygons, polygon).center;
        if (!pointColors) return;
        addColors(shape, view, polygons.size(polygon),
                  [&](std::size_t k) { return polygons.pointId(polygon, k); });
      });
    }
    return roundedUp(boundOf(mesh, polygon, shape));
  }

  Placement withPlacement(std::size_t mesh, std::size_t polygon) const {
    Placement placement;
    detail::withTypedMesh(scene.meshes[mesh].mesh, [&](auto points, auto polygons) {
      placement = placementOf(points, polygons, polygon);
    });
    return placement;
  }

  // The normal a polygon is lit by, turned toward the viewer when its back is seen.
  glm::dvec3 facing(const PolygonShape& shape, glm::dvec3 normal, const glm::dvec3& point) const {
    if (normal == glm::dvec3(0.0)) return bounds.toViewer(point);
    const bool flip = twoSided && bounds.seenFromBack(shape.center, shape.normal);
    return flip ? -normal : normal;
  }

  // Where a sample's ray meets its polygon: the polygon's triangle whose smallest weight is
  // largest (the one holding the hit), and the weights clamped onto it.
  struct Hit {
    const MeshTriangle* triangle = nullptr;
    glm::dvec3 weights{0.0};
    std::array<glm::dvec3, 3> corners{};
  };
  Hit hit(std::size_t mesh, std::size_t polygon, const Ray& ray) const;
  Color phong(std::size_t mesh, std::size_t polygon, const Hit& hit, const Ray& ray) const;
  void lightCorners(std::size_t mesh, std::size_t polygon, std::span<Color> out,
                    std::span<Color> bright) const;
  Color gouraud(std::size_t mesh, const Hit& hit, std::span<const Color> cornerColors,
                std::span<const Color> cornerBright) const;
  Color shadeSample(std::size_t index, int x, int y, std::span<const Color> cornerColors,
                    std::span<const Color> cornerBright) const;
};

// Gouraud: every corner of the polygon lit with its normal and color; with a scalar texture
// (the color known per sample only) lit for a black surface into `out` and a white one into
// `bright` (QualityRenderer.h).
void QualityRenderer::Frame::lightCorners(std::size_t m, std::size_t polygon, std::span<Color> out,
                                          std::span<Color> bright) const {
  const MeshView& mesh = scene.meshes[m].mesh;
  const ShadingMesh& shading = meshes[m];
  const PolygonShape& shape = shading.shapes[polygon];
  const Color flatColor = polygonColor(m, polygon);
  detail::withTypedMesh(mesh, [&](auto points, auto polygons) {
    for (std::size_t k = 0; k < polygons.size(polygon); ++k) {
      const std::size_t corner = polygons.begin(polygon) + k, point = polygons.pointId(polygon, k);
      SurfaceSample sample;
      sample.position = points[point];
      sample.normal = facing(shape, shading.normals.normals[shading.normals.cornerNormal[corner]],
                             sample.position);
      sample.toViewer = bounds.toViewer(sample.position);
      const std::size_t index = firstCorner[m] + corner;
      if (!mesh.scalarTexture.empty()) {
        sample.color = Color(0.0f);
        out[index] = shader.shade(sample, materials[m]);
        sample.color = Color(1.0f);
        bright[index] = shader.shade(sample, materials[m]);
        continue;
      }
      sample.color = mesh.pointColors.empty() ? flatColor : toColor(mesh.pointColors[point]);
      out[index] = shader.shade(sample, materials[m]);
    }
  });
}

QualityRenderer::Frame::Hit QualityRenderer::Frame::hit(std::size_t m, std::size_t polygon,
                                                        const Ray& ray) const {
  const ShadingMesh& shading = meshes[m];
  Hit found;
  double best = -INFINITY;
  for (std::uint32_t t = shading.firstTriangle[polygon]; t < shading.firstTriangle[polygon + 1];
       ++t) {
    const MeshTriangle& candidate = shading.triangles[t];
    std::array<glm::dvec3, 3> c;
    for (int k = 0; k < 3; ++k)
      c[k] = pointAt(scene.meshes[m].mesh.points, candidate.point[k]);
    const glm::dvec3 w = barycentric(c[0], c[1], c[2], ray);
    const double smallest = std::min({w.x, w.y, w.z});
    if (found.triangle && !(smallest > best)) continue;
    found = {&candidate, w, c};
    best = smallest;
  }
  found.weights = clampedOnto(found.weights);
  return found;
}

Color QualityRenderer::Frame::phong(std::size_t m, std::size_t polygon, const Hit& hit,
                                    const Ray& ray) const {
  const MeshView& mesh = scene.meshes[m].mesh;
  const VertexNormals& normals = meshes[m].normals;
  SurfaceSample sample;
  glm::dvec3 normal(0.0);
  for (int k = 0; k < 3; ++k) {
    sample.position += hit.weights[k] * hit.corners[k];
    normal += hit.weights[k] * normals.normals[normals.cornerNormal[hit.triangle->corner[k]]];
  }
  const PolygonShape& shape = meshes[m].shapes[polygon];
  const double length = glm::length(normal);
  normal = length > 0.0 && std::isfinite(length) ? normal / length : shape.normal;
  sample.normal = facing(shape, normal, sample.position);
  sample.toViewer = CameraRays::toViewer(ray);
  sample.color =
      pointColorAt(mesh, hit.triangle->point, hit.weights).value_or(polygonColor(m, polygon));
  return shader.shade(sample, materials[m]);
}

Color QualityRenderer::Frame::gouraud(std::size_t m, const Hit& hit,
                                      std::span<const Color> cornerColors,
                                      std::span<const Color> cornerBright) const {
  glm::dvec3 dark(0.0), bright(0.0);
  for (int k = 0; k < 3; ++k) {
    const std::size_t corner = firstCorner[m] + hit.triangle->corner[k];
    dark += hit.weights[k] * glm::dvec3(cornerColors[corner]);
    if (!cornerBright.empty()) bright += hit.weights[k] * glm::dvec3(cornerBright[corner]);
  }
  const MeshView& mesh = scene.meshes[m].mesh;
  if (mesh.scalarTexture.empty()) return Color(dark);
  const glm::dvec3 cd(*pointColorAt(mesh, hit.triangle->point, hit.weights));
  return Color(dark + cd * (bright - dark));
}

Color QualityRenderer::Frame::shadeSample(std::size_t index, int x, int y,
                                          std::span<const Color> cornerColors,
                                          std::span<const Color> cornerBright) const {
  const auto [m, polygon] = locate(static_cast<std::size_t>(samples.polygonId[index]));
  const Ray ray = rays.through({x + 0.5, y + 0.5});
  const Hit found = hit(m, polygon, ray);
  if (!found.triangle) return toColor(samples.color[index]);  // no triangle: as painted
  return gouraud(m) ? gouraud(m, found, cornerColors, cornerBright) : phong(m, polygon, found, ray);
}

namespace {

// Calls work(row) for every row in [0, rows), spread over the renderer's threads.
template <class Work>
void forRows(Renderer& renderer, int rows, const Work& work) {
  renderer.parallelFor(static_cast<std::size_t>(rows), kRowsPerTask,
                       [&](std::size_t begin, std::size_t end) {
                         for (std::size_t y = begin; y < end; ++y)
                           work(static_cast<int>(y));
                       });
}

// Whether the summary-only estimate takes the frame (FlatErrorBoundOfMesh.h): no spot light,
// and every mesh diffuse with one colour per polygon; else the per-polygon bounds.
bool summaryApplies(const Scene& scene, std::span<const PreparedMaterial> materials) {
  for (const Light& light : scene.lights.lights)
    if (std::holds_alternative<SpotLight>(light)) return false;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const MeshView& mesh = scene.meshes[m].mesh;
    if (!mesh.pointColors.empty() || !mesh.scalarTexture.empty() || materials[m].specular > 0.0)
      return false;
  }
  return true;
}

// The predicted RMSE and maximum from the rows' sums of pixel estimates (in fixed point:
// exact integers, the same in any order).
void setPredicted(std::span<const detail::EstimateSums> rows, QualityStats& stats) {
  std::uint64_t squares = 0, covered = 0;
  std::uint32_t largest = 0;
  for (const detail::EstimateSums& row : rows) {
    squares += row.squares;
    covered += row.covered;
    largest = std::max(largest, row.largest);
  }
  const double unit = detail::kEstimateUnit;
  stats.predictedMaxError = largest / unit;
  stats.predictedRmse =
      covered > 0 ? std::sqrt(static_cast<double>(squares) / static_cast<double>(covered)) / unit
                  : 0.0;
}

// A count rounded up to an even one (the fixed bounds are read in 32-bit pairs).
std::size_t evenCount(std::size_t count) {
  return count + count % 2;
}

// Sample rows per block of the estimate's pass: the rows just above and below a block's are
// taken by both blocks that read them, 2 in 18.
constexpr int kSampleRowsPerTask = 16;

}  // namespace

QualityRenderer::~QualityRenderer() = default;
QualityRenderer::QualityRenderer(QualityRenderer&&) noexcept = default;

// Per visible polygon: its bound (estimate, adaptive), whether it is shaded again and, for
// Gouraud, its lit corners.
std::size_t QualityRenderer::preparePolygons(const Frame& frame, bool bounds, bool corners) {
  const std::size_t polygons = frame.firstPolygon.back();
  polygonBounds_.resize(bounds ? polygons : 0);  // only the visible ones are set and read
  reshade_.resize(frame.reshades() ? polygons : 0);
  cornerBright_.clear();
  if (corners) {
    std::size_t total = 0;
    bool textured = false;
    for (const SceneMesh& mesh : frame.scene.meshes) {
      total += mesh.mesh.polygons.connectivitySize;
      textured = textured || !mesh.mesh.scalarTexture.empty();
    }
    cornerColors_.resize(total);
    cornerBright_.resize(textured ? total : 0);
  }
  if (bounds && frame.meshes.empty()) {  // flat, one bound per visible polygon and no more
    renderer_.parallelFor(polygons, kPolygonsPerTask, [&](std::size_t begin, std::size_t end) {
      boundFromCorners(frame, begin, end, nullptr);
    });
    return 0;
  }
  const std::size_t blocks = (polygons + kPolygonsPerTask - 1) / kPolygonsPerTask;
  std::vector<std::size_t> reshaded(blocks, 0);
  renderer_.parallelFor(polygons, kPolygonsPerTask, [&](std::size_t begin, std::size_t end) {
    std::size_t count = 0;
    for (std::size_t id = begin; id < end; ++id) {
      if (!shown_[id]) continue;
      const auto [m, polygon] = frame.locate(id);
      if (bounds) polygonBounds_[id] = roundedUp(frame.boundOf(m, polygon));
      if (corners && frame.gouraud(m)) frame.lightCorners(m, polygon, cornerColors_, cornerBright_);
      if (!frame.reshades()) continue;
      reshade_[id] = frame.reshadesPolygon(m, bounds ? polygonBounds_[id] : 0.0f);
      count += reshade_[id];
    }
    reshaded[begin / kPolygonsPerTask] = count;
  });
  std::size_t total = 0;
  for (std::size_t count : reshaded)
    total += count;
  return total;
}

// The bounds of the visible polygons among ids [begin, end) of the meshes `skip` does not
// mark, from their corners and kept terms, one by one (the shade phase bounds the others:
// EstimateHook.h); returns how many.
std::size_t QualityRenderer::boundFromCorners(const Frame& frame, std::size_t begin,
                                              std::size_t end, const std::atomic<bool>* skip) {
  std::size_t count = 0;
  for (std::size_t m = 0; m < frame.terms.size(); ++m) {
    const std::size_t offset = frame.firstPolygon[m], first = std::max(begin, offset),
                      last = std::min(end, frame.firstPolygon[m + 1]);
    if (first >= last || (skip && skip[m].load(std::memory_order_relaxed))) continue;
    detail::withTypedMesh(frame.scene.meshes[m].mesh, [&](auto points, auto polygons) {
      detail::forEachShownPolygon(shown_, first, last, [&](std::size_t id) {
        const std::size_t polygon = id - offset;
        const Placement placement = placementOf(points, polygons, polygon);
        polygonBounds_[id] = frame.boundOne(m, polygon, &placement.center, placement.normal);
        ++count;
      });
    });
  }
  return count;
}

// The estimate per pixel (EstimateRows.h, QualityStats): per sample the largest, over the
// polygons its 3 × 3 neighbourhood shows, of their bound plus how far their flat color is
// from the sample's, plus 0.5 for the sample's rounding; per pixel the mean of its samples',
// plus 0.5 for rounding that mean; 0 where the pixel shows no polygon. All in fixed point
// (kEstimateUnit steps, each rounding up), so the sums are exact integers: the same bytes in
// any order. Then the statistics over covered pixels. Reads the visible polygons' bounds that
// preparePolygons left.
void QualityRenderer::estimate(const Frame& frame, const FramebufferView& target, bool image,
                               QualityStats& stats) {
  const FramebufferView& grid = frame.samples;
  const int g = frame.grid;
  estimate_.resize(image ? static_cast<std::size_t>(target.width) * target.height : 0);
  rowSums_.assign(static_cast<std::size_t>(target.height), {});
  fixedBounds_.resize(evenCount(polygonBounds_.size()));
  renderer_.parallelFor(polygonBounds_.size(), kPolygonsPerTask,
                        [&](std::size_t begin, std::size_t end) {
                          detail::forEachShownPolygon(shown_, begin, end, [&](std::size_t id) {
                            fixedBounds_[id] = detail::fixedBoundOf(polygonBounds_[id]);
                          });
                        });
  const detail::EstimateGrid samples{grid.polygonId, grid.color, fixedBounds_.data(),
                                     nullptr,        grid.width, grid.height};
  // Blocks of pixel rows, taken in turn by one task per thread, each with a space of its own
  // (kept from frame to frame): the blocks' results go to their own rows, in any order.
  const std::size_t rowsPerBlock = static_cast<std::size_t>(std::max(1, kSampleRowsPerTask / g));
  const std::size_t blocks =
      (static_cast<std::size_t>(target.height) + rowsPerBlock - 1) / rowsPerBlock;
  const std::size_t tasks = std::min(blocks, static_cast<std::size_t>(renderer_.threadCount()));
  while (spaces_.size() < tasks)
    spaces_.push_back(std::make_unique<detail::EstimateSpace>());
  std::atomic<std::size_t> nextBlock{0};
  renderer_.parallelFor(tasks, 1, [&](std::size_t task, std::size_t) {
    detail::EstimateSpace& space = *spaces_[task];
    space.resize(grid.width, g);
    for (std::size_t block; (block = nextBlock.fetch_add(1)) < blocks;) {
      const std::size_t begin = block * rowsPerBlock;
      const std::size_t end =
          std::min(begin + rowsPerBlock, static_cast<std::size_t>(target.height));
      // Sample rows r − 1 to end · g, each row's maxima found once; row r estimated once r + 1's
      // are, a pixel row once its g sample rows are.
      const int firstRow = static_cast<int>(begin) * g, lastRow = static_cast<int>(end) * g;
      for (int r = firstRow - 1; r <= lastRow; ++r) {
        if (r >= 0 && r < grid.height) space.findMaxima(samples, r);
        const int estimated = r - 1;
        if (estimated < firstRow) continue;
        space.estimateSamples(samples, estimated, image || g > 1);  // else only the span is read
        if ((estimated + 1) % g != 0) continue;
        const int y = estimated / g;
        const std::uint32_t* pixels = space.pixelEstimates();
        // One sample: the pixels outside the row's covered span are 0.
        const auto [first, last] =
            g == 1 ? space.spans[estimated % 3] : std::array<int, 2>{0, target.width};
        rowSums_[y] = detail::estimateSums(pixels, first, last);
        if (!image) continue;
        float* out = estimate_.data() + static_cast<std::size_t>(y) * target.width;
        for (int x = 0; x < target.width; ++x)  // exact: a power-of-two scale
          out[x] = static_cast<float>(pixels[x]) / static_cast<float>(detail::kEstimateUnit);
      }
    }
  });
  setPredicted(rowSums_, stats);
}

// The hook of a fused estimate (EstimateHook.h) for the render to come.
void QualityRenderer::hookUp(
    const Frame& frame, const detail::BatchLighting* facing,
    detail::FunctionRef<float(std::size_t, std::size_t, const glm::dvec3*, const glm::dvec3&)>
        boundOne,
    bool summary, detail::EstimateHook& hook) {
  const std::size_t meshCount = frame.scene.meshes.size();
  meshTerms_.clear();
  for (const MeshTerms& terms : frame.terms)  // none for the summary: the shade bounds nothing
    meshTerms_.push_back(summary ? nullptr : terms.polygons.data());
  polygonBounds_.resize(frame.firstPolygon.back());
  fixedBounds_.resize(evenCount(polygonBounds_.size()));
  // The pixels' part at one sample per pixel only (a pixel of more samples needs them all).
  const bool pixels = frame.grid == 1;
  rowSums_.assign(pixels ? static_cast<std::size_t>(frame.samples.height) : 0, {});
  const bool image = pixels && frame.settings.errorEstimateImage;
  if (pixels) {
    estimate_.resize(image ? static_cast<std::size_t>(frame.samples.width) * frame.samples.height
                           : 0);
  }
  hook.meshes = frame.scene.meshes.data();
  hook.meshCount = meshCount;
  hook.terms = meshTerms_.data();
  hook.lighting = frame.batchLighting ? &*frame.batchLighting : nullptr;
  hook.facingLighting = facing;
  hook.materials = frame.batchMaterials.data();
  hook.boundOne = boundOne;
  if (summary) blockBounds(frame);
  hook.bounds = summary ? nullptr : polygonBounds_.data();
  hook.fixedBounds = summary ? blockBounds_.data() : fixedBounds_.data();
  hook.boundShift = summary ? detail::kBoundBlockShift : 0;
  hook.bounded = std::make_unique<std::atomic<bool>[]>(meshCount);
  hook.height = frame.samples.height;
  hook.rows = pixels ? rowSums_.data() : nullptr;
  hook.image = image ? estimate_.data() : nullptr;
}

// After a render that took the estimate: the polygons of meshes its shade phase did not bound
// (lit without direct light) bounded here, and then, if there were any or the samples are more
// than one per pixel, the estimate's own pass over the samples (their bounds came after the
// resolve); else the rows' sums.
void QualityRenderer::finishFused(const Frame& frame, const detail::EstimateHook& hook,
                                  const FramebufferView& target, QualityStats& stats) {
  const Clock::time_point start = Clock::now();
  FACET_ASSERT(renderer_.shownPolygons().size() == frame.firstPolygon.back());
  shown_ = renderer_.shownPolygons().data();
  std::atomic<std::size_t> late{0};
  bool all = true;
  for (std::size_t m = 0; m < hook.meshCount; ++m)
    all = all && hook.bounded[m].load(std::memory_order_relaxed);
  if (!all) {
    renderer_.parallelFor(frame.firstPolygon.back(), kPolygonsPerTask,
                          [&](std::size_t begin, std::size_t end) {
                            late += boundFromCorners(frame, begin, end, hook.bounded.get());
                          });
  }
  if (late > 0 || !hook.rows) {
    estimate(frame, target, frame.settings.errorEstimateImage, stats);
  } else {
    setPredicted(rowSums_, stats);
  }
  estimated_ = stats;
  stats.estimateSeconds = secondsSince(start);
}

// The summary-only estimate (QualityStats::predicted*, no image; flat at one sample per
// pixel under lights and materials largestFlatBound takes): the per-pixel rule of the estimate
// with each polygon's bound b_q replaced by its block's, B ≥ b_q (FlatErrorBoundOfMesh.h),
// found before the render (blockBounds) and read by the resolve (EstimateHook.h). Every pixel's
// estimate max_q (D(c_p, c_q) + B_q) + 0.5 is then at least the per-pixel estimate's, in the
// fixed point too (⌈B·unit⌉ ≥ ⌈b·unit⌉), so the RMSE and maximum are (tested): looser where
// a block's worst polygon is worse than the pixel's, and no bound per polygon per frame.
// A polygon without a normal (bound 255, in no block) wins no sample in practice; if one does,
// the per-polygon bounds and the pass over the image, after the render.
void QualityRenderer::estimateSummary(const Frame& frame, const FramebufferView& target,
                                      QualityStats& stats) {
  const Clock::time_point start = Clock::now();
  FACET_ASSERT(renderer_.shownPolygons().size() == frame.firstPolygon.back());
  shown_ = renderer_.shownPolygons().data();
  bool degenerateShown = false;
  for (std::size_t m = 0; m < frame.terms.size(); ++m) {
    for (const std::size_t p : frame.terms[m].degenerate)
      degenerateShown = degenerateShown || shown_[frame.firstPolygon[m] + p] != 0;
  }
  if (degenerateShown) {
    renderer_.parallelFor(
        frame.firstPolygon.back(), kPolygonsPerTask,
        [&](std::size_t begin, std::size_t end) { boundFromCorners(frame, begin, end, nullptr); });
    estimate(frame, target, false, stats);
  } else {
    setPredicted(rowSums_, stats);
  }
  estimated_ = stats;
  stats.estimateSeconds = secondsSince(start);
}

// The bounds of the blocks of polygon ids (blockBounds_, EstimateRows.h's fixed point, an even
// count) for the summary-only estimate: per mesh, each block of its polygons bounded from
// what they share (largestFlatBound); a block of ids that holds the end of one mesh and the
// start of the next takes the larger.
void QualityRenderer::blockBounds(const Frame& frame) {
  const std::size_t ids = frame.firstPolygon.back();
  blockBounds_.assign(evenCount((ids + detail::kBoundBlock - 1) / detail::kBoundBlock), 0);
  for (std::size_t m = 0; m < frame.terms.size(); ++m) {
    const std::vector<detail::MeshBoundExtent>& blocks = frame.terms[m].blocks;
    const SceneMesh& mesh = frame.scene.meshes[m];
    const glm::dvec3 surface = mesh.mesh.polygonColors.empty()
                                   ? glm::min(glm::dvec3(mesh.material.color), kMaxRadiance)
                                   : glm::dvec3(1.0);  // 8-bit colours
    const std::optional<detail::BlockBoundSetup> setup =
        detail::prepareBlockBound(frame.scene.lights, frame.materials[m], surface);
    FACET_ASSERT(setup.has_value());  // summaryApplies
    localBounds_.resize(blocks.size());
    renderer_.parallelFor(blocks.size(), 256, [&](std::size_t begin, std::size_t end) {
      for (std::size_t b = begin; b < end; ++b)
        localBounds_[b] =
            detail::fixedBoundOf(roundedUp(detail::largestFlatBound(*setup, blocks[b])));
    });
    const std::size_t first = frame.firstPolygon[m], count = mesh.mesh.polygons.count;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const std::size_t from = first + b * detail::kBoundBlock;
      const std::size_t to = std::min(from + detail::kBoundBlock, first + count) - 1;
      for (std::size_t g = from / detail::kBoundBlock; g <= to / detail::kBoundBlock; ++g)
        blockBounds_[g] = std::max(blockBounds_[g], localBounds_[b]);
    }
  }
}

// Per output pixel: its samples, shaded again where the mode asks, averaged and rounded once;
// depth and id from the fixed sample (QualityRenderer.h).
void QualityRenderer::shadeAndResolve(const Frame& frame, const FramebufferView& target,
                                      QualityStats& stats) {
  const FramebufferView& grid = frame.samples;
  const int g = frame.grid;
  const float weight = 1.0f / static_cast<float>(g * g);
  std::vector<std::size_t> rowReshaded(static_cast<std::size_t>(target.height), 0);
  forRows(renderer_, target.height, [&](int y) {
    for (int x = 0; x < target.width; ++x) {
      glm::vec4 sum(0.0f);
      for (int j = 0; j < g; ++j) {
        for (int i = 0; i < g; ++i) {
          const int sx = x * g + i, sy = y * g + j;
          const std::size_t index = static_cast<std::size_t>(sy) * grid.width + sx;
          const std::int32_t id = grid.polygonId[index];
          const Rgba8 painted = grid.color[index];
          if (id >= 0 && frame.reshades() && reshade_[id]) {
            sum += glm::vec4(frame.shadeSample(index, sx, sy, cornerColors_, cornerBright_), 1.0f);
            ++rowReshaded[y];
          } else {
            sum += glm::vec4(toColor(painted), painted.a / 255.0f);
          }
        }
      }
      sum *= weight;
      const std::size_t out = static_cast<std::size_t>(y) * target.width + x;
      target.color[out] = toRgba8(Color(sum), sum.a);
      if (g > 1) {
        const std::size_t fixed =
            static_cast<std::size_t>(y * g + g / 2) * grid.width + (x * g + g / 2);
        if (target.depth) target.depth[out] = grid.depth[fixed];  // none without depth output
        target.polygonId[out] = grid.polygonId[fixed];
      }
    }
  });
  for (std::size_t count : rowReshaded)
    stats.samplesReshaded += count;
}

QualityStats QualityRenderer::render(const Scene& scene, std::span<const ShadingMesh> shading,
                                     const Camera& camera, const FramebufferView& target,
                                     const QualitySettings& settings) {
  const Clock::time_point start = Clock::now();
  validate(settings);
  if (!settings.meshShading.empty() && settings.meshShading.size() != scene.meshes.size()) {
    throw Error("QualitySettings.meshShading has " + std::to_string(settings.meshShading.size()) +
                " entries for " + std::to_string(scene.meshes.size()) + " scene meshes");
  }
  QualityStats stats;
  const bool reshades = reshadesAny(settings);
  const int g = gridSide(settings.samplesPerPixel);
  const EstimateKey estimateFor{g, target.width, target.height, settings.errorEstimateImage};
  const std::optional<EstimateKey> estimated =
      std::exchange(estimatedFor_, {});  // until this render's
  if (!settings.estimateError || !settings.errorEstimateImage) estimate_.clear();
  if (!reshades && g == 1 && !settings.estimateError) {
    stats.render = renderer_.render(scene, camera, target);
    stats.totalSeconds = secondsSince(start);
    return stats;
  }
  shading = shadingFor(scene, shading, reshades, settings.estimateError);
  FramebufferView grid = target;
  if (g > 1) {
    const long long side = static_cast<long long>(g) * std::max(target.width, target.height);
    if (side > kMaxImageSide) {
      throw Error("QualityRenderer: " + std::to_string(settings.samplesPerPixel) +
                  " samples per pixel of a " + std::to_string(target.width) + "x" +
                  std::to_string(target.height) + " image need a sample grid side of " +
                  std::to_string(side) + ", above kMaxImageSide (" + std::to_string(kMaxImageSide) +
                  ")");
    }
    samples_.resize(target.width * g, target.height * g);
    grid = samples_.view();
  }
  // Flat: the bounds taken by the render's shade phase, and at one sample per pixel the
  // per-pixel estimate by its resolve (EstimateHook.h). Validated first: the frame's lights
  // and camera are checked as the Renderer checks them, so the same error comes first.
  const bool fused = settings.estimateError && shading.empty();
  if (fused) detail::validateRenderInputs(scene, camera, grid, renderer_.depthOutput());
  std::optional<Frame> fusedFrame;
  std::optional<detail::BatchLighting> facing;
  detail::EstimateHook hook;
  auto boundOne = [&](std::size_t m, std::size_t polygon, const glm::dvec3* center,
                      const glm::dvec3& normal) {
    return fusedFrame->boundOne(m, polygon, center, normal);
  };
  bool summary = false;  // the summary-only estimate (estimateSummary)
  if (fused) {
    fusedFrame.emplace(scene, shading, settings, camera, grid, g, renderer_.twoSidedLighting());
    fusedFrame->prepareBatches(terms_);
    facing = facingLighting(fusedFrame->batchLighting);
    summary =
        g == 1 && !settings.errorEstimateImage && summaryApplies(scene, fusedFrame->materials);
    hookUp(*fusedFrame, facing ? &*facing : nullptr, boundOne, summary, hook);
  }
  struct Unhook {  // also when the render throws
    Renderer& renderer;
    ~Unhook() { renderer.estimateHook_ = nullptr; }
  } unhook{renderer_};
  renderer_.estimateHook_ = fused ? &hook : nullptr;
  stats.render = renderer_.render(scene, camera, grid);
  renderer_.estimateHook_ = nullptr;
  if (stats.render.aborted) {
    if (g > 1) renderer_.render(Scene{}, camera, target);  // a valid, empty image
    stats.totalSeconds = secondsSince(start);
    return stats;
  }
  if (fused && stats.render.plan.path != RenderPath::Resolve) {
    if (summary) {
      estimateSummary(*fusedFrame, target, stats);
    } else {
      finishFused(*fusedFrame, hook, target, stats);
    }
    estimatedFor_ = estimateFor;
    const Clock::time_point phase = Clock::now();
    if (g > 1) shadeAndResolve(*fusedFrame, target, stats);
    stats.shadeSeconds = secondsSince(phase);
    stats.totalSeconds = secondsSince(start);
    return stats;
  }
  Frame frame(scene, shading, settings, camera, grid, g, renderer_.twoSidedLighting());
  frame.prepareBatches(terms_);
  Clock::time_point phase = Clock::now();
  // Only the background changed since this object's last render: same polygons, same flat
  // colors where any polygon shows, so the same estimate (it ignores the background).
  // A kept image serves a request for the summary alone (its image is then dropped).
  const bool keepEstimate = settings.estimateError &&
                            stats.render.plan.path == RenderPath::Resolve && estimated &&
                            estimated->servesFor(estimateFor);
  const bool bounds = (settings.estimateError && !keepEstimate) || frame.adaptive();
  bool corners = false;  // some mesh is Gouraud-shaded: its corners are lit first
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    corners = corners || frame.gouraud(m);
  if (bounds || corners || frame.reshades()) {
    FACET_ASSERT(renderer_.shownPolygons().size() == frame.firstPolygon.back());
    shown_ = renderer_.shownPolygons().data();  // the polygons the render lit: every one shown
    stats.polygonsReshaded = preparePolygons(frame, bounds, corners);
  }
  if (keepEstimate) {
    stats.estimateKept = true;
    stats.predictedRmse = estimated_.predictedRmse;
    stats.predictedMaxError = estimated_.predictedMaxError;
  } else if (settings.estimateError) {
    estimate(frame, target, settings.errorEstimateImage, stats);
    estimated_ = stats;
  }
  if (settings.estimateError) estimatedFor_ = estimateFor;
  stats.estimateSeconds = secondsSince(phase);
  phase = Clock::now();
  if (frame.reshades() || g > 1) shadeAndResolve(frame, target, stats);
  stats.shadeSeconds = secondsSince(phase);
  stats.totalSeconds = secondsSince(start);
  return stats;
}

std::span<const ShadingMesh> QualityRenderer::shadingFor(const Scene& scene,
                                                         std::span<const ShadingMesh> given,
                                                         bool reshades, bool estimates) {
  if (given.empty() && !reshades) {
    owned_.clear();
    if (estimates) updateTerms(scene);
    return {};
  }
  if (!given.empty() && given.size() != scene.meshes.size()) {
    throw Error("QualityRenderer got " + std::to_string(given.size()) + " ShadingMeshes for " +
                std::to_string(scene.meshes.size()) + " scene meshes");
  }
  if (given.empty()) {
    owned_.clear();
    for (const SceneMesh& mesh : scene.meshes)
      owned_.emplace_back(mesh.mesh, VertexNormalOptions{}, parallelOn(renderer_));
    given = owned_;
  }
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    if (given[m].polygonCount() != scene.meshes[m].mesh.polygons.count) {
      throw Error("ShadingMesh " + std::to_string(m) + " has " +
                  std::to_string(given[m].polygonCount()) + " polygons, its scene mesh " +
                  std::to_string(scene.meshes[m].mesh.polygons.count));
    }
  }
  return given;
}

}  // namespace facet

namespace facet {

// The bound terms of the meshes whose arrays or version changed (every render for an
// unversioned mesh), from their corner normals: without keeping the normals themselves.
void QualityRenderer::updateTerms(const Scene& scene) {
  terms_.resize(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const MeshView& mesh = scene.meshes[m].mesh;
    const MeshTerms::Key key{detail::MeshIdentity::of(mesh), mesh.pointNormals.data,
                             mesh.pointNormals.count, mesh.pointNormals.type};
    MeshTerms& terms = terms_[m];
    if (key.geometry.version != 0 && terms.key == key) continue;
    terms = {};  // a mesh that throws leaves nothing behind that claims to be its
    validatePointData(mesh);
    const VertexNormals normals = mesh.pointNormals.count > 0
                                      ? fromPointNormals(mesh, mesh.pointNormals)
                                      : computeVertexNormals(mesh, {}, parallelOn(renderer_));
    terms.polygons.resize(mesh.polygons.count);
    terms.blocks.resize((mesh.polygons.count + detail::kBoundBlock - 1) / detail::kBoundBlock);
    renderer_.parallelFor(
        mesh.polygons.count, kPolygonsPerTask, [&](std::size_t begin, std::size_t end) {
          forEachPolygon(mesh, normals, begin, end, [&](std::size_t p, const Corners& corners) {
            const detail::BoundTerms& t = terms.polygons[p] = termsOf(corners);
            if (t.radius < 0.0f) return;
            // A task's polygons are whole blocks (parallelFor's ranges start at multiples of
            // kPolygonsPerTask, a multiple of kBoundBlock).
            detail::MeshBoundExtent& block = terms.blocks[p >> detail::kBoundBlockShift];
            for (const glm::dvec3& corner : corners.points)
              block.add(t.radius, t.sinNormalSpread, corner);
          });
        });
    for (std::size_t p = 0; p < terms.polygons.size(); ++p)
      if (terms.polygons[p].radius < 0.0f) terms.degenerate.push_back(p);
    terms.key = key;
  }
}

}  // namespace facet
