// libFuzzer target over the core's public API: random meshes (float or double points with
// extreme and special values, 32- or 64-bit ids, polygons of any size with repeated and bad
// ids), every light and material model, cameras (degenerate ones too), image sizes (invalid
// ones too), both visibility modes; each frame rendered on 1 and on 2 threads.
//
// After every render it checks what Facet promises (see README, "Fuzzing and sanitizers"):
// only facet::Error escapes, and it leaves the image untouched; both thread counts agree on
// the error or on every byte; depth is finite and in [0, 1]; ids are −1 or a polygon of the
// scene; background pixels are the background color and alpha, polygon pixels are opaque.

#include <cstdint>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "FuzzInput.h"
#include "facet/Conventions.h"
#include "facet/Error.h"
#include "facet/Renderer.h"

namespace facet::fuzz {
namespace {

Color anyColor(FuzzedDataProvider& in) {
  const float r = toFloat(anyDouble(in, 0.0, 1.0));
  const float g = toFloat(anyDouble(in, 0.0, 1.0));
  return {r, g, toFloat(anyDouble(in, 0.0, 1.0))};
}

// A mesh whose arrays it owns, in the types the input chose, and the view over them.
struct FuzzMesh {
  std::vector<double> xyz64;
  std::vector<float> xyz32;
  std::vector<std::int64_t> offsets64, ids64;
  std::vector<std::int32_t> offsets32, ids32;
  std::vector<Rgba8> colors;
  MeshView view;
};

std::size_t anyVertexCount(FuzzedDataProvider& in) {
  const auto kind = in.ConsumeIntegral<std::uint8_t>();
  if (kind < 16) return in.ConsumeIntegralInRange<std::size_t>(0, 2);  // empty cells
  if (kind < 24) return in.ConsumeIntegralInRange<std::size_t>(7, 64);
  return in.ConsumeIntegralInRange<std::size_t>(3, 6);
}

void makePoints(FuzzedDataProvider& in, const Placement& placement, FuzzMesh& mesh) {
  const std::size_t count = in.ConsumeIntegralInRange<std::size_t>(0, 48);
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3 p = placement.place(anyVector(in, -1.0, 1.0));
    mesh.xyz64.insert(mesh.xyz64.end(), {p.x, p.y, p.z});
  }
  if (in.ConsumeBool()) {
    for (double x : mesh.xyz64)
      mesh.xyz32.push_back(toFloat(x));
    mesh.view.points = PointArray::ofXyz(std::span<const float>(mesh.xyz32));
  } else {
    mesh.view.points = PointArray::ofXyz(std::span<const double>(mesh.xyz64));
  }
}

// Polygons, sometimes with a broken structure that validation must reject: an offset out of
// order or past the connectivity, a point id out of range, a wrong color count.
void makePolygons(FuzzedDataProvider& in, FuzzMesh& mesh) {
  const auto pointCount = static_cast<std::int64_t>(mesh.view.points.count);
  const std::size_t count = in.ConsumeIntegralInRange<std::size_t>(0, 24);
  mesh.offsets64.push_back(0);
  for (std::size_t p = 0; p < count; ++p) {
    const std::size_t n = anyVertexCount(in);
    std::vector<std::int64_t> ids;
    for (std::size_t k = 0; k < n; ++k)
      ids.push_back(anyPointId(in, pointCount, ids));
    mesh.ids64.insert(mesh.ids64.end(), ids.begin(), ids.end());
    mesh.offsets64.push_back(static_cast<std::int64_t>(mesh.ids64.size()));
  }
  if (count > 0 && in.ConsumeIntegralInRange(0, 31) == 0) {
    mesh.offsets64[in.ConsumeIntegralInRange<std::size_t>(0, count)] =
        in.ConsumeIntegralInRange<std::int64_t>(-2,
                                                static_cast<std::int64_t>(mesh.ids64.size()) + 2);
  }
  const auto colorKind = in.ConsumeIntegralInRange(0, 15);
  if (colorKind < 6) {
    std::size_t colorCount = count;
    if (colorKind == 0) colorCount = in.ConsumeBool() ? count + 1 : count - (count > 0);
    for (std::size_t p = 0; p < colorCount; ++p) {
      const auto rgba = in.ConsumeIntegral<std::uint32_t>();
      mesh.colors.push_back(std::bit_cast<Rgba8>(rgba));
    }
  }
  if (in.ConsumeBool()) {
    mesh.view.polygons = PolygonArray::of(mesh.offsets64, mesh.ids64);
  } else {
    // Out-of-range 64-bit values wrap: still out of range, or another id (fine too).
    for (auto o : mesh.offsets64)
      mesh.offsets32.push_back(static_cast<std::int32_t>(o));
    for (auto id : mesh.ids64)
      mesh.ids32.push_back(static_cast<std::int32_t>(id));
    mesh.view.polygons = PolygonArray::of(mesh.offsets32, mesh.ids32);
  }
  mesh.view.polygonColors = mesh.colors;
}

void decideClosedSurface(FuzzedDataProvider& in, FuzzMesh& mesh) {
  switch (in.ConsumeIntegralInRange(0, 3)) {
    case 0:
      mesh.view.closedSurface = true;  // possibly a lie: loses back faces, nothing else
      break;
    case 1:
      try {
        mesh.view.closedSurface = isClosedSurface(mesh.view);
      } catch (const Error&) {
        // bad structure: the render reports it
      }
      break;
    default:
      break;
  }
  if (in.ConsumeIntegralInRange(0, 63) == 0) {  // null arrays with non-zero counts
    if (in.ConsumeBool()) {
      mesh.view.points.data = nullptr;
    } else {
      mesh.view.polygons.connectivity = nullptr;
    }
  }
}

Attenuation anyAttenuation(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange(0, 2)) {
    case 0:
      return NoAttenuation{};
    case 1: {
      QuadraticAttenuation q;
      q.constant = anyDouble(in, 0.0, 2.0);
      q.linear = anyDouble(in, 0.0, 1.0);
      q.quadratic = anyDouble(in, 0.0, 1e-2);
      return q;
    }
    default:
      return FalloffDistanceAttenuation{anyDouble(in, 0.0, 10.0)};
  }
}

