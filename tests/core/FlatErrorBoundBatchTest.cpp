// The error estimate's SIMD parts on every instruction set this CPU has: each lane of the
// bound's batch (FlatErrorBoundBatch.h) is the scalar FlatErrorBound::bound to the last bit,
// over random polygons and every light and material the batch takes, and lanes the scalar
// bound treats apart are NaN; the pass over the samples (EstimateRows.h) is its per-sample
// definition to the last bit; a flat render's estimate is the same bytes on every one.

#include <bit>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "../support/ReferenceScenes.h"
#include "../support/TestMeshes.h"
#include "../support/TestRender.h"
#include "EstimateRows.h"
#include "FlatErrorBoundBatch.h"
#include "SetupBatch.h"
#include "facet/FlatErrorBound.h"
#include "facet/QualityRenderer.h"

namespace facet::testing {
namespace {

using detail::kBoundBatchSize;

class BoundBatches : public EveryTargetTest {};

// A sample's estimate by its definition (EstimateRows.h), in 1/128 units: over the covered
// samples q of its 3 × 3 neighbourhood, the largest channel difference plus q's bound rounded
// up to 1/128 (`fixedBound`, by id), plus 0.5, capped at 255; 0 for the background.
template <class FixedBound>
std::uint32_t definedEstimate(const std::vector<Rgba8>& colors,
                              const std::vector<std::int32_t>& ids, const FixedBound& fixedBound,
                              int width, int height, int x, int y) {
  if (ids[y * width + x] < 0) return 0;
  const Rgba8 p = colors[y * width + x];
  std::uint32_t largest = 0;
  for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny) {
    for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
      const std::int32_t id = ids[ny * width + nx];
      if (id < 0) continue;
      const Rgba8 q = colors[ny * width + nx];
      const int d = std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
      largest = std::max(largest, static_cast<std::uint32_t>(d) * 128 + fixedBound(id));
    }
  }
  return std::min(largest + 64, 255u * 128);
}

struct Case {
  std::string name;
  LightSet lights;
  Camera camera;
  bool twoSided;
  Material material;
};

std::vector<Case> cases() {
  LightSet mixed;
  mixed.lights.push_back(DirectionalLight{{-1, -2, -3}, Color(0.9f, 0.7f, 0.5f)});
  mixed.lights.push_back(
      PointLight{{3, 2, 4}, Color(0.8f), 1.5, QuadraticAttenuation{1, 0.1, 0.02}});
  mixed.lights.push_back(  // a constant term only (vtkLight's default): one factor
      PointLight{{-1.5, 2.5, 3}, Color(0.6f), 1.2, QuadraticAttenuation{0.8, 0.0, 0.0}});
  mixed.lights.push_back(PointLight{{-2, 5, 1}, Color(0.3f, 0.9f, 0.6f), 0.7, NoAttenuation{}});
  mixed.lights.push_back(
      PointLight{{0.5, -3, 2}, Color(1.0f), 2.0, FalloffDistanceAttenuation{2.5}});
  LightSet onePoint;
  onePoint.lights.push_back(PointLight{{0, 0, 5}, Color(1.0f), 1.0, QuadraticAttenuation{}});
  Camera perspective;
  perspective.position = {0.3, 0.4, 6.0};
  Camera parallel = perspective;
  parallel.parallelProjection = true;
  Material lambert;
  lambert.diffuse = 0.8;
  lambert.color = Color(0.9f, 0.5f, 0.2f);
  Material lerp = lambert;
  lerp.diffuseModel = DiffuseModel::Lerp;
  return {{"mixed lights, perspective, two-sided", mixed, perspective, true, lambert},
          {"mixed lights, parallel, one-sided", mixed, parallel, false, lambert},
          {"one point light, Lerp", onePoint, perspective, true, lerp},
          {"no lights", LightSet{}, perspective, true, lambert}};
}

// Random polygons near the origin, some with the eye or a light at their center.
struct Polygons {
  std::vector<PolygonShape> shapes;
  std::vector<float> sines;
  std::vector<Color> colors;
};

