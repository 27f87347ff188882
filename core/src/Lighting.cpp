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
double capped(double x) {
  return x > 0.0 ? std::min(x, kMaxRadiance) : 0.0;
}
glm::dvec3 capped(const Color& c) {
  return {capped(c.r), capped(c.g), capped(c.b)};
}

glm::dvec3 radianceOf(const Color& color, double intensity) {
  const double i = std::max(intensity, 0.0);
  return {capped(color.r * i), capped(color.g * i), capped(color.b * i)};
}

double specularFactor(const PreparedMaterial& m, const glm::dvec3& normal,
                      const glm::dvec3& toLight, const glm::dvec3& toViewer, double cosine) {
  double alignment = 0.0;
  if (m.material.specularModel == SpecularModel::Phong) {
    const glm::dvec3 reflected = 2.0 * cosine * normal - toLight;
    alignment = glm::dot(reflected, toViewer);
  } else {
    const auto half = detail::normalizeRobust(toLight + toViewer);
    if (!half) return 0.0;  // light exactly behind the viewer's line of sight: no half vector
    alignment = glm::dot(normal, half->unit);
  }
  // Clamp to [0, 1] first: a dot of unit vectors may round past 1, and x^1e6 would notice.
  alignment = std::clamp(alignment, 0.0, 1.0);
  return std::pow(alignment, m.specularPower);
}

double preparedDiffuseFactor(const PreparedMaterial& m, double cosine) {
  const double lit = cosine > 0.0 ? std::min(cosine, 1.0) : 0.0;  // NaN → 0
  if (m.material.diffuseModel == DiffuseModel::Lambert) return lit;
  return m.lerpAmbient + (m.lerpFull - m.lerpAmbient) * lit;
}

}  // namespace

Shader::PreparedLight Shader::prepare(const Light& light) {
  using Kind = PreparedLight::Kind;
  return std::visit(detail::Overloaded{
                        [](const DirectionalLight& l) {
                          return PreparedLight{Kind::Directional,
                                               glm::dvec3{0.0},
                                               -detail::normalizeRobust(l.direction)->unit,
                                               radianceOf(l.color, l.intensity),
                                               NoAttenuation{},
                                               {}};
                        },
                        [](const PointLight& l) {
                          return PreparedLight{Kind::Point,     l.position,
                                               glm::dvec3{0.0}, radianceOf(l.color, l.intensity),
                                               l.attenuation,   {}};
                        },
                        [](const SpotLight& l) {
                          return PreparedLight{Kind::Spot,
                                               l.position,
                                               detail::normalizeRobust(l.direction)->unit,
                                               radianceOf(l.color, l.intensity),
                                               l.attenuation,
                                               l.cone};
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

PreparedMaterial::PreparedMaterial(const Material& m)
    : material(m),
      specularColor(capped(m.specularColor)),
      ambient(capped(m.ambient)),
      diffuse(capped(m.diffuse)),
      specular(capped(m.specular)),
      specularPower(capped(m.specularPower)),
      lerpAmbient(capped(m.lerpAmbient)),
      lerpFull(capped(m.lerpFull)) {
  if (m.ambientColor) ambientColor = capped(*m.ambientColor);
}

inline glm::dvec3 Shader::arriving(const PreparedLight& light, const SurfaceSample& sample,
                                   glm::dvec3& toLight) const {
  if (light.kind == PreparedLight::Kind::Directional) {
    toLight = light.direction;
    return light.radiance;
  }
  // A light exactly at the point lights it head-on (see "Edge cases" in Lighting.h).
  toLight = sample.normal;
  double distance = 0.0;
  const glm::dvec3 offset = light.position - sample.position;
  const double distanceSquared = glm::dot(offset, offset);
  if (distanceSquared > 1e-290 && distanceSquared < 1e290) {  // the common case, exactly
    distance = std::sqrt(distanceSquared);
    toLight = offset / distance;
  } else if (offset != glm::dvec3(0.0)) {
    const auto unit = detail::normalizeRobust(offset);
    if (!unit) return glm::dvec3(0.0);  // beyond double range: unreachable
    toLight = unit->unit;
    distance = unit->length;
  }
  double factor = std::holds_alternative<NoAttenuation>(light.attenuation)
                      ? 1.0
                      : attenuationFactor(light.attenuation, distance);
  if (light.kind == PreparedLight::Kind::Spot) {
    factor *= spotFactor(light.cone, glm::dot(-toLight, light.direction));
  }
  return light.radiance * factor;
}

Color Shader::shade(const SurfaceSample& sample, const Material& material) const {
  return shade(sample, PreparedMaterial(material));
}

Color Shader::shade(const SurfaceSample& sample, const PreparedMaterial& m) const {
  const glm::dvec3 surface = capped(sample.color);
  glm::dvec3 diffuseSum{0.0}, specularSum{0.0};
  for (const PreparedLight& light : lights_) {
    glm::dvec3 toLight;
    const glm::dvec3 radiance = arriving(light, sample, toLight);
    if (radiance == glm::dvec3(0.0)) continue;
    const double cosine = glm::dot(sample.normal, toLight);
    diffuseSum += radiance * preparedDiffuseFactor(m, cosine);
    if (m.specular > 0.0 && cosine > 0.0) {
      specularSum += radiance * specularFactor(m, sample.normal, toLight, sample.toViewer,
                                               std::min(cosine, 1.0));
    }
  }

  const glm::dvec3 ambientTerm = m.ambient * (m.ambientColor ? *m.ambientColor : surface);
  const glm::dvec3 base = ambientTerm + surface * ambient_ + m.diffuse * surface * diffuseSum;
  if (m.material.specularMix == SpecularMix::Add) {
    return saturate(Color(base + m.specular * m.specularColor * specularSum));
  }
  const glm::dvec3 unblended(saturate(Color(base)));
  const glm::dvec3 blend = glm::min(m.specular * specularSum, glm::dvec3(1.0));
  return saturate(Color((1.0 - blend) * unblended + blend * m.specularColor));
}

Color shade(const SurfaceSample& sample, const Material& material, const LightSet& lightSet) {
  return Shader(lightSet).shade(sample, material);
}

double diffuseFactor(const Material& material, double cosine) {
  return preparedDiffuseFactor(PreparedMaterial(material), cosine);
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