SpotCone anyCone(FuzzedDataProvider& in) {
  if (in.ConsumeBool()) {
    const double full = anyDouble(in, 0.0, 180.0);
    return LinearSpotCone{full, anyDouble(in, 0.0, 90.0)};
  }
  const double angle = anyDouble(in, 0.0, 180.0);
  return ExponentSpotCone{angle, anyDouble(in, 0.0, 16.0)};
}

Light anyLight(FuzzedDataProvider& in, const Placement& placement) {
  switch (in.ConsumeIntegralInRange(0, 2)) {
    case 0:
      return DirectionalLight{anyVector(in, -1.0, 1.0), anyColor(in), anyDouble(in, 0.0, 2.0)};
    case 1:
      return PointLight{placement.place(anyVector(in, -3.0, 3.0)), anyColor(in),
                        anyDouble(in, 0.0, 2.0), anyAttenuation(in)};
    default: {
      SpotLight spot;
      spot.position = placement.place(anyVector(in, -3.0, 3.0));
      spot.direction = anyVector(in, -1.0, 1.0);
      spot.color = anyColor(in);
      spot.intensity = anyDouble(in, 0.0, 2.0);
      spot.attenuation = anyAttenuation(in);
      spot.cone = anyCone(in);
      return spot;
    }
  }
}

LightSet anyLights(FuzzedDataProvider& in, const Placement& placement) {
  LightSet lights;
  if (in.ConsumeBool()) lights.ambient = {anyColor(in), anyDouble(in, 0.0, 2.0)};
  const int count = in.ConsumeIntegralInRange(0, 4);
  for (int i = 0; i < count; ++i)
    lights.lights.push_back(anyLight(in, placement));
  return lights;
}