Polygons randomPolygons(const Case& c, std::size_t count) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.0, 1.0);
  Polygons p;
  for (std::size_t i = 0; i < count; ++i) {
    PolygonShape shape;
    shape.center = {2 * unit(random), 2 * unit(random), 2 * unit(random)};
    if (i % 37 == 5) shape.center = c.camera.position;
    if (i % 41 == 7 && !c.lights.lights.empty()) {
      if (const auto* point = std::get_if<PointLight>(&c.lights.lights.back()))
        shape.center = point->position;
    }
    shape.normal = glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)));
    shape.normal = glm::dvec3(glm::vec3(shape.normal));  // as kept: float
    shape.radius = static_cast<float>(i % 5 == 0 ? 3.0 * positive(random) : 0.1 * positive(random));
    // Spreads from none to beyond 90° (a sine of 2), as kept: float.
    const float sine = i % 11 == 0 ? 2.0f : static_cast<float>(std::pow(positive(random), 3));
    shape.cosNormalSpread = sine >= 1.0f ? 0.0 : std::sqrt(1.0 - double(sine) * sine);
    p.shapes.push_back(shape);
    p.sines.push_back(sine);
    p.colors.push_back(Color(positive(random), positive(random), positive(random)));
  }
  return p;
}

TEST_F(BoundBatches, EveryLaneIsTheScalarBoundOnEveryInstructionSet) {
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  ASSERT_GE(targets.size(), 2u) << "at least one SIMD target and the portable one";
  for (const Case& c : cases()) {
    const PreparedMaterial material(c.material);
    const FlatErrorBound scalar(c.lights, c.camera, c.twoSided);
    const auto lighting = detail::batchLighting(c.lights, c.camera, c.twoSided);
    const auto terms = detail::batchMaterial(material);
    ASSERT_TRUE(lighting && terms) << c.name;
    const Polygons polygons = randomPolygons(c, 64 * kBoundBatchSize);
    for (const detail::SimdTarget& target : targets) {
      detail::useSimdTarget(target.bits);
      std::size_t compared = 0, apart = 0;
      for (std::size_t first = 0; first < polygons.shapes.size(); first += kBoundBatchSize) {
        detail::BoundBatch batch;
        for (std::size_t lane = 0; lane < kBoundBatchSize; ++lane) {
          const PolygonShape& shape = polygons.shapes[first + lane];
          for (int k = 0; k < 3; ++k) {
            batch.center[k][lane] = shape.center[k];
            batch.normal[k][lane] = shape.normal[k];
            batch.surface[k][lane] = polygons.colors[first + lane][k];
          }
          batch.radius[lane] = shape.radius;
          batch.sinNormalSpread[lane] = polygons.sines[first + lane];
        }
        detail::boundBatch(*lighting, *terms, batch, kBoundBatchSize);
        for (std::size_t lane = 0; lane < kBoundBatchSize; ++lane) {
          const PolygonShape& shape = polygons.shapes[first + lane];
          if (std::isnan(batch.bound[lane])) {  // the eye or a light at its center
            EXPECT_TRUE(shape.center == c.camera.position ||
                        (shape.center == glm::dvec3(-2, 5, 1) ||
                         shape.center == glm::dvec3(0.5, -3, 2) ||
                         shape.center == glm::dvec3(0, 0, 5)))
                << c.name << ", " << target.name << ", polygon " << first + lane;
            ++apart;
            continue;
          }
          const double expected = scalar.bound(shape, material, polygons.colors[first + lane]);
          ASSERT_EQ(batch.bound[lane], expected)
              << c.name << ", " << target.name << ", polygon " << first + lane;
          ++compared;
        }
      }
      EXPECT_GT(compared, 900u) << c.name << ", " << target.name;
      EXPECT_GT(apart, 0u) << c.name << ", " << target.name;  // the eye at a center
    }
  }
}

