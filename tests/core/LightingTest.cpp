// The lighting formula of Lighting.h against closed forms and the seeds' numbers.

#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "facet/Error.h"
#include "facet/Lighting.h"

namespace facet {
namespace {

constexpr float kTolerance = 1e-6f;

glm::dvec3 unitAtDegreesFromZ(double degrees) {
  const double r = degrees * M_PI / 180.0;
  return {std::sin(r), 0.0, std::cos(r)};
}

// A lit sample at the origin facing +Z, seen from +Z.
SurfaceSample facingUp(Color color = Color(1.0f)) {
  SurfaceSample s;
  s.color = color;
  return s;
}

LightSet noAmbient() {
  LightSet set;
  set.ambient.intensity = 0.0;
  return set;
}

DirectionalLight directionalFrom(const glm::dvec3& toLight, Color color = Color(1.0f)) {
  DirectionalLight light;
  light.direction = -toLight;
  light.color = color;
  return light;
}

void expectColorNear(const Color& actual, const Color& expected, float tolerance = kTolerance) {
  EXPECT_NEAR(actual.r, expected.r, tolerance) << "red";
  EXPECT_NEAR(actual.g, expected.g, tolerance) << "green";
  EXPECT_NEAR(actual.b, expected.b, tolerance) << "blue";
}

TEST(Lambert, CosineTableOfTheShadingGuide) {
  struct Row {
    double degrees;
    double printed;  // the guide's two-decimal value
  };
  for (const Row row : {Row{0, 1.00}, Row{45, 0.71}, Row{90, 0.00}}) {
    LightSet lights = noAmbient();
    lights.lights.push_back(directionalFrom(unitAtDegreesFromZ(row.degrees)));
    const Color c = shade(facingUp(), Material{}, lights);
    EXPECT_NEAR(c.r, row.printed, 0.005) << row.degrees << "°";
    EXPECT_NEAR(c.r, std::cos(row.degrees * M_PI / 180.0), kTolerance) << row.degrees << "°";
  }
}

TEST(Lambert, NothingPastNinetyDegrees) {
  for (double degrees : {90.5, 120.0, 180.0}) {
    LightSet lights = noAmbient();
    lights.lights.push_back(directionalFrom(unitAtDegreesFromZ(degrees)));
    expectColorNear(shade(facingUp(), Material{}, lights), Color(0.0f));
  }
}

TEST(DotProduct, SeedExampleAngle) {
  EXPECT_NEAR(angleBetweenDegrees({1, 2, 3}, {4, 5, 6}), 12.93, 0.005);
  EXPECT_DOUBLE_EQ(angleBetweenDegrees({1, 1, 1}, {3, 3, 3}), 0.0) << "parallel: exactly 0";
  EXPECT_DOUBLE_EQ(angleBetweenDegrees({1, 0, 0}, {-2, 0, 0}), 180.0);
  EXPECT_THROW(angleBetweenDegrees({0, 0, 0}, {1, 0, 0}), Error);
}

TEST(ColorProduct, WhiteSurfaceUnderRedLightIsRed) {
  LightSet lights = noAmbient();
  lights.lights.push_back(directionalFrom({0, 0, 1}, Color(1, 0, 0)));
  expectColorNear(shade(facingUp(Color(1.0f)), Material{}, lights), Color(1, 0, 0));
}

TEST(ColorProduct, RedSurfaceUnderBlueLightIsBlack) {
  LightSet lights = noAmbient();
  lights.lights.push_back(directionalFrom({0, 0, 1}, Color(0, 0, 1)));
  expectColorNear(shade(facingUp(Color(1, 0, 0)), Material{}, lights), Color(0.0f));
}

TEST(Composition, ContributionsOfColoredLightsAdd) {
  const Color surface(0.8f, 0.6f, 0.4f);
  const DirectionalLight red = directionalFrom(unitAtDegreesFromZ(30), Color(0.3f, 0.0f, 0.1f));
  const DirectionalLight green = directionalFrom(unitAtDegreesFromZ(-50), Color(0.0f, 0.4f, 0.2f));
  LightSet one = noAmbient(), other = noAmbient(), both = noAmbient();
  one.lights = {red};
  other.lights = {green};
  both.lights = {red, green};
  const Color sum =
      shade(facingUp(surface), Material{}, one) + shade(facingUp(surface), Material{}, other);
  expectColorNear(shade(facingUp(surface), Material{}, both), sum);
}

TEST(Composition, SumSaturatesOnceAtWhite) {
  LightSet lights = noAmbient();
  for (int i = 0; i < 3; ++i)
    lights.lights.push_back(directionalFrom({0, 0, 1}, Color(0.6f)));
  const Color c = shade(facingUp(Color(1.0f, 0.5f, 0.2f)), Material{}, lights);
  // 3 × 0.6 = 1.8 per light channel: red saturates, green 0.9, blue 0.36.
  expectColorNear(c, Color(1.0f, 0.9f, 0.36f));
}

TEST(Composition, AmbientOnlyMultipliesSurfaceColor) {
  LightSet lights;  // Sixth 3D's default ambient, no direct lights
  const Color surface(1.0f, 0.5f, 0.0f);
  expectColorNear(shade(facingUp(surface), Material{}, lights), surface * (50.0f / 255.0f));
}

TEST(Composition, NoLightsAtAllIsBlack) {
  expectColorNear(shade(facingUp(), Material{}, noAmbient()), Color(0.0f));
}

TEST(Composition, ReducesToVtkWithoutSceneAmbient) {
  // VTK: Ka·AmbientColor + Kd·DiffuseColor·Σ df·light + Ks·SpecularColor·Σ sf·light.
  Material m;
  m.ambient = 0.2;
  m.diffuse = 0.7;
  m.specular = 0.3;
  m.specularPower = 8.0;
  m.ambientColor = Color(0.1f, 0.2f, 0.3f);
  m.specularColor = Color(1.0f, 0.9f, 0.8f);
  const Color surface(0.5f, 0.6f, 0.7f);
  const glm::dvec3 toLight = unitAtDegreesFromZ(40);
  const glm::dvec3 toViewer = unitAtDegreesFromZ(-20);
  LightSet lights = noAmbient();
  lights.lights.push_back(directionalFrom(toLight, Color(0.9f, 0.8f, 0.7f)));
  SurfaceSample s = facingUp(surface);
  s.toViewer = toViewer;

  const glm::dvec3 n(0, 0, 1);
  const double df = glm::dot(n, toLight);
  const glm::dvec3 reflected = 2.0 * df * n - toLight;
  const double sf = std::pow(glm::dot(reflected, toViewer), 8.0);
  const glm::dvec3 light(0.9, 0.8, 0.7);
  const glm::dvec3 expected = 0.2 * glm::dvec3(0.1, 0.2, 0.3) +
                              0.7 * glm::dvec3(surface) * df * light +
                              0.3 * glm::dvec3(1.0, 0.9, 0.8) * sf * light;
  expectColorNear(shade(s, m, lights), Color(expected), 1e-5f);
}

TEST(Composition, ReducesToSixthWithDefaultMaterial) {
  // Sixth 3D: color × (ambient + Σ light·cos).
  LightSet lights;
  lights.ambient.color = Color(0.1f, 0.15f, 0.2f);
  PointLight point;
  point.position = {30.0, 0.0, 40.0};  // distance 50, cos = 0.8
  point.color = Color(1.0f, 0.5f, 0.25f);
  lights.lights.push_back(point);
  const Color surface(0.9f, 0.8f, 0.7f);
  const double attenuation = 1.0 / (1.0 + 1e-4 * 2500.0);
  const glm::dvec3 expected =
      glm::dvec3(surface) *
      (glm::dvec3(0.1, 0.15, 0.2) + 0.8 * attenuation * glm::dvec3(1.0, 0.5, 0.25));
  expectColorNear(shade(facingUp(surface), Material{}, lights), Color(expected), 1e-6f);
}

TEST(Composition, AmbientCoefficientUsesSurfaceColorByDefault) {
  Material m;
  m.ambient = 0.5;
  m.diffuse = 0.0;
  expectColorNear(shade(facingUp(Color(0.4f, 0.2f, 1.0f)), m, noAmbient()),
                  Color(0.2f, 0.1f, 0.5f));
}

TEST(Specular, PhongPeaksOnTheMirrorDirection) {
  Material m;
  m.diffuse = 0.0;
  m.specular = 1.0;
  m.specularPower = 20.0;
  LightSet lights = noAmbient();
  lights.lights.push_back(directionalFrom(unitAtDegreesFromZ(45)));
  SurfaceSample s = facingUp();
  s.toViewer = unitAtDegreesFromZ(-45);
  expectColorNear(shade(s, m, lights), Color(1.0f));
  s.toViewer = {0, 0, 1};  // R·V = cos 45°
  expectColorNear(shade(s, m, lights), Color(float(std::pow(std::cos(M_PI / 4), 20.0))));
}

TEST(Specular, BlinnPhongUsesTheHalfVector) {
  Material m;
  m.diffuse = 0.0;
  m.specular = 1.0;
  m.specularPower = 10.0;
  m.specularModel = SpecularModel::BlinnPhong;
  LightSet lights = noAmbient();
  lights.lights.push_back(directionalFrom(unitAtDegreesFromZ(60)));
  SurfaceSample s = facingUp();  // viewer along N: the half vector is 30° from N
  expectColorNear(shade(s, m, lights), Color(float(std::pow(std::cos(M_PI / 6), 10.0))));
  m.specularModel = SpecularModel::Phong;  // R·V = cos 60°
  expectColorNear(shade(s, m, lights), Color(float(std::pow(0.5, 10.0))));
}

TEST(Specular, NoHighlightOnFacesTurnedAwayFromTheLight) {
  Material m;
  m.specular = 1.0;
  m.specularPower = 0.0;  // would be 1 everywhere the face is lit
  LightSet lights = noAmbient();
  lights.lights.push_back(directionalFrom(unitAtDegreesFromZ(100)));
  expectColorNear(shade(facingUp(), m, lights), Color(0.0f));
}

TEST(Specular, BlendMixIsTheNotesFormula) {
  // One white light: C = f·light + (1 − f)·diffuse with f the specular factor.
  Material m;
  m.specular = 1.0;
  m.specularPower = 4.0;
  m.specularMix = SpecularMix::Blend;
  LightSet lights = noAmbient();
  const glm::dvec3 toLight = unitAtDegreesFromZ(30);
  lights.lights.push_back(directionalFrom(toLight));
  SurfaceSample s = facingUp(Color(0.2f, 0.4f, 0.6f));
  const double cosine = std::cos(M_PI / 6);
  const double f = std::pow(cosine, 4.0);  // R·V = cos 30° with the viewer on the normal
  const glm::dvec3 diffuse = glm::dvec3(0.2, 0.4, 0.6) * cosine;
  expectColorNear(shade(s, m, lights), Color(f * glm::dvec3(1.0) + (1.0 - f) * diffuse), 1e-6f);
}

TEST(LerpDiffuse, InterpolatesBetweenUnlitAndFull) {
  Material m;
  m.diffuseModel = DiffuseModel::Lerp;
  m.lerpAmbient = 0.2;
  m.lerpFull = 0.9;
  EXPECT_DOUBLE_EQ(diffuseFactor(m, 0.5), 0.2 + 0.7 * 0.5);
  EXPECT_DOUBLE_EQ(diffuseFactor(m, -0.5), 0.2) << "cos clamped at 0";
  EXPECT_DOUBLE_EQ(diffuseFactor(m, 1.5), 0.9) << "cos clamped at 1";
  LightSet lights = noAmbient();
  lights.lights.push_back(directionalFrom(unitAtDegreesFromZ(60)));
  expectColorNear(shade(facingUp(Color(1, 0.5f, 0)), m, lights), Color(0.55f, 0.275f, 0.0f));
}

TEST(LerpDiffuse, DefaultsEqualLambert) {
  Material lerp;
  lerp.diffuseModel = DiffuseModel::Lerp;
  for (double c : {-1.0, 0.0, 0.3, 1.0})
    EXPECT_DOUBLE_EQ(diffuseFactor(lerp, c), diffuseFactor(Material{}, c));
}

TEST(PointLight, AttenuationAtTheSeedDistances) {
  for (const auto& [distance, expected] :
       {std::pair{0.001, 1.0}, {100.0, 0.5}, {300.0, 0.1}, {500.0, 1.0 / 26.0}}) {
    LightSet lights = noAmbient();
    PointLight point;
    point.position = {0.0, 0.0, distance};
    lights.lights.push_back(point);
    EXPECT_NEAR(shade(facingUp(), Material{}, lights).r, expected, 1e-6) << "d = " << distance;
  }
}

TEST(SpotLight, SeedConeThroughTheShading) {
  // A spot 100 units above the origin pointing down; the surface point moves sideways so
  // the angle from the axis is 10°, 27.5° and 36°. The light is also what tilts N·L, so
  // compare with cos × cone factor; no attenuation.
  for (const auto& [degrees, cone] : {std::pair{10.0, 1.0}, {27.5, 0.5}, {36.0, 0.0}}) {
    SpotLight spot;
    spot.position = {0.0, 0.0, 100.0};
    spot.direction = {0.0, 0.0, -1.0};
    spot.attenuation = NoAttenuation{};
    LightSet lights = noAmbient();
    lights.lights.push_back(spot);
    SurfaceSample s = facingUp();
    s.position = {100.0 * std::tan(degrees * M_PI / 180.0), 0.0, 0.0};
    const double cosine = std::cos(degrees * M_PI / 180.0);
    EXPECT_NEAR(shade(s, Material{}, lights).r, cosine * cone, 1e-6) << degrees << "°";
  }
}

TEST(Validation, ErrorsNameTheOffendingValue) {
  LightSet lights;
  PointLight bad;
  bad.intensity = std::nan("");
  lights.lights = {DirectionalLight{}, bad};
  try {
    Shader shader(lights);
    FAIL() << "expected facet::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lights[1].intensity"), std::string::npos) << e.what();
  }
  lights.lights = {DirectionalLight{{0, 0, 0}}};
  EXPECT_THROW(Shader{lights}, Error);
  SpotLight wide;
  wide.cone = ExponentSpotCone{200.0, 1.0};
  lights.lights = {wide};
  EXPECT_THROW(Shader{lights}, Error);
  Material m;
  m.specularPower = -1.0;
  EXPECT_THROW(validate(m), Error);
}

}  // namespace
}  // namespace facet