Material anyMaterial(FuzzedDataProvider& in) {
  Material m;
  if (in.ConsumeBool()) return m;  // vtkProperty's defaults
  m.color = anyColor(in);
  if (in.ConsumeBool()) m.ambientColor = anyColor(in);
  m.specularColor = anyColor(in);
  m.ambient = anyDouble(in, 0.0, 1.0);
  m.diffuse = anyDouble(in, 0.0, 1.0);
  m.specular = anyDouble(in, 0.0, 1.0);
  m.specularPower = anyDouble(in, 0.0, 128.0);
  m.diffuseModel = in.ConsumeBool() ? DiffuseModel::Lambert : DiffuseModel::Lerp;
  m.lerpAmbient = anyDouble(in, 0.0, 1.0);
  m.lerpFull = anyDouble(in, 0.0, 1.0);
  m.specularModel = in.ConsumeBool() ? SpecularModel::Phong : SpecularModel::BlinnPhong;
  m.specularMix = in.ConsumeBool() ? SpecularMix::Add : SpecularMix::Blend;
  m.backfaceCulling = in.ConsumeBool();
  return m;
}

// A camera looking at the scene from about 3 units away, or anything else.
Camera anyCamera(FuzzedDataProvider& in, const Placement& placement) {
  Camera camera;
  camera.position = placement.place(glm::dvec3(0.0, 0.0, 3.0) + anyVector(in, -3.0, 3.0));
  camera.focalPoint = placement.place(anyVector(in, -0.5, 0.5));
  camera.viewUp = anyVector(in, -1.0, 1.0);
  camera.viewAngleDegrees = anyDouble(in, 1.0, 179.0);
  camera.parallelProjection = in.ConsumeBool();
  camera.parallelScale = placement.scale * anyDouble(in, 0.0, 3.0);
  camera.nearClip = placement.scale * anyDouble(in, 0.0, 2.0);
  camera.farClip = camera.nearClip + placement.scale * anyDouble(in, 0.0, 10.0);
  if (in.ConsumeIntegralInRange(0, 3) == 0)
    camera.windowCenter = {anyDouble(in, -1.0, 1.0), anyDouble(in, -1.0, 1.0)};
  return camera;
}

// The planes of one render, pre-filled with values no render writes, so that a render that
// throws can be seen to leave them untouched.
struct Target {
  static constexpr Rgba8 kUnwrittenColor{1, 2, 3, 4};
  static constexpr float kUnwrittenDepth = -7.0f;
  static constexpr std::int32_t kUnwrittenId = -7;

  std::vector<Rgba8> color;
  std::vector<float> depth;
  std::vector<std::int32_t> ids;
  FramebufferView view;

  // A view of width × height; an invalid size gets one-pixel planes (it must be refused
  // before anything is written), and sometimes a plane is null.
  Target(int width, int height, int nullPlane) {
    const bool valid =
        width >= 1 && height >= 1 && width <= kMaxImageSide && height <= kMaxImageSide;
    const std::size_t pixels = valid ? static_cast<std::size_t>(width) * height : 1;
    color.assign(pixels, kUnwrittenColor);
    depth.assign(pixels, kUnwrittenDepth);
    ids.assign(pixels, kUnwrittenId);
    view = {width, height, nullPlane == 1 ? nullptr : color.data(),
            nullPlane == 2 ? nullptr : depth.data(), nullPlane == 3 ? nullptr : ids.data()};
  }

  bool untouched() const {
    for (std::size_t i = 0; i < color.size(); ++i) {
      if (!(color[i] == kUnwrittenColor) || depth[i] != kUnwrittenDepth || ids[i] != kUnwrittenId)
        return false;
    }
    return true;
  }
};

struct Outcome {
  std::optional<std::string> error;
  RenderStats stats;
};

Outcome renderOnce(Renderer& renderer, const Scene& scene, const Camera& camera, Target& target) {
  Outcome outcome;
  try {
    outcome.stats = renderer.render(scene, camera, target.view);
  } catch (const Error& e) {
    outcome.error = e.what();
  } catch (const std::exception& e) {
    FUZZ_CHECK(false, "render threw something other than facet::Error: %s", e.what());
  } catch (...) {
    FUZZ_CHECK(false, "render threw something other than facet::Error");
  }
  return outcome;
}

