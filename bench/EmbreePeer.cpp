// A peer for `make bench-peers`: a plain Embree 3 ray caster drawing the bench sphere
// (PeerScene.h). One primary ray per pixel center, traced in packets (rtcIntersect16 where
// Embree has native 16-wide packets, AVX-512; rtcIntersect8 otherwise); flat shading from the
// hit's geometric normal; every frame writes RGBA8, window depth and the primitive id, as
// Facet's framebuffer holds them. The BVH is built once (rtcCommitScene, Embree's default
// build quality, `threads=T` for its task scheduler) and reported on its own; frames trace
// on T threads that take 32 × 8-pixel tiles from a shared counter.
//
//   build/bin/embree_peer --triangles 2000000 --frames 10 --threads 2

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "PeerScene.h"

namespace facet::bench {
namespace {

constexpr int kTileWidth = 32, kTileHeight = 8;

struct Image {
  std::vector<std::uint32_t> rgba;  // RGBA8, R in the lowest byte
  std::vector<float> depth;
  std::vector<std::int32_t> primitiveId;
  Image() : rgba(kPeerWidth * kPeerHeight), depth(rgba.size()), primitiveId(rgba.size()) {}
};

// Primary rays: origin at the eye, direction = forward + x·right + y·up with forward of unit
// length, so a hit's ray parameter t is its view-space distance along −Z (the depth buffer's
// z) and the near and far planes are t = near and t = far.
struct RayFrame {
  glm::vec3 eye, forward, right, up;  // right and up scaled to the image's half extent at t = 1
  float near, far;
  float depthScale, depthOffset;  // window depth = depthOffset − depthScale / t (OpenGL's)

  explicit RayFrame(const Camera& camera) {
    const glm::dmat4 worldFromView = glm::inverse(viewFromWorld(camera));
    const double halfHeight = std::tan(glm::radians(camera.viewAngleDegrees) / 2.0);
    const double halfWidth = halfHeight * kPeerWidth / kPeerHeight;
    eye = glm::vec3(camera.position);
    right = glm::vec3(halfWidth * glm::dvec3(worldFromView[0]));
    up = glm::vec3(halfHeight * glm::dvec3(worldFromView[1]));
    forward = glm::vec3(-glm::dvec3(worldFromView[2]));
    const double n = camera.nearClip, f = camera.farClip;
    near = float(n);
    far = float(f);
    // z_ndc = (f + n)/(f − n) − 2fn/((f − n)·t); window = (z_ndc + 1)/2.
    depthOffset = float(0.5 * (f + n) / (f - n) + 0.5);
    depthScale = float(f * n / (f - n));
  }
  glm::vec3 direction(int x, int y) const {
    const float u = 2.0f * (x + 0.5f) / kPeerWidth - 1.0f;
    const float v = 2.0f * (y + 0.5f) / kPeerHeight - 1.0f;
    return forward + u * right + v * up;
  }
};

std::uint32_t packGray(float level) {
  const auto byte = static_cast<std::uint32_t>(std::lround(255.0f * std::fmin(level, 1.0f)));
  return byte | byte << 8 | byte << 16 | 0xff000000u;
}

// Packets of N rays over a block of 4 × (N / 4) pixels; row 0 at the bottom, as Facet.
template <int N>
class PacketTracer {
 public:
  static constexpr int kBlockWidth = 4, kBlockHeight = N / 4;

  PacketTracer(RTCScene scene, const RayFrame& rays, const glm::vec3& light, Image& image)
      : scene_(scene), rays_(rays), light_(light), image_(image) {}

  void traceTile(int x0, int y0) {
    for (int y = y0; y < y0 + kTileHeight; y += kBlockHeight) {
      for (int x = x0; x < x0 + kTileWidth; x += kBlockWidth)
        traceBlock(x, y);
    }
  }

 private:
  void traceBlock(int x0, int y0) {
    alignas(64) int valid[N];
    alignas(64) RTCRayHitNt<N> packet;
    for (int i = 0; i < N; ++i) {
      const int x = x0 + i % kBlockWidth, y = y0 + i / kBlockWidth;
      valid[i] = x < kPeerWidth && y < kPeerHeight ? -1 : 0;
      const glm::vec3 d = rays_.direction(x, y);
      packet.ray.org_x[i] = rays_.eye.x;
      packet.ray.org_y[i] = rays_.eye.y;
      packet.ray.org_z[i] = rays_.eye.z;
      packet.ray.dir_x[i] = d.x;
      packet.ray.dir_y[i] = d.y;
      packet.ray.dir_z[i] = d.z;
      packet.ray.tnear[i] = rays_.near;
      packet.ray.tfar[i] = rays_.far;
      packet.ray.time[i] = 0.0f;
      packet.ray.mask[i] = ~0u;
      packet.ray.id[i] = static_cast<unsigned>(i);
      packet.ray.flags[i] = 0;
      packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // a block of neighboring pixels
    if constexpr (N == 16) {
      rtcIntersect16(valid, scene_, &context, reinterpret_cast<RTCRayHit16*>(&packet));
    } else {
      rtcIntersect8(valid, scene_, &context, reinterpret_cast<RTCRayHit8*>(&packet));
    }
    for (int i = 0; i < N; ++i) {
      if (valid[i])
        writePixel(packet, i, (y0 + i / kBlockWidth) * kPeerWidth + x0 + i % kBlockWidth);
    }
  }

  void writePixel(const RTCRayHitNt<N>& packet, int i, int pixel) {
    if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
      image_.rgba[pixel] = 0xff000000u;
      image_.depth[pixel] = 1.0f;
      image_.primitiveId[pixel] = -1;
      return;
    }
    const float t = packet.ray.tfar[i];
    const glm::vec3 point =
        rays_.eye + t * glm::vec3(packet.ray.dir_x[i], packet.ray.dir_y[i], packet.ray.dir_z[i]);
    const glm::vec3 normal(packet.hit.Ng_x[i], packet.hit.Ng_y[i], packet.hit.Ng_z[i]);
    // Two-sided Lambert (VTK's default two-sided lighting).
    image_.rgba[pixel] =
        packGray(std::abs(glm::dot(glm::normalize(normal), glm::normalize(light_ - point))));
    image_.depth[pixel] = rays_.depthOffset - rays_.depthScale / t;
    image_.primitiveId[pixel] = static_cast<std::int32_t>(packet.hit.primID[i]);
  }

