#include "facet/MeshReference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "facet/Error.h"
#include "facet/Lighting.h"
#include "facet/MeshTriangles.h"

namespace facet {
namespace {

// One scene mesh, ready to trace: its triangles, corner normals and points relative to the
// eye in double (Embree gets a float copy).
struct TracedMesh {
  const SceneMesh* source = nullptr;
  PreparedMaterial material;
  std::vector<MeshTriangle> triangles;
  VertexNormals normals;
  std::vector<glm::dvec3> points;

  // The triangle's corners relative to the eye.
  std::array<glm::dvec3, 3> corners(std::uint32_t triangle) const {
    const MeshTriangle& t = triangles[triangle];
    return {points[t.point[0]], points[t.point[1]], points[t.point[2]]};
  }

  // Phong's normal: the corner normals interpolated at the barycentric weights. Where they
  // cancel (or a degenerate polygon's are zero), the triangle's own `face` normal.
  glm::dvec3 normalAt(std::uint32_t triangle, const glm::dvec3& weights,
                      const glm::dvec3& face) const {
    glm::dvec3 sum(0.0);
    for (int k = 0; k < 3; ++k)
      sum += weights[k] * normals.normals[normals.cornerNormal[triangles[triangle].corner[k]]];
    const double length = glm::length(sum);
    if (length > 0.0 && std::isfinite(length)) return sum / length;
    const double faceLength = glm::length(face);
    return faceLength > 0.0 ? face / faceLength : glm::dvec3(0.0, 0.0, 1.0);
  }

  // The polygon's color, as the rasterizer takes it: its own, else the material's (point
  // colors and scalars, interpolated, win over it: pointColorAt).
  Color colorOf(std::uint32_t polygon) const {
    const auto& colors = source->mesh.polygonColors;
    if (colors.empty()) return source->material.color;
    const Rgba8 c = colors[polygon];
    return Color(c.r, c.g, c.b) / 255.0f;
  }
};

std::string meshName(std::size_t i) {
  return "Scene.meshes[" + std::to_string(i) + "]";
}

// Corner normals that index out of their mesh would read out of bounds: refuse them.
void requireFits(const VertexNormals& normals, std::size_t cornerCount, std::size_t i) {
  bool fits = normals.cornerNormal.size() >= cornerCount;
  for (std::size_t k = 0; fits && k < cornerCount; ++k)
    fits = normals.cornerNormal[k] < normals.normals.size();
  if (!fits) {
    throw Error("MeshTracer normals[" + std::to_string(i) + "] do not fit " + meshName(i) + ": " +
                std::to_string(normals.cornerNormal.size()) + " corner entries for " +
                std::to_string(cornerCount) + " corners, or an index past its " +
                std::to_string(normals.normals.size()) + " normals");
  }
}

std::size_t cornerCount(const std::vector<MeshTriangle>& triangles) {
  std::size_t count = 0;
  for (const MeshTriangle& t : triangles)
    count = std::max<std::size_t>({count, t.corner[0] + 1u, t.corner[1] + 1u, t.corner[2] + 1u});
  return count;
}

TracedMesh prepare(const SceneMesh& source, const glm::dvec3& eye, const VertexNormals* given,
                   const VertexNormalOptions& normalOptions, std::size_t i) {
  validate(source.material);
  validatePointData(source.mesh);  // pointColorAt reads the per-point arrays
  TracedMesh mesh;
  mesh.source = &source;
  mesh.material = PreparedMaterial(source.material);
  mesh.triangles = triangulateMesh(source.mesh);
  mesh.normals = given ? *given : computeVertexNormals(source.mesh, normalOptions);
  requireFits(mesh.normals, cornerCount(mesh.triangles), i);
  mesh.points.resize(source.mesh.points.count);
  for (std::size_t p = 0; p < mesh.points.size(); ++p)
    mesh.points[p] = pointAt(source.mesh.points, p) - eye;
  return mesh;
}

// Rejects hits on back faces, for materials that cull them (vtkProperty::BackfaceCulling).
void cullBackFaces(const RTCFilterFunctionNArguments* args) {
  const auto* mesh = static_cast<const TracedMesh*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const auto [a, b, c] = mesh->corners(RTCHitN_primID(args->hit, args->N, i));
    const glm::dvec3 direction(RTCRayN_dir_x(args->ray, args->N, i),
                               RTCRayN_dir_y(args->ray, args->N, i),
                               RTCRayN_dir_z(args->ray, args->N, i));
    if (glm::dot(glm::cross(b - a, c - a), direction) > 0.0) args->valid[i] = 0;
  }
}

struct DeviceDeleter {
  void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
};
struct SceneDeleter {
  void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};

void recordError(void* userPtr, RTCError code, const char* message) {
  auto* error = static_cast<std::string*>(userPtr);
  if (error->empty()) error->assign("Embree error " + std::to_string(code) + ": " + message);
}

// The hit recomputed in double on the triangle Embree found: its barycentric coordinates
// (weights of corners 0, 1, 2; Möller & Trumbore 1997), clamped onto the triangle (Embree's
// float test may accept a ray a rounding outside it).
glm::dvec3 barycentric(const std::array<glm::dvec3, 3>& corner, const glm::dvec3& origin,
                       const glm::dvec3& direction, const RTCHit& hit) {
  const glm::dvec3 e1 = corner[1] - corner[0], e2 = corner[2] - corner[0];
  const glm::dvec3 p = glm::cross(direction, e2);
  const double determinant = glm::dot(e1, p);
  glm::dvec2 uv(hit.u, hit.v);  // seen exactly edge-on: Embree's
  if (determinant != 0.0) {
    const glm::dvec3 s = origin - corner[0], q = glm::cross(s, e1);
    uv =
        glm::max(glm::dvec2(glm::dot(s, p), glm::dot(direction, q)) / determinant, glm::dvec2(0.0));
  }
  if (uv.x + uv.y > 1.0) uv /= uv.x + uv.y;
  return {1.0 - uv.x - uv.y, uv.x, uv.y};
}

}  // namespace