void checkImage(const Target& target, const Outcome& outcome, std::size_t polygonCount,
                Rgba8 background) {
  if (outcome.error) {
    FUZZ_CHECK(target.untouched(), "the render threw '%s' after writing to the image",
               outcome.error->c_str());
    return;
  }
  std::size_t covered = 0;
  for (std::size_t i = 0; i < target.color.size(); ++i) {
    const float d = target.depth[i];
    const std::int32_t id = target.ids[i];
    const Rgba8 c = target.color[i];
    FUZZ_CHECK(d >= 0.0f && d <= 1.0f, "pixel %zu: depth %.9g outside [0, 1] (id %d)", i, d, id);
    FUZZ_CHECK(id >= -1 && (id < 0 || static_cast<std::size_t>(id) < polygonCount),
               "pixel %zu: polygon id %d, the scene has %zu polygons", i, id, polygonCount);
    if (id < 0) {
      FUZZ_CHECK(c == background && d == 1.0f,
                 "pixel %zu: background shows RGBA (%d %d %d %d) depth %.9g, expected (%d %d %d "
                 "%d) depth 1",
                 i, c.r, c.g, c.b, c.a, d, background.r, background.g, background.b, background.a);
    } else {
      FUZZ_CHECK(c.a == 255, "pixel %zu: polygon %d has alpha %d, polygons are opaque", i, id, c.a);
      ++covered;
    }
  }
  if (!outcome.stats.aborted) {
    FUZZ_CHECK(outcome.stats.pixelsCovered == covered,
               "RenderStats::pixelsCovered is %zu, the image shows %zu polygon pixels",
               outcome.stats.pixelsCovered, covered);
  }
}

// Both thread counts throw the same error or paint the same bytes. A render stopped by its
// progress callback may stop before validation finds the error, at a point that depends on
// the thread count: only a finished render must agree.
void checkSameResult(const Target& one, const Outcome& oneOutcome, const Target& two,
                     const Outcome& twoOutcome) {
  const auto finished = [](const Outcome& o) { return o.error || !o.stats.aborted; };
  if (!finished(oneOutcome) || !finished(twoOutcome)) return;
  FUZZ_CHECK(oneOutcome.error == twoOutcome.error, "1 thread: %s; 2 threads: %s",
             oneOutcome.error ? oneOutcome.error->c_str() : "ok",
             twoOutcome.error ? twoOutcome.error->c_str() : "ok");
  if (oneOutcome.error) return;
  for (std::size_t i = 0; i < one.color.size(); ++i) {
    FUZZ_CHECK(one.color[i] == two.color[i] &&
                   std::bit_cast<std::uint32_t>(one.depth[i]) ==
                       std::bit_cast<std::uint32_t>(two.depth[i]) &&
                   one.ids[i] == two.ids[i],
               "pixel %zu differs: 1 thread id %d depth %.9g, 2 threads id %d depth %.9g", i,
               one.ids[i], one.depth[i], two.ids[i], two.depth[i]);
  }
}

// Stops the render at its stopAfter-th progress report (0: never).
Renderer::ProgressCallback stopper(int stopAfter) {
  if (stopAfter == 0) return {};
  return [calls = 0, stopAfter](double fraction) mutable {
    FUZZ_CHECK(fraction >= 0.0 && fraction <= 1.0, "progress fraction %.17g", fraction);
    return ++calls < stopAfter;
  };
}

// FACET_FUZZ_PRINT=1: the scene and each frame as C++ statements for a repro (facet::Mesh
// holds double points and 64-bit ids; the comments say what the input used instead).
bool printing() {
  static const bool on = std::getenv("FACET_FUZZ_PRINT") != nullptr;
  return on;
}

void printVector(const char* name, const glm::dvec3& v) {
  std::fprintf(stderr, "%s = {%.17g, %.17g, %.17g};\n", name, v.x, v.y, v.z);
}

std::string attenuationCode(const Attenuation& attenuation) {
  char text[160] = "facet::NoAttenuation{}";
  if (const auto* q = std::get_if<QuadraticAttenuation>(&attenuation)) {
    std::snprintf(text, sizeof text, "facet::QuadraticAttenuation{%.17g, %.17g, %.17g}",
                  q->constant, q->linear, q->quadratic);
  } else if (const auto* f = std::get_if<FalloffDistanceAttenuation>(&attenuation)) {
    std::snprintf(text, sizeof text, "facet::FalloffDistanceAttenuation{%.17g}", f->distance);
  }
  return text;
}