  RTCScene scene_;
  const RayFrame& rays_;
  glm::vec3 light_;
  Image& image_;
};

template <int N>
void traceFrame(RTCScene scene, const RayFrame& rays, const glm::vec3& light, Image& image,
                int threads) {
  constexpr int tilesX = (kPeerWidth + kTileWidth - 1) / kTileWidth;
  constexpr int tiles = tilesX * ((kPeerHeight + kTileHeight - 1) / kTileHeight);
  std::atomic<int> next{0};
  const auto work = [&] {
    PacketTracer<N> tracer(scene, rays, light, image);
    for (int tile = next++; tile < tiles; tile = next++) {
      tracer.traceTile(tile % tilesX * kTileWidth, tile / tilesX * kTileHeight);
    }
  };
  std::vector<std::jthread> helpers;
  for (int i = 1; i < threads; ++i)
    helpers.emplace_back(work);
  work();
}

[[noreturn]] void embreeFailed(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "embree_peer: Embree error %d: %s\n", int(code), message);
  std::exit(1);
}

RTCScene buildScene(RTCDevice device, const PeerScene& scene) {
  RTCGeometry mesh = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // rtcSetNewGeometryBuffer pads the buffers as Embree's 16-byte vertex loads need.
  std::memcpy(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                      3 * sizeof(float), scene.pointCount()),
              scene.xyz.data(), scene.xyz.size() * sizeof(float));
  std::memcpy(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                      3 * sizeof(std::uint32_t), scene.triangleCount()),
              scene.indices.data(), scene.indices.size() * sizeof(std::uint32_t));
  rtcCommitGeometry(mesh);
  RTCScene out = rtcNewScene(device);
  rtcAttachGeometry(out, mesh);
  rtcReleaseGeometry(mesh);
  return out;
}

// Starts Embree's worker threads on a one-triangle scene, so that the timed build is the
// cost of a mesh change in a running application.
void warmUpScheduler(RTCDevice device) {
  PeerScene triangle;
  triangle.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  triangle.indices = {0, 1, 2};
  RTCScene scene = buildScene(device, triangle);
  rtcCommitScene(scene);
  rtcReleaseScene(scene);
}

int run(const PeerOptions& options) {
  const PeerScene scene = makePeerScene(options.triangles);
  const std::string config = "threads=" + std::to_string(options.threads);
  RTCDevice device = rtcNewDevice(config.c_str());
  if (!device) {
    std::fprintf(stderr, "embree_peer: rtcNewDevice(\"%s\") failed: error %d\n", config.c_str(),
                 int(rtcGetDeviceError(nullptr)));
    return 1;
  }
  rtcSetDeviceErrorFunction(device, embreeFailed, nullptr);
  warmUpScheduler(device);

  RTCScene bvh = buildScene(device, scene);
  const auto start = std::chrono::steady_clock::now();
  rtcCommitScene(bvh);
  const double buildSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const bool wide = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  const RayFrame rays(scene.camera);
  const glm::vec3 light(scene.light);
  Image image;
  const double seconds = medianFrameSeconds(options.frames, [&] {
    if (wide) {
      traceFrame<16>(bvh, rays, light, image, options.threads);
    } else {
      traceFrame<8>(bvh, rays, light, image, options.threads);
    }
  });
  if (!options.image.empty()) {
    writePpm(options.image, reinterpret_cast<const std::uint8_t*>(image.rgba.data()));
  }
  printPeerResult("embree", options, scene,
                  {{"seconds_per_frame", std::to_string(seconds)},
                   {"build_seconds", std::to_string(buildSeconds)},
                   {"packet", std::to_string(wide ? 16 : 8)},
                   {"pixels_covered", std::to_string(coveredPixels(image.depth))},
                   {"renderer", jsonString("Embree " RTC_VERSION_STRING)}});
  rtcReleaseScene(bvh);
  rtcReleaseDevice(device);
  return 0;
}

}  // namespace
}  // namespace facet::bench

int main(int argc, char** argv) {
  try {
    return facet::bench::run(facet::bench::parsePeerOptions(argc, argv));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "embree_peer: %s\n", error.what());
    return 1;
  }
}
