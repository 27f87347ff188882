// The lighting in SIMD lanes (ShadeBatch.h) against Shader::shade sample by sample, byte for
// byte, on every instruction set this CPU has: directional and point lights (one, several, none,
// colored, bright), Lambert and Lerp diffuse, a material ambient color or none, both specular
// mixes; samples with random normals and positions, colors below 0, above 1, NaN and beyond
// kMaxRadiance, a light at the sample and one beyond double's range from it (shade()'s rare
// branches), and batches that do not fill their last group of lanes.

#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/EveryTargetTest.h"
#include "SetupBatch.h"
#include "ShadeBatch.h"
#include "ShaderAccess.h"

namespace facet::testing {
namespace {

using detail::kShadeBatchSize;
using detail::ShadeBatch;

struct BatchLightCase {
  std::string name;
  LightSet lights;
};

std::vector<BatchLightCase> batchLightCases() {
  const PointLight headlight{{0.5, -1.0, 8.0}, Color(1.0f), 1.0, NoAttenuation{}};
  std::vector<BatchLightCase> cases;
  cases.push_back({"one point light", {AmbientLight{Color(0.0f), 0.0}, {headlight}}});
  cases.push_back(
      {"point lights, colored, bright, scene ambient",
       {AmbientLight{Color(0.2f, 0.1f, 0.3f), 1.0},
        {headlight, PointLight{{-3.0, 2.0, 1.0}, Color(0.9f, 0.2f, 0.4f), 2.5, NoAttenuation{}},
         PointLight{{0.0, 0.0, -5.0}, Color(1.0f), 1e5, NoAttenuation{}}}}});
  cases.push_back({"directional lights",
                   {AmbientLight{Color(0.05f), 1.0},
                    {DirectionalLight{{0.3, -0.2, -1.0}, Color(1.0f), 1.0},
                     DirectionalLight{{-1.0, 0.5, 0.2}, Color(0.3f, 0.6f, 0.9f), 0.7}}}});
  cases.push_back({"no direct light", {AmbientLight{Color(0.5f), 1.0}, {}}});
  return cases;
}

std::vector<Material> batchMaterials() {
  std::vector<Material> out(4);
  out[1].ambient = 0.3;
  out[1].diffuse = 0.6;
  out[1].specularMix = SpecularMix::Blend;
  out[2].diffuseModel = DiffuseModel::Lerp;
  out[2].lerpAmbient = 0.25;
  out[2].lerpFull = 0.9;
  out[3].ambient = 0.4;
  out[3].ambientColor = Color(0.1f, 0.7f, 0.2f);
  out[3].diffuse = 2.0;
  return out;
}

// Samples around the lights: random unit normals (either side), positions in a box about the
// origin, colors mostly in [0, 1] with the stiff ones among them; two samples at the lights'
// rare branches when there is a point light at `light`.
std::vector<SurfaceSample> batchSamples(std::size_t count, const glm::dvec3& light, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<float> channel(0.0f, 1.0f);
  const float stiff[] = {-0.5f, 1.5f, std::numeric_limits<float>::quiet_NaN(), 3e6f, 0.0f, -0.0f};
  std::vector<SurfaceSample> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    SurfaceSample& s = out[i];
    s.position = {4.0 * unit(random), 4.0 * unit(random), 4.0 * unit(random)};
    s.normal = glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)) + 1e-3);
    s.color = {channel(random), channel(random), channel(random)};
    if (random() % 8 == 0) s.color[random() % 3] = stiff[random() % std::size(stiff)];
  }
  if (count > 7) out[7].position = light;                                  // at the light
  if (count > 20) out[20].position = light + glm::dvec3(1e150, 0.0, 0.0);  // squared: > 1e290
  return out;
}

class ShadeBatches : public EveryTargetTest {};

TEST_F(ShadeBatches, LanesGiveShadesBytesOnEveryTarget) {
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  ASSERT_GE(targets.size(), 1u);
  for (const detail::SimdTarget& target : targets) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    unsigned seed = 1;
    for (const BatchLightCase& lights : batchLightCases()) {
      SCOPED_TRACE(lights.name);
      const Shader shader(lights.lights);
      ASSERT_TRUE(detail::shadesInBatches(shader));
      const detail::ShaderAccess::Routine shade = detail::ShaderAccess::routine(shader, false);
      for (const Material& material : batchMaterials()) {
        const PreparedMaterial prepared(material);
        for (std::size_t count :
             {kShadeBatchSize, std::size_t{61}, std::size_t{1}, std::size_t{0}}) {
          const std::vector<SurfaceSample> in = batchSamples(count, {0.5, -1.0, 8.0}, seed++);
          ShadeBatch batch;
          for (const SurfaceSample& s : in) {  // as a triangle's corner sum
            SurfaceSample sum = s;
            sum.position *= 3.0;
            batch.add(sum, 3.0);
          }
          detail::ShadeBatchColors colors;
          detail::shadeBatch(shader, prepared, batch, colors);
          int differing = 0;
          for (std::size_t i = 0; i < count; ++i) {
            SurfaceSample sample = in[i];
            sample.position = (3.0 * sample.position) / 3.0;
            const Rgba8 expected = toRgba8(shade(shader, sample, prepared));
            const Rgba8 got = colors[i];
            if ((got.r != expected.r || got.g != expected.g || got.b != expected.b ||
                 got.a != expected.a) &&
                ++differing <= 5) {
              ADD_FAILURE() << "sample " << i << " of " << count << ": lanes (" << int(got.r)
                            << ", " << int(got.g) << ", " << int(got.b) << ", " << int(got.a)
                            << "), shade (" << int(expected.r) << ", " << int(expected.g) << ", "
                            << int(expected.b) << ", " << int(expected.a) << ")";
            }
          }
          EXPECT_EQ(differing, 0) << count << " samples";
        }
      }
    }
  }
}