std::string coneCode(const SpotCone& cone) {
  char text[160];
  if (const auto* l = std::get_if<LinearSpotCone>(&cone)) {
    std::snprintf(text, sizeof text, "facet::LinearSpotCone{%.17g, %.17g}",
                  l->fullIntensityAngleDegrees, l->falloffAngleDegrees);
  } else {
    const auto& e = std::get<ExponentSpotCone>(cone);
    std::snprintf(text, sizeof text, "facet::ExponentSpotCone{%.17g, %.17g}", e.coneAngleDegrees,
                  e.exponent);
  }
  return text;
}

std::int64_t entry(const PolygonArray& polygons, const void* array, std::size_t k) {
  return polygons.type == PolygonArray::Type::Int32 ? static_cast<const std::int32_t*>(array)[k]
                                                    : static_cast<const std::int64_t*>(array)[k];
}

void printMesh(const SceneMesh& sceneMesh, std::size_t m) {
  const MeshView& mesh = sceneMesh.mesh;
  const PolygonArray& polygons = mesh.polygons;
  const bool floats = mesh.points.type == PointArray::Type::Float32;
  std::fprintf(stderr, "facet::Mesh mesh%zu;  // %s points, %s ids%s\n", m,
               floats ? "float" : "double",
               polygons.type == PolygonArray::Type::Int32 ? "int32" : "int64",
               mesh.closedSurface ? ", closedSurface" : "");
  for (std::size_t i = 0; mesh.points.data && i < mesh.points.count; ++i) {
    const glm::dvec3 p = floats ? glm::dvec3(static_cast<const glm::vec3*>(mesh.points.data)[i])
                                : static_cast<const glm::dvec3*>(mesh.points.data)[i];
    std::fprintf(stderr, "mesh%zu.addPoint({%.17g, %.17g, %.17g});  // %zu\n", m, p.x, p.y, p.z, i);
  }
  if (!polygons.offsets) return;
  std::fprintf(stderr, "mesh%zu.offsets = {", m);
  for (std::size_t i = 0; i <= polygons.count; ++i)
    std::fprintf(stderr, "%s%lld", i ? ", " : "",
                 static_cast<long long>(entry(polygons, polygons.offsets, i)));
  std::fprintf(stderr, "};\nmesh%zu.connectivity = {", m);
  for (std::size_t k = 0; polygons.connectivity && k < polygons.connectivitySize; ++k)
    std::fprintf(stderr, "%s%lld", k ? ", " : "",
                 static_cast<long long>(entry(polygons, polygons.connectivity, k)));
  std::fprintf(stderr, "};\n");
  for (const Rgba8& c : mesh.polygonColors)
    std::fprintf(stderr, "mesh%zu.polygonColors.push_back({%d, %d, %d, %d});\n", m, c.r, c.g, c.b,
                 c.a);
  const Material& mat = sceneMesh.material;
  std::fprintf(stderr,
               "// material: color (%g %g %g) Ka %.17g Kd %.17g Ks %.17g n %.17g diffuse %d "
               "specular %d mix %d culling %d\n",
               mat.color.r, mat.color.g, mat.color.b, mat.ambient, mat.diffuse, mat.specular,
               mat.specularPower, static_cast<int>(mat.diffuseModel),
               static_cast<int>(mat.specularModel), static_cast<int>(mat.specularMix),
               mat.backfaceCulling);
}

void printLight(const Light& light) {
  std::visit(
      [](const auto& l) {
        using T = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<T, DirectionalLight>) {
          std::fprintf(stderr, "lights.push_back(facet::DirectionalLight{{%.17g, %.17g, %.17g}",
                       l.direction.x, l.direction.y, l.direction.z);
        } else {
          std::fprintf(stderr, "lights.push_back(facet::%s{{%.17g, %.17g, %.17g}",
                       std::is_same_v<T, PointLight> ? "PointLight" : "SpotLight", l.position.x,
                       l.position.y, l.position.z);
          if constexpr (std::is_same_v<T, SpotLight>) {
            std::fprintf(stderr, ", {%.17g, %.17g, %.17g}", l.direction.x, l.direction.y,
                         l.direction.z);
          }
        }
        std::fprintf(stderr, ", {%.9g, %.9g, %.9g}, %.17g", l.color.r, l.color.g, l.color.b,
                     l.intensity);
        if constexpr (!std::is_same_v<T, DirectionalLight>) {
          std::fprintf(stderr, ", %s", attenuationCode(l.attenuation).c_str());
        }
        if constexpr (std::is_same_v<T, SpotLight>) {
          std::fprintf(stderr, ", %s", coneCode(l.cone).c_str());
        }
        std::fprintf(stderr, "});\n");
      },
      light);
}

