#include "facet/Lighting.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "Overloaded.h"
#include "Validate.h"
#include "Vector.h"

namespace facet {
namespace {

// Caps a non-negative factor so that products of a handful of them stay finite in double
// (see "Edge cases" in Lighting.h). NaN and negative values map to 0.
double capped(double x) { return x > 0.0 ? std::min(x, kMaxRadiance) : 0.0; }
glm::dvec3 capped(const Color& c) { return {capped(c.r), capped(c.g), capped(c.b)}; }

glm::dvec3 radianceOf(const Color& color, double intensity) {
  const double i = std::max(intensity, 0.0);
  return {capped(color.r * i), capped(color.g * i), capped(color.b * i)};
}

double specularFactor(const Material& material, const glm::dvec3& normal,
                      const glm::dvec3& toLight, const glm::dvec3& toViewer, double cosine) {
  double alignment = 0.0;
  if (material.specularModel == SpecularModel::Phong) {
    const glm::dvec3 reflected = 2.0 * cosine * normal - toLight;
    alignment = glm::dot(reflected, toViewer);
  } else {
    const auto half = detail::normalizeRobust(toLight + toViewer);
    if (!half) return 0.0;  // light exactly behind the viewer's line of sight: no half vector
    alignment = glm::dot(normal, half->unit);
  }
  // Clamp to [0, 1] first: a dot of unit vectors may round past 1, and x^1e6 would notice.
  alignment = std::clamp(alignment, 0.0, 1.0);
  return std::pow(alignment, capped(material.specularPower));
}

}  // namespace

Shader::PreparedLight Shader::prepare(const Light& light) {
  using Kind = PreparedLight::Kind;
  return std::visit(
      detail::Overloaded{
          [](const DirectionalLight& l) {
            return PreparedLight{Kind::Directional, glm::dvec3{0.0},
                                 -detail::normalizeRobust(l.direction)->unit,
                                 radianceOf(l.color, l.intensity), NoAttenuation{}, {}};
          },
          [](const PointLight& l) {
            return PreparedLight{Kind::Point, l.position, glm::dvec3{0.0},
                                 radianceOf(l.color, l.intensity), l.attenuation, {}};
          },
          [](const SpotLight& l) {
            return PreparedLight{Kind::Spot, l.position,
                                 detail::normalizeRobust(l.direction)->unit,
                                 radianceOf(l.color, l.intensity), l.attenuation, l.cone};
          },
      },
      light);
}

void Shader::reset(const LightSet& lightSet) {
  lights_.clear();
  ambient_ = glm::dvec3(0.0);
  hasPositionalLights_ = false;
  validate(lightSet);
  ambient_ = radianceOf(lightSet.ambient.color, lightSet.ambient.intensity);
  for (const Light& light : lightSet.lights) {
    const PreparedLight prepared = prepare(light);
    if (prepared.radiance == glm::dvec3(0.0)) continue;  // dark lights cost nothing
    lights_.push_back(prepared);
    hasPositionalLights_ |= prepared.kind != PreparedLight::Kind::Directional;
  }
}

Shader::LightAtPoint Shader::arriving(const PreparedLight& light,
                                      const SurfaceSample& sample) const {
  if (light.kind == PreparedLight::Kind::Directional) return {light.direction, light.radiance};
  // A light exactly at the point lights it head-on (see "Edge cases" in Lighting.h).
  glm::dvec3 toLight = sample.normal;
  double distance = 0.0;
  const glm::dvec3 offset = light.position - sample.position;
  if (offset != glm::dvec3(0.0)) {
    const auto unit = detail::normalizeRobust(offset);
    if (!unit) return {sample.normal, glm::dvec3{0.0}};  // beyond double range: unreachable
    toLight = unit->unit;
    distance = unit->length;
  }
  double factor = attenuationFactor(light.attenuation, distance);
  if (light.kind == PreparedLight::Kind::Spot) {
    factor *= spotFactor(light.cone, glm::dot(-toLight, light.direction));
  }
  return {toLight, light.radiance * factor};
}

Color Shader::shade(const SurfaceSample& sample, const Material& material) const {
  const glm::dvec3 surface = capped(sample.color);
  const glm::dvec3 ambientColor = material.ambientColor ? capped(*material.ambientColor) : surface;
  const double ka = capped(material.ambient);
  const double kd = capped(material.diffuse);
  const double ks = capped(material.specular);

  glm::dvec3 diffuseSum{0.0}, specularSum{0.0};
  for (const PreparedLight& light : lights_) {
    const LightAtPoint arrived = arriving(light, sample);
    if (arrived.radiance == glm::dvec3(0.0)) continue;
    const double cosine = glm::dot(sample.normal, arrived.toLight);
    diffuseSum += arrived.radiance * diffuseFactor(material, cosine);
    if (ks > 0.0 && cosine > 0.0) {
      specularSum += arrived.radiance *
                     specularFactor(material, sample.normal, arrived.toLight, sample.toViewer,
                                    std::min(cosine, 1.0));
    }
  }

  const glm::dvec3 base = ka * ambientColor + surface * ambient_ + kd * surface * diffuseSum;
  const glm::dvec3 specularColor = capped(material.specularColor);
  if (material.specularMix == SpecularMix::Add) {
    return saturate(Color(base + ks * specularColor * specularSum));
  }
  const glm::dvec3 unblended(saturate(Color(base)));
  const glm::dvec3 blend = glm::min(ks * specularSum, glm::dvec3(1.0));
  return saturate(Color((1.0 - blend) * unblended + blend * specularColor));
}

Color shade(const SurfaceSample& sample, const Material& material, const LightSet& lightSet) {
  return Shader(lightSet).shade(sample, material);
}

double diffuseFactor(const Material& material, double cosine) {
  const double lit = cosine > 0.0 ? std::min(cosine, 1.0) : 0.0;  // NaN → 0
  if (material.diffuseModel == DiffuseModel::Lambert) return lit;
  const double unlitLevel = capped(material.lerpAmbient);
  return unlitLevel + (capped(material.lerpFull) - unlitLevel) * lit;
}

double angleBetweenDegrees(const glm::dvec3& a, const glm::dvec3& b) {
  detail::requireNonZeroDirection(a, "angleBetweenDegrees: a");
  detail::requireNonZeroDirection(b, "angleBetweenDegrees: b");
  const glm::dvec3 ua = detail::normalizeRobust(a)->unit;
  const glm::dvec3 ub = detail::normalizeRobust(b)->unit;
  // atan2(|a×b|, a·b) is accurate at every angle, unlike acos near 0° and 180°.
  return glm::degrees(std::atan2(glm::length(glm::cross(ua, ub)), glm::dot(ua, ub)));
}

}  // namespace facet