// Shown triangles in columns (ShownTriangleBatch) against gatherSample's sample lit by
// Shader::shade, byte for byte on every target: random corners and face normals, some normals
// flipped (two-sided back faces), some zero (reported, not lit), one triangle's center at the
// headlight (shade()'s rare branch); with centers and without (the origin).
TEST_F(ShadeBatches, ShownTrianglesGiveShadesBytesOnEveryTarget) {
  const std::vector<detail::SimdTarget> targets = detail::simdTargets();
  ASSERT_GE(targets.size(), 1u);
  const glm::dvec3 headlight{0.5, -1.0, 8.0};
  for (const detail::SimdTarget& target : targets) {
    SCOPED_TRACE(target.name);
    detail::useSimdTarget(target.bits);
    unsigned seed = 1;
    int zeroNormalsSeen = 0, flippedSeen = 0;
    for (const BatchLightCase& lights : batchLightCases()) {
      SCOPED_TRACE(lights.name);
      const Shader shader(lights.lights);
      const detail::ShaderAccess::Routine shade = detail::ShaderAccess::routine(shader, false);
      for (const Material& material : batchMaterials()) {
        const PreparedMaterial prepared(material);
        for (const bool centers : {true, false}) {
          for (std::size_t count :
               {kShadeBatchSize, std::size_t{61}, std::size_t{1}, std::size_t{0}}) {
            std::mt19937 random(seed++);
            std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
            const Color surface(0.2f + 0.8f * std::abs(unit(random)), std::abs(unit(random)),
                                random() % 4 == 0 ? 1.5f : std::abs(unit(random)));
            detail::ShownTriangleBatch batch;
            std::vector<SurfaceSample> expected(count);
            std::vector<bool> zeroNormal(count);
            for (std::size_t i = 0; i < count; ++i) {
              batch.polygon[i] = static_cast<std::int32_t>(1000 + i);
              glm::dvec3 sum(0.0);
              for (int k = 0; k < 3; ++k) {
                glm::dvec3 corner(4.0f * unit(random), 4.0f * unit(random), 4.0f * unit(random));
                if (i == 7) corner = headlight;  // the center at the light
                for (int c = 0; c < 3; ++c)
                  batch.corner[k][c][i] = corner[c];
                sum += corner;
              }
              glm::vec3 normal(unit(random), unit(random), unit(random));
              zeroNormal[i] = random() % 16 == 0;
              if (zeroNormal[i]) normal = glm::vec3(i % 2 == 0 ? 0.0f : -0.0f);
              const bool flipped = random() % 3 == 0;
              flippedSeen += flipped;
              batch.flip[i] = flipped ? std::uint64_t{1} << 63 : 0;
              for (int c = 0; c < 3; ++c)
                batch.normal[c][i] = normal[c];
              SurfaceSample& sample = expected[i];
              sample.position = centers ? sum / 3.0 : glm::dvec3(0.0);
              sample.normal = flipped ? -glm::dvec3(normal) : glm::dvec3(normal);
              sample.color = surface;
            }
            batch.count = count;
            detail::ShadeBatchColors colors;
            const std::uint64_t zeros =
                detail::shadeTriangleBatch(shader, prepared, batch, surface, centers, colors);
            int differing = 0;
            for (std::size_t i = 0; i < count; ++i) {
              EXPECT_EQ((zeros >> i) & 1, zeroNormal[i] ? 1u : 0u) << "lane " << i;
              if (zeroNormal[i]) {
                ++zeroNormalsSeen;
                continue;
              }
              const Rgba8 want = toRgba8(shade(shader, expected[i], prepared));
              const Rgba8 got = colors[i];
              if ((got.r != want.r || got.g != want.g || got.b != want.b || got.a != want.a) &&
                  ++differing <= 5) {
                ADD_FAILURE() << "triangle " << i << " of " << count << ", centers " << centers
                              << ": lanes (" << int(got.r) << ", " << int(got.g) << ", "
                              << int(got.b) << "), shade (" << int(want.r) << ", " << int(want.g)
                              << ", " << int(want.b) << ")";
              }
            }
            EXPECT_EQ(differing, 0) << count << " triangles";
            if (count < 64) {
              EXPECT_EQ(zeros >> count, 0u) << "no lane past the batch's count";
            }
          }
        }
      }
    }
    EXPECT_GT(zeroNormalsSeen, 0);
    EXPECT_GT(flippedSeen, 0);
  }
}

TEST_F(ShadeBatches, TakeOnlyTheLightsTheyComputeAsShadeDoes) {
  const auto takes = [](Light light) {
    return detail::shadesInBatches(Shader(LightSet{AmbientLight{}, {light}}));
  };
  EXPECT_TRUE(takes(DirectionalLight{}));
  EXPECT_TRUE(takes(PointLight{{0, 0, 1}, Color(1.0f), 1.0, NoAttenuation{}}));
  // VTK's (1, 0, 0) attenuation is no attenuation (Lighting.cpp).
  EXPECT_TRUE(takes(PointLight{{0, 0, 1}, Color(1.0f), 1.0, QuadraticAttenuation{1.0, 0.0, 0.0}}));
  EXPECT_FALSE(takes(PointLight{}));  // Sixth 3D's attenuation
  EXPECT_FALSE(takes(SpotLight{}));
}

}  // namespace
}  // namespace facet::testing