void print(const Scene& scene) {
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    printMesh(scene.meshes[m], m);
  for (const Light& light : scene.lights.lights)
    printLight(light);
}

void print(const Camera& camera, int width, int height) {
  std::fprintf(stderr, "// frame %d x %d\n", width, height);
  printVector("camera.position", camera.position);
  printVector("camera.focalPoint", camera.focalPoint);
  printVector("camera.viewUp", camera.viewUp);
  std::fprintf(stderr,
               "camera.viewAngleDegrees = %.17g;\ncamera.parallelProjection = %s;\n"
               "camera.parallelScale = %.17g;\ncamera.nearClip = %.17g;\n"
               "camera.farClip = %.17g;\ncamera.windowCenter = {%.17g, %.17g};\n",
               camera.viewAngleDegrees, camera.parallelProjection ? "true" : "false",
               camera.parallelScale, camera.nearClip, camera.farClip, camera.windowCenter.x,
               camera.windowCenter.y);
}

void fuzzOne(FuzzedDataProvider& in) {
  const Placement placement = anyPlacement(in);
  const int meshCount = in.ConsumeIntegralInRange(0, 3);
  std::vector<FuzzMesh> meshes(static_cast<std::size_t>(meshCount));
  Scene scene;
  std::size_t polygonCount = 0;
  for (FuzzMesh& mesh : meshes) {
    makePoints(in, placement, mesh);
    makePolygons(in, mesh);
    decideClosedSurface(in, mesh);
    scene.meshes.push_back({mesh.view, anyMaterial(in)});
    polygonCount += mesh.view.polygons.count;
  }
  scene.lights = anyLights(in, placement);
  if (printing()) print(scene);

  Renderer one, two;
  one.setThreadCount(1);
  two.setThreadCount(2);
  const Visibility visibility = in.ConsumeBool() ? Visibility::ZBuffer : Visibility::PainterSort;
  const bool twoSided = in.ConsumeBool();
  const Color background = anyColor(in);
  const float alpha = toFloat(anyDouble(in, 0.0, 1.0));
  const Rgba8 backgroundPixel = toRgba8(background, alpha);
  for (Renderer* r : {&one, &two}) {
    r->setVisibility(visibility);
    r->setTwoSidedLighting(twoSided);
    r->setBackground(background, alpha);
  }

  // A few frames through the same renderers (their buffers are reused between frames).
  const int frames = in.ConsumeIntegralInRange(1, 3);
  for (int frame = 0; frame < frames; ++frame) {
    const Camera camera = anyCamera(in, placement);
    const int width = anySide(in), height = anySide(in);
    if (printing()) print(camera, width, height);
    const int nullPlane =
        in.ConsumeIntegralInRange(0, 63) < 3 ? in.ConsumeIntegralInRange(1, 3) : 0;
    const int stopAfter =
        in.ConsumeIntegralInRange(0, 7) == 0 ? in.ConsumeIntegralInRange(1, 8) : 0;
    one.setProgressCallback(stopper(stopAfter));
    two.setProgressCallback(stopper(stopAfter));
    try {
      (void)one.plan(scene, camera, width, height).describe();
    } catch (const Error&) {
    }
    Target oneTarget(width, height, nullPlane), twoTarget(width, height, nullPlane);
    const Outcome oneOutcome = renderOnce(one, scene, camera, oneTarget);
    const Outcome twoOutcome = renderOnce(two, scene, camera, twoTarget);
    checkImage(oneTarget, oneOutcome, polygonCount, backgroundPixel);
    checkImage(twoTarget, twoOutcome, polygonCount, backgroundPixel);
    checkSameResult(oneTarget, oneOutcome, twoTarget, twoOutcome);
  }
}

}  // namespace
}  // namespace facet::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  facet::fuzz::fuzzOne(in);
  return 0;
}