// The shade's float lanes (boundShadeColumns: the bound in float with a proven margin,
// FlatErrorBoundBatch.cpp) against the double bound on extreme inputs: polygons from 1e-6 to
// 1e3 across, far from the origin (1e7), lights on the surface and near it, grazing and
// back-facing normals, spreads from none to nearly 90°. Every lane the lanes take is at least
// roundedUp(double bound) and within its margin (2^-16 of the light's reach, plus the
// products' rounding) above it; every instruction set gives the same bytes; and
// boundOneColumn (the separate passes' bound) is the lanes' value.
TEST_F(BoundBatches, FloatLanesBoundTheDoubleBoundOnExtremeInputs) {
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  std::mt19937 random(19);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.0, 1.0);
  const auto logUniform = [&](double lo, double hi) {
    return std::exp(std::log(lo) + positive(random) * (std::log(hi) - std::log(lo)));
  };
  for (const Case& c : cases()) {
    for (const double offset : {0.0, 1e7}) {  // near the origin, and far from it
      const glm::dvec3 shift(offset, -0.5 * offset, 0.25 * offset);
      LightSet lights = c.lights;
      for (Light& light : lights.lights) {
        if (auto* point = std::get_if<PointLight>(&light)) point->position += shift;
      }
      Camera camera = c.camera;
      camera.position += shift;
      camera.focalPoint += shift;
      const PreparedMaterial material(c.material);
      const FlatErrorBound scalar(lights, camera, c.twoSided);
      const auto lighting = detail::batchLighting(lights, camera, c.twoSided);
      const auto terms = detail::batchMaterial(material);
      ASSERT_TRUE(lighting && terms) << c.name;
      std::vector<glm::dvec3> lightPoints;
      for (const Light& light : lights.lights) {
        if (const auto* point = std::get_if<PointLight>(&light))
          lightPoints.push_back(point->position);
      }
      std::vector<float> first;  // the first target's bounds
      for (std::size_t t = 0; t < targets.size(); ++t) {
        detail::useSimdTarget(targets[t].bits);
        std::mt19937 polygons(23);  // the same polygons on every target
        random = polygons;
        std::size_t compared = 0, index = 0;
        for (int round = 0; round < 64; ++round) {
          detail::ShadeBatch batch;
          detail::ShadeBatchCenters centers;
          alignas(64) float radius[detail::kShadeBatchSize], sine[detail::kShadeBatchSize];
          std::vector<PolygonShape> shapes;
          std::vector<Color> colors;
          for (std::size_t lane = 0; lane < detail::kShadeBatchSize; ++lane) {
            PolygonShape shape;
            const double size = logUniform(1e-6, 1e3);
            shape.center = shift + glm::dvec3(2 * unit(random), 2 * unit(random), 2 * unit(random));
            if (!lightPoints.empty() && lane % 4 == 1) {  // a light on or near the surface
              const glm::dvec3 light = lightPoints[lane % lightPoints.size()];
              shape.center = light + size * logUniform(1e-3, 4.0) *
                                         glm::dvec3(unit(random), unit(random), unit(random));
            }
            glm::dvec3 normal =
                glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)));
            if (lane % 4 == 2 && !lightPoints.empty()) {  // grazing: the light in its plane
              const glm::dvec3 toLight = glm::normalize(lightPoints[0] - shape.center);
              normal = glm::normalize(glm::cross(toLight, normal));
            }
            shape.normal = glm::dvec3(glm::vec3(normal));
            shape.radius = static_cast<float>(size);
            const float spread = lane % 8 == 3 ? 0.0f
                                 : lane % 8 == 5
                                     ? static_cast<float>(1.0 - logUniform(1e-7, 1e-2))
                                     : static_cast<float>(std::pow(positive(random), 3));
            shape.cosNormalSpread = spread >= 1.0f ? 0.0 : std::sqrt(1.0 - double(spread) * spread);
            const Color color(positive(random), positive(random), positive(random));
            for (int k = 0; k < 3; ++k) {
              centers.xyz[k][lane] = shape.center[k];
              batch.normal[k][lane] = shape.normal[k];
              batch.color[k][lane] = color[k];
            }
            radius[lane] = shape.radius;
            sine[lane] = spread;
            shapes.push_back(shape);
            colors.push_back(color);
          }
          batch.count = detail::kShadeBatchSize;
          alignas(64) float bounds[detail::kShadeBatchSize];
          alignas(64) detail::EstimateBound fixed[detail::kShadeBatchSize];
          detail::boundShadeColumns(*lighting, *terms, batch, centers, radius, sine, bounds, fixed);
          for (std::size_t lane = 0; lane < detail::kShadeBatchSize; ++lane, ++index) {
            if (t == 0) {
              first.push_back(bounds[lane]);
            } else {
              ASSERT_EQ(std::bit_cast<std::uint32_t>(bounds[lane]),
                        std::bit_cast<std::uint32_t>(first[index]))
                  << c.name << ", " << targets[t].name << ", polygon " << index;
            }
            if (std::isnan(bounds[lane])) continue;  // the double bound's
            const double exact = scalar.bound(shapes[lane], material, colors[lane]);
            ASSERT_GE(bounds[lane], detail::roundedUp(exact))
                << c.name << ", offset " << offset << ", polygon " << index;
            // Above by the margin at most: 2^-16 of Kd·Cd·Σ E_hi (≤ 8 here) in 8-bit units.
            EXPECT_LE(bounds[lane], exact * (1.0 + 0x1p-18) + 255.0 * 8.0 * 0x1p-15)
                << c.name << ", offset " << offset << ", polygon " << index;
            EXPECT_EQ(bounds[lane], detail::boundOneColumn(*lighting, *terms, shapes[lane].center,
                                                           shapes[lane].normal, colors[lane],
                                                           radius[lane], sine[lane]));
            ++compared;
          }
        }
        EXPECT_GT(compared, 2000u) << c.name << ", " << targets[t].name;
      }
    }
  }
}