struct MeshTracer::Impl {
  std::string embreeError;
  std::unique_ptr<RTCDeviceTy, DeviceDeleter> device;
  std::unique_ptr<RTCSceneTy, SceneDeleter> scene;
  std::vector<TracedMesh> meshes;
  Shader shader;
  glm::dvec3 eye;
  bool twoSidedLighting;

  void throwIfFailed() const {
    if (!embreeError.empty()) throw Error("MeshTracer: " + embreeError);
  }
  void attach(TracedMesh& mesh, unsigned id);
  std::optional<Color> shade(const Ray& ray, const glm::dvec3& origin, const RTCRayHit& hit) const;
};

void MeshTracer::Impl::attach(TracedMesh& mesh, unsigned id) {
  if (mesh.triangles.empty()) return;  // Embree refuses empty buffers; nothing to hit anyway
  RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               mesh.points.size()));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), mesh.triangles.size()));
  throwIfFailed();
  for (std::size_t p = 0; p < mesh.points.size(); ++p) {
    for (int axis = 0; axis < 3; ++axis)
      vertices[3 * p + axis] = static_cast<float>(mesh.points[p][axis]);
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k)
      indices[3 * t + k] = mesh.triangles[t].point[k];
  }
  rtcSetGeometryUserData(geometry, &mesh);
  if (mesh.source->material.backfaceCulling) {
    rtcSetGeometryIntersectFilterFunction(geometry, cullBackFaces);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene.get(), geometry, id);
  rtcReleaseGeometry(geometry);
  throwIfFailed();
}

