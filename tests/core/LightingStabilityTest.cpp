// Every finite input gives a finite color in [0, 1]: a sweep over the extreme cases the
// stability promise names (lights on the surface, zero/negative intensity, 0°/90°/180°
// spots, falloff 0, shininess 0 and 1e6, dot products past 1, distances whose squares
// overflow, huge intensities and colors).

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "facet/Lighting.h"

namespace facet {
namespace {

void expectFiniteInUnitRange(const Color& c, const std::string& what) {
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(std::isfinite(c[i])) << what << " channel " << i << " = " << c[i];
    ASSERT_GE(c[i], 0.0f) << what << " channel " << i;
    ASSERT_LE(c[i], 1.0f) << what << " channel " << i;
  }
}

std::vector<SpotCone> extremeCones() {
  std::vector<SpotCone> cones;
  for (double angle : {0.0, 1e-9, 45.0, 90.0, 179.0, 180.0}) {
    for (double falloff : {0.0, 1e-9, 15.0, 180.0})
      cones.push_back(LinearSpotCone{angle, falloff});
    for (double exponent : {0.0, 1.0, 1e6})
      cones.push_back(ExponentSpotCone{angle, exponent});
  }
  return cones;
}

std::vector<Attenuation> extremeAttenuations() {
  return {NoAttenuation{},
          QuadraticAttenuation{},
          QuadraticAttenuation{0.0, 0.0, 1.0},
          QuadraticAttenuation{0.0, 0.0, 0.0},
          QuadraticAttenuation{1e300, 1e300, 1e300},
          FalloffDistanceAttenuation{0.0},
          FalloffDistanceAttenuation{1e300}};
}

std::vector<Material> extremeMaterials() {
  std::vector<Material> materials;
  for (double power : {0.0, 1.0, 1e6}) {
    for (SpecularModel model : {SpecularModel::Phong, SpecularModel::BlinnPhong}) {
      for (SpecularMix mix : {SpecularMix::Add, SpecularMix::Blend}) {
        Material m;
        m.ambient = 1e300;
        m.specular = 1e300;
        m.specularPower = power;
        m.specularModel = model;
        m.specularMix = mix;
        m.diffuseModel = power == 1.0 ? DiffuseModel::Lerp : DiffuseModel::Lambert;
        m.lerpAmbient = 1e300;
        materials.push_back(m);
        m.ambient = m.specular = 0.0;
        m.diffuse = 0.0;
        materials.push_back(m);
      }
    }
  }
  return materials;
}

TEST(LightingStability, ExtremeLightsOnExtremeSurfacesStayFiniteAndInRange) {
  const glm::dvec3 center(0.0);
  const std::vector<glm::dvec3> lightPositions = {
      center,                  // light exactly at the polygon center (d = 0)
      {0.0, 0.0, 1e-300},      // denormal distance
      {0.0, 0.0, 1e20},        // d² overflows float
      {1e200, -1e200, 1e200},  // d² overflows double
      {-1e308, 1e308, 0.0},    // the offset itself overflows double
      {3.0, 4.0, -5.0}};       // behind the surface
  const std::vector<double> intensities = {0.0, -1.0, -1e300, 1.0, 1e300};
  const std::vector<Color> colors = {Color(0.0f), Color(1.0f), Color(3e38f)};

  int shaded = 0;
  for (const SpotCone& cone : extremeCones()) {
    for (const Attenuation& attenuation : extremeAttenuations()) {
      for (const glm::dvec3& position : lightPositions) {
        for (double intensity : intensities) {
          for (const Color& color : colors) {
            SpotLight spot{position, {0.0, 0.0, -1.0}, color, intensity, attenuation, cone};
            PointLight point{position, color, intensity, attenuation};
            DirectionalLight directional{{1e-300, 0.0, -1e-300}, color, intensity};
            LightSet lights;
            lights.ambient = AmbientLight{color, intensity};
            lights.lights = {spot, point, directional};
            const Shader shader(lights);
            for (const Material& material : extremeMaterials()) {
              SurfaceSample sample;
              sample.position = center;
              // A normal whose length rounds slightly past 1, so dot products may exceed 1.
              sample.normal = glm::dvec3(0.0, 0.0, 1.0 + 4e-16);
              sample.toViewer = glm::normalize(glm::dvec3(1.0, 1.0, 1.0));
              sample.color = color;
              expectFiniteInUnitRange(shader.shade(sample, material),
                                      "case " + std::to_string(shaded));
              ++shaded;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(shaded, 100000);
}

TEST(LightingStability, LightOnTheSurfaceLightsItHeadOn) {
  PointLight point;
  point.position = {1.0, 2.0, 3.0};
  point.attenuation = NoAttenuation{};
  LightSet lights;
  lights.ambient.intensity = 0.0;
  lights.lights = {point};
  SurfaceSample sample;
  sample.position = point.position;
  EXPECT_FLOAT_EQ(shade(sample, Material{}, lights).g, 1.0f);
}

TEST(LightingStability, ViewerExactlyOppositeTheLightHasNoBlinnHalfVector) {
  Material m;
  m.specular = 1.0;
  m.specularModel = SpecularModel::BlinnPhong;
  LightSet lights;
  lights.ambient.intensity = 0.0;
  DirectionalLight grazing;
  grazing.direction = {-1.0, 0.0, 0.0};  // toward the light: +X
  lights.lights = {grazing};
  SurfaceSample sample;
  sample.normal = {0.0, 0.0, 1.0};
  sample.toViewer = {-1.0, 0.0, 0.0};  // L + V = 0
  expectFiniteInUnitRange(shade(sample, m, lights), "L = -V");
}

TEST(LightingStability, RandomFiniteInputsNeverLeaveTheUnitRange) {
  std::mt19937_64 random(20261121);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto wild = [&] { return unit(random) * std::pow(10.0, exponent(random)); };
  auto wildVector = [&] { return glm::dvec3(wild(), wild(), wild()); };
  for (int i = 0; i < 20000; ++i) {
    LightSet lights;
    lights.ambient = AmbientLight{Color(float(std::abs(unit(random)))), wild()};
    lights.lights.push_back(
        PointLight{wildVector(), Color(1.0f), wild(),
                   QuadraticAttenuation{std::abs(wild()), std::abs(wild()), std::abs(wild())}});
    lights.lights.push_back(
        SpotLight{wildVector(), wildVector(), Color(0.5f), wild(),
                  FalloffDistanceAttenuation{std::abs(wild())},
                  ExponentSpotCone{90.0 * std::abs(unit(random)), std::abs(wild())}});
    Material m;
    m.specular = std::abs(wild());
    m.specularPower = std::abs(wild());
    SurfaceSample sample;
    sample.position = wildVector();
    sample.normal = glm::normalize(glm::dvec3(unit(random), unit(random), unit(random)) +
                                   glm::dvec3(0.0, 0.0, 1e-3));
    expectFiniteInUnitRange(shade(sample, m, lights), "random case " + std::to_string(i));
  }
}

}  // namespace
}  // namespace facet