TEST_F(BoundBatches, NotTakenForSpotLightsSpecularMaterialsOrManyLights) {
  LightSet spot;
  spot.lights.push_back(SpotLight{});
  EXPECT_FALSE(detail::batchLighting(spot, Camera{}, true));
  EXPECT_TRUE(detail::batchLighting(LightSet{}, Camera{}, true));
  // The float lanes' margin covers the sum of 32 lights' deviations; more are the scalar
  // bound's.
  LightSet many;
  many.lights.assign(32, DirectionalLight{});
  EXPECT_TRUE(detail::batchLighting(many, Camera{}, true));
  many.lights.push_back(DirectionalLight{});
  EXPECT_FALSE(detail::batchLighting(many, Camera{}, true));
  Material shiny;
  shiny.specular = 0.5;
  EXPECT_FALSE(detail::batchMaterial(PreparedMaterial(shiny)));
  EXPECT_TRUE(detail::batchMaterial(PreparedMaterial(Material{})));
}

// The estimate's pass over a grid of samples (EstimateRows.h: fields, row maxima, sample
// estimates) against its definition — per covered sample, over the covered samples q of its
// 3 × 3 neighbourhood, the largest channel difference plus q's bound rounded up to 1/128,
// plus 0.5, capped at 255 — and their sums to the last bit (summed apart and in the pass), on
// every instruction set.
TEST_F(BoundBatches, SampleEstimatesAreTheirDefinitionOnEveryInstructionSet) {
  std::mt19937 random(3);
  std::uniform_int_distribution<int> channel(0, 255), polygon(-3, 40);
  std::uniform_real_distribution<float> bound(0.0f, 300.0f);
  const int width = 203, height = 5;  // not a multiple of any vector's lanes
  std::vector<float> bounds(41);
  for (float& b : bounds)
    b = bound(random);
  bounds[7] = 0.0f;
  bounds[8] = INFINITY;        // no bound: 255
  bounds[9] = 1.0f / 1024.0f;  // rounds up to 1/128
  bounds[10] = NAN;            // no bound either: 255
  bounds[11] = -3.0f;          // below 0 (none is made so): 0
  bounds[12] = -0.0f;
  std::vector<Rgba8> colors(width * height);
  std::vector<std::int32_t> ids(width * height);
  for (int i = 0; i < width * height; ++i) {
    const auto byte = [&] { return static_cast<std::uint8_t>(channel(random)); };
    colors[i] = {byte(), byte(), byte(), byte()};
    ids[i] = std::max(-1, polygon(random));  // some background
  }
  // The definition, in 1/128 units.
  const auto fixedBound = [&](std::int32_t id) {
    const float b = bounds[id];
    const float capped = !(b < 255.0f) ? 255.0f : std::max(b, 0.0f);  // NaN as 255
    return static_cast<std::uint32_t>(std::ceil(capped * 128.0f));
  };
  // The bounds as the pass reads them: in fixed point, one more (a covered sample's fields are
  // never 0), an even count.
  std::vector<detail::EstimateBound> fixed(bounds.size() + 1, 0);
  for (std::size_t id = 0; id < bounds.size(); ++id) {
    fixed[id] = detail::fixedBoundOf(bounds[id]);
    ASSERT_EQ(fixed[id], fixedBound(static_cast<std::int32_t>(id)) + 1) << "polygon " << id;
  }
  const auto expected = [&](int x, int y) {
    return definedEstimate(colors, ids, fixedBound, width, height, x, y);
  };
  const std::size_t stride = width + 2;
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    detail::useSimdTarget(target.bits);
    std::vector<std::vector<detail::EstimateField>> maxima(height);
    for (int y = 0; y < height; ++y) {
      std::vector<detail::EstimateField> fields(detail::kEstimateFields * stride, 0);
      maxima[y].assign(detail::kEstimateFields * stride, 0);
      detail::neighbourFields(colors.data() + y * width, ids.data() + y * width, fixed.data(), 0,
                              width, fields.data() + 1, stride);
      // The same fields with each sample's color its polygon's, gathered by id (the resolve's
      // rows outside its band, EstimateHook.h).
      std::vector<Rgba8> polygonColors(bounds.size()), rowColors(width);
      for (std::size_t p = 0; p < polygonColors.size(); ++p)
        polygonColors[p] = colors[(y * width + 3 * p) % colors.size()];
      for (int x = 0; x < width; ++x) {
        const std::int32_t id = ids[y * width + x];
        rowColors[x] = id < 0 ? Rgba8{} : polygonColors[id];
      }
      std::vector<detail::EstimateField> byId(fields.size(), 0), byRow(fields.size(), 0);
      detail::neighbourFieldsById(polygonColors.data(), ids.data() + y * width, fixed.data(), 0,
                                  width, byId.data() + 1, stride);
      detail::neighbourFields(rowColors.data(), ids.data() + y * width, fixed.data(), 0, width,
                              byRow.data() + 1, stride);
      ASSERT_EQ(byId, byRow) << target.name << ", row " << y;
      detail::rowMaxima(fields.data() + 1, 0, width, maxima[y].data() + 1, stride);
    }
    const std::vector<detail::EstimateField> zeros(detail::kEstimateFields * stride, 0);
    const auto row = [&](int y) { return (y < 0 || y >= height ? zeros : maxima[y]).data() + 1; };
    for (int y = 0; y < height; ++y) {
      for (const auto& [begin, end] : {std::pair{0, width}, std::pair{5, 190}, std::pair{9, 9}}) {
        std::vector<std::uint32_t> out(width, 7);
        detail::sampleEstimates(row(y - 1), row(y), row(y + 1), stride, colors.data() + y * width,
                                ids.data() + y * width, begin, end, out.data());
        detail::EstimateSums sums;  // and their statistics
        for (int x = 0; x < width; ++x) {
          ASSERT_EQ(out[x], x >= begin && x < end ? expected(x, y) : 7u)
              << target.name << ", sample " << x << ", " << y;
          if (x < begin || x >= end) continue;
          sums.squares += std::uint64_t{out[x]} * out[x];
          sums.largest = std::max(sums.largest, out[x]);
          sums.covered += out[x] != 0;
        }
        const detail::EstimateSums found = detail::estimateSums(out.data(), begin, end);
        EXPECT_EQ(found.squares, sums.squares) << target.name;
        EXPECT_EQ(found.largest, sums.largest) << target.name;
        EXPECT_EQ(found.covered, sums.covered) << target.name;
        // The same sums found in the pass, without the estimates stored (the resolve's).
        const detail::EstimateSums fused = detail::sampleEstimateSums(
            row(y - 1), row(y), row(y + 1), stride, colors.data() + y * width,
            ids.data() + y * width, begin, end);
        EXPECT_EQ(fused.squares, sums.squares) << target.name;
        EXPECT_EQ(fused.largest, sums.largest) << target.name;
        EXPECT_EQ(fused.covered, sums.covered) << target.name;
      }
    }
  }
}