std::optional<Color> MeshTracer::Impl::shade(const Ray& ray, const glm::dvec3& origin,
                                             const RTCRayHit& hit) const {
  const TracedMesh& mesh = meshes[hit.hit.geomID];
  const std::array<glm::dvec3, 3> corner = mesh.corners(hit.hit.primID);
  const glm::dvec3 weights = barycentric(corner, origin, ray.direction, hit.hit);
  const glm::dvec3 face = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
  const glm::dvec3 normal = mesh.normalAt(hit.hit.primID, weights, face);
  SurfaceSample sample;
  sample.position = eye + weights.x * corner[0] + weights.y * corner[1] + weights.z * corner[2];
  const bool seenFromBack = glm::dot(face, ray.direction) > 0.0;
  sample.normal = seenFromBack && twoSidedLighting ? -normal : normal;
  sample.toViewer = CameraRays::toViewer(ray);
  const MeshTriangle& triangle = mesh.triangles[hit.hit.primID];
  sample.color = pointColorAt(mesh.source->mesh, triangle.point, weights)
                     .value_or(mesh.colorOf(triangle.polygon));
  return shader.shade(sample, mesh.material);
}

MeshTracer::MeshTracer(const Scene& scene, const glm::dvec3& eye, bool twoSidedLighting,
                       std::span<const VertexNormals> normals,
                       const VertexNormalOptions& normalOptions)
    : impl_(std::make_unique<Impl>()) {
  if (!normals.empty() && normals.size() != scene.meshes.size()) {
    throw Error("MeshTracer got " + std::to_string(normals.size()) + " VertexNormals for " +
                std::to_string(scene.meshes.size()) + " meshes");
  }
  Impl& impl = *impl_;
  impl.shader = Shader(scene.lights);
  impl.eye = eye;
  impl.twoSidedLighting = twoSidedLighting;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    impl.meshes.push_back(
        prepare(scene.meshes[i], eye, normals.empty() ? nullptr : &normals[i], normalOptions, i));
  }
  impl.device.reset(rtcNewDevice(nullptr));
  if (!impl.device)
    throw Error("MeshTracer: Embree device: " + std::to_string(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(impl.device.get(), recordError, &impl.embreeError);
  impl.scene.reset(rtcNewScene(impl.device.get()));
  // Robust: no optimization that trades accuracy (rays must not slip between triangles).
  rtcSetSceneFlags(impl.scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl.scene.get(), RTC_BUILD_QUALITY_HIGH);
  impl.throwIfFailed();
  for (std::size_t i = 0; i < impl.meshes.size(); ++i)
    impl.attach(impl.meshes[i], static_cast<unsigned>(i));
  rtcCommitScene(impl.scene.get());
  impl.throwIfFailed();
}

MeshTracer::~MeshTracer() = default;

std::optional<Color> MeshTracer::operator()(const Ray& ray) const {
  // Start at the near plane: Embree needs tnear ≥ 0, and parallel projection may put the
  // near plane behind the eye.
  const glm::dvec3 origin = ray.origin - impl_->eye + ray.tNear * ray.direction;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit hit{};
  hit.ray.org_x = static_cast<float>(origin.x);
  hit.ray.org_y = static_cast<float>(origin.y);
  hit.ray.org_z = static_cast<float>(origin.z);
  hit.ray.dir_x = static_cast<float>(ray.direction.x);
  hit.ray.dir_y = static_cast<float>(ray.direction.y);
  hit.ray.dir_z = static_cast<float>(ray.direction.z);
  hit.ray.tnear = 0.0f;
  hit.ray.tfar = static_cast<float>(ray.tFar - ray.tNear);
  hit.ray.mask = std::numeric_limits<unsigned>::max();
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene.get(), &context, &hit);
  if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return impl_->shade(ray, origin, hit);
}

ReferenceRender renderMeshReference(const Scene& scene, const Camera& camera, int width, int height,
                                    const ReferenceOptions& options,
                                    std::span<const VertexNormals> normals,
                                    const VertexNormalOptions& normalOptions) {
  validate(camera);
  const MeshTracer tracer(scene, camera.position, options.twoSidedLighting, normals, normalOptions);
  return renderReference(camera, width, height, options,
                         [&](const Ray& ray) { return tracer(ray); });
}

}  // namespace facet
