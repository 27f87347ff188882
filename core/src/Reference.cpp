#include "facet/Reference.h"

#include <chrono>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "ThreadPool.h"
#include "Validate.h"
#include "facet/Conventions.h"
#include "facet/ImageMetrics.h"

namespace facet {
namespace {

// Chris Wellons' "lowbias32" integer hash (hash-prospector): full avalanche, cheap.
std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

std::uint32_t reverseBits(std::uint32_t x) {
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

// Sobol's second dimension, XOR-scrambled (Kollig & Keller 2002, Fig. 2's Sobol2).
std::uint32_t sobolSecond(std::uint32_t index, std::uint32_t scramble) {
  for (std::uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1) {
    if (index & 1u) scramble ^= v;
  }
  return scramble;
}

double toUnitInterval(std::uint32_t bits) {
  return bits * 0x1p-32;
}

int resolveThreads(int threads) {
  if (threads > 0) return threads;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : static_cast<int>(hardware);
}

}  // namespace

CameraRays::CameraRays(const Camera& camera, int width, int height)
    : eye_(camera.position),
      parallel_(camera.parallelProjection),
      nearClip_(camera.nearClip),
      farClip_(camera.farClip) {
  validate(camera);
  detail::requireInRange(width, 1, kMaxImageSide, "CameraRays width");
  detail::requireInRange(height, 1, kMaxImageSide, "CameraRays height");
  const glm::dmat4 viewFromClip =
      glm::inverse(clipFromView(camera, static_cast<double>(width) / height));
  // A window point on the near plane (OpenGL NDC depth −1), in view space.
  const auto onNear = [&](double x, double y) {
    const glm::dvec4 ndc(2.0 * x / width - 1.0, 2.0 * y / height - 1.0, -1.0, 1.0);
    const glm::dvec4 view = viewFromClip * ndc;
    return glm::dvec3(view) / view.w;
  };
  nearOrigin_ = onNear(0.0, 0.0);
  nearPerX_ = onNear(1.0, 0.0) - nearOrigin_;
  nearPerY_ = onNear(0.0, 1.0) - nearOrigin_;
  const glm::dmat4 view = viewFromWorld(camera);
  right_ = {view[0][0], view[1][0], view[2][0]};
  up_ = {view[0][1], view[1][1], view[2][1]};
  back_ = {view[0][2], view[1][2], view[2][2]};
}

Ray CameraRays::through(const glm::dvec2& window) const {
  const glm::dvec3 onNear = nearOrigin_ + window.x * nearPerX_ + window.y * nearPerY_;
  const auto toWorld = [&](const glm::dvec3& v) { return right_ * v.x + up_ * v.y + back_ * v.z; };
  Ray ray;
  if (parallel_) {
    ray.origin = eye_ + toWorld({onNear.x, onNear.y, 0.0});
    ray.direction = -back_;
    ray.tNear = nearClip_;
    ray.tFar = farClip_;
    return ray;
  }
  const double length = glm::length(onNear);
  ray.origin = eye_;
  ray.direction = toWorld(onNear / length);
  // onNear lies at view depth nearClip, at distance `length` from the eye.
  ray.tNear = length;
  ray.tFar = length * (farClip_ / nearClip_);
  return ray;
}

PixelSamplePattern::PixelSamplePattern(int x, int y) {
  const std::uint32_t pixel =
      hash32(static_cast<std::uint32_t>(x) ^ hash32(static_cast<std::uint32_t>(y) + 0x9e3779b9u));
  scrambleX_ = hash32(pixel ^ 0x68bc21ebu);
  scrambleY_ = hash32(pixel ^ 0x02e5be93u);
}

glm::dvec2 PixelSamplePattern::offset(std::uint32_t index) const {
  return {toUnitInterval(reverseBits(index) ^ scrambleX_),
          toUnitInterval(sobolSecond(index, scrambleY_))};
}

glm::dvec2 referenceSampleOffset(int x, int y, std::uint32_t index) {
  return PixelSamplePattern(x, y).offset(index);
}

void validate(const ReferenceOptions& options) {
  detail::requireInRange(options.samplesPerPixel, 1, 1 << 20, "ReferenceOptions.samplesPerPixel");
  detail::requireInRange(options.threads, 0, 1024, "ReferenceOptions.threads");
  detail::requireColor(options.background, "ReferenceOptions.background");
}

namespace {

// A pixel's running sums.
struct PixelSum {
  glm::dvec3 color{0.0};
  std::uint32_t hits = 0;

  void store(FloatImage& image, std::size_t i, std::uint32_t samples) const {
    image.color[i] = Color(color / static_cast<double>(samples));
    image.coverage[i] = static_cast<float>(static_cast<double>(hits) / samples);
  }
};

// One pixel: its samples summed in index order, in double; the first half stored apart.
void tracePixel(const CameraRays& rays, const ReferenceOptions& options, const SampleTracer& trace,
                int x, int y, FloatImage& image, FloatImage& half) {
  // Saturated as the rasterizer's output is, so the image stays in [0, 1] (and NaN-free)
  // whatever a tracer returns.
  const glm::dvec3 background(saturate(options.background));
  const auto samples = static_cast<std::uint32_t>(options.samplesPerPixel);
  const std::size_t i = image.indexOf(x, y);
  const PixelSamplePattern pattern(x, y);
  PixelSum sum;
  for (std::uint32_t s = 0; s < samples; ++s) {
    if (s == samples / 2 && s > 0) sum.store(half, i, s);
    const glm::dvec2 offset = pattern.offset(s);
    const std::optional<Color> seen = trace(rays.through({x + offset.x, y + offset.y}));
    sum.color += seen ? glm::dvec3(saturate(*seen)) : background;
    sum.hits += seen.has_value();
  }
  sum.store(image, i, samples);
}

}  // namespace

ReferenceRender renderReference(const Camera& camera, int width, int height,
                                const ReferenceOptions& options, const SampleTracer& trace) {
  const auto start = std::chrono::steady_clock::now();
  validate(options);
  const CameraRays rays(camera, width, height);
  ReferenceRender result;
  result.image = FloatImage(width, height);
  FloatImage half(width, height);
  detail::ThreadPool pool(resolveThreads(options.threads));
  auto row = [&](std::size_t y) {
    for (int x = 0; x < width; ++x)
      tracePixel(rays, options, trace, x, static_cast<int>(y), result.image, half);
  };
  auto report = [&](std::size_t rowsDone) {
    return !options.progress || options.progress(static_cast<double>(rowsDone) / height);
  };
  result.aborted = !pool.run(static_cast<std::size_t>(height), row, report);
  if (!result.aborted && options.samplesPerPixel > 1) {
    result.convergence = compareImages(result.image, half).rmse;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace facet