// The pass over a grid (EstimateSpace) whose rows are grey (r = g = b: it keeps two planes of
// fields for them) and not, in runs of each and alone, against the definition, on every
// instruction set: a grey row beside one that is not takes all six planes.
TEST_F(BoundBatches, GreyAndColoredRowsGiveTheirDefinitionOnEveryInstructionSet) {
  std::mt19937 random(5);
  std::uniform_int_distribution<int> channel(0, 255), polygon(-3, 40);
  const int width = 77, height = 12;
  const bool greyRows[height] = {true,  true,  true, false, true,  true,
                                 false, false, true, true,  false, true};
  std::vector<detail::EstimateBound> fixed(42);
  for (auto& q : fixed)
    q = detail::fixedBoundOf(std::uniform_real_distribution<float>(0.0f, 300.0f)(random));
  std::vector<Rgba8> colors(width * height);
  std::vector<std::int32_t> ids(width * height);
  for (int i = 0; i < width * height; ++i) {
    const auto byte = [&] { return static_cast<std::uint8_t>(channel(random)); };
    const std::uint8_t grey = byte();
    colors[i] = greyRows[i / width] ? Rgba8{grey, grey, grey, byte()}
                                    : Rgba8{byte(), byte(), byte(), byte()};
    ids[i] = std::max(-1, polygon(random));
  }
  const auto fixedBound = [&](std::int32_t id) { return fixed[id] - 1u; };
  const detail::EstimateGrid grid{ids.data(), colors.data(), fixed.data(), nullptr, width, height};
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    detail::useSimdTarget(target.bits);
    detail::EstimateSpace space;
    space.resize(width, 1);
    for (int frame = 0; frame < 2; ++frame) {  // the space kept: its planes as the last left them
      for (int r = 0; r <= height; ++r) {
        if (r < height) space.findMaxima(grid, r);
        if (r == 0) continue;
        const int y = r - 1;
        space.estimateSamples(grid, y, true);
        const std::uint32_t* estimates = space.pixelEstimates();
        for (int x = 0; x < width; ++x) {
          ASSERT_EQ(estimates[x], definedEstimate(colors, ids, fixedBound, width, height, x, y))
              << target.name << ", sample " << x << ", " << y << ", frame " << frame;
        }
      }
    }
  }
}

// A flat render's estimate (bounds in batches from the kept extents) on every instruction set.
TEST_F(BoundBatches, TheEstimateIsTheSameBytesOnEveryInstructionSet) {
  const Mesh sphere = makeUvSphere(48, 25);
  Material matte;
  matte.diffuse = 0.9;
  Scene scene = oneMeshScene(sphere.view(), matte, twoLights());
  const Camera camera = fitCamera(sphere, {0.2, -0.3, -1});
  std::vector<float> first;
  for (const detail::SimdTarget& target : detail::simdTargets()) {
    detail::useSimdTarget(target.bits);
    Renderer renderer;
    QualityRenderer quality(renderer);
    Framebuffer image(96, 72);
    const QualityStats stats = quality.render(scene, {}, camera, image, {.estimateError = true});
    EXPECT_GT(stats.predictedMaxError, 1.0) << target.name;
    const std::vector<float> estimate(quality.errorEstimate().begin(),
                                      quality.errorEstimate().end());
    if (first.empty()) first = estimate;
    EXPECT_EQ(estimate, first) << target.name;
  }
}

// A batch of any count (1..64, mostly not a multiple of a vector's lanes) gives each live
// lane the full batch's bits on every target, whatever garbage lies past the count (NaN,
// negative radii, centers at the eye), and writes nothing past its arrays.
TEST_F(BoundBatches, PartialBatchesAreTheFullBatchsLanesOnEveryTarget) {
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  for (const Case& c : cases()) {
    const auto lighting = detail::batchLighting(c.lights, c.camera, c.twoSided);
    const PreparedMaterial material(c.material);
    const auto terms = detail::batchMaterial(material);
    ASSERT_TRUE(lighting && terms);
    const Polygons p = randomPolygons(c, detail::kShadeBatchSize);
    std::vector<float> firstBounds;
    std::vector<std::uint16_t> firstFixed;
    for (const auto& target : targets) {
      detail::useSimdTarget(target.bits);
      std::vector<float> full;
      std::vector<std::uint16_t> fullFixed;
      for (std::size_t count = detail::kShadeBatchSize; count >= 1; --count) {
        detail::ShadeBatch batch;
        detail::ShadeBatchCenters centers;
        alignas(64) float radius[detail::kShadeBatchSize], sine[detail::kShadeBatchSize];
        for (std::size_t lane = 0; lane < detail::kShadeBatchSize; ++lane) {
          const bool live = lane < count;
          for (int k = 0; k < 3; ++k) {
            centers.xyz[k][lane] = live ? p.shapes[lane].center[k] : c.camera.position[k];
            batch.normal[k][lane] = live ? p.shapes[lane].normal[k] : (lane % 2 ? NAN : 1e308);
            batch.color[k][lane] = live ? p.colors[lane][k] : NAN;
          }
          radius[lane] = live ? p.shapes[lane].radius : (lane % 2 ? NAN : -1.0f);
          sine[lane] = live ? p.sines[lane] : NAN;
        }
        batch.count = count;
        struct Out {
          alignas(64) float bounds[detail::kShadeBatchSize];
          float guard[32];
          alignas(64) detail::EstimateBound fixed[detail::kShadeBatchSize];
          detail::EstimateBound guardFixed[32];
        } out;
        std::fill(std::begin(out.guard), std::end(out.guard), 12345.0f);
        std::fill(std::begin(out.guardFixed), std::end(out.guardFixed), 777);
        detail::boundShadeColumns(*lighting, *terms, batch, centers, radius, sine, out.bounds,
                                  out.fixed);
        for (float g : out.guard)
          ASSERT_EQ(g, 12345.0f);
        for (auto g : out.guardFixed)
          ASSERT_EQ(g, 777);
        if (count == detail::kShadeBatchSize) {
          full.assign(out.bounds, out.bounds + count);
          fullFixed.assign(out.fixed, out.fixed + count);
        }
        for (std::size_t lane = 0; lane < count; ++lane) {
          ASSERT_EQ(std::bit_cast<std::uint32_t>(out.bounds[lane]),
                    std::bit_cast<std::uint32_t>(full[lane]))
              << c.name << " " << target.name << " count " << count << " lane " << lane;
          ASSERT_EQ(out.fixed[lane], fullFixed[lane]);
          // A lone polygon (boundOneColumn) is the batch's lane.
          const float one = detail::boundOneColumn(*lighting, *terms, p.shapes[lane].center,
                                                   p.shapes[lane].normal, p.colors[lane],
                                                   radius[lane], sine[lane]);
          ASSERT_EQ(std::bit_cast<std::uint32_t>(one), std::bit_cast<std::uint32_t>(full[lane]));
        }
      }
      if (firstBounds.empty()) {
        firstBounds = full;
        firstFixed = fullFixed;
      } else {
        for (std::size_t lane = 0; lane < full.size(); ++lane) {
          ASSERT_EQ(std::bit_cast<std::uint32_t>(full[lane]),
                    std::bit_cast<std::uint32_t>(firstBounds[lane]))
              << c.name << " " << target.name << " lane " << lane;
          ASSERT_EQ(fullFixed[lane], firstFixed[lane]);
        }
      }
    }
  }
}

}  // namespace
}  // namespace facet::testing
