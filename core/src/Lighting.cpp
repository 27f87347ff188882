#include "facet/Lighting.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "Overloaded.h"
#include "Radiance.h"
#include "Validate.h"
#include "Vector.h"

namespace facet {
namespace {

using detail::capped;
using detail::radianceOf;

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

using detail::PreparedLight;

// The direction to a positional light and its distance; a light exactly at the point lights
// it head-on (see "Edge cases" in Lighting.h). False when the distance is beyond double's
// range (no light arrives).
bool towardLight(const PreparedLight& light, const SurfaceSample& sample, glm::dvec3& toLight,
                 double& distance) {
  toLight = sample.normal;
  distance = 0.0;
  const glm::dvec3 offset = light.position - sample.position;
  const double distanceSquared = glm::dot(offset, offset);
  if (distanceSquared > 1e-290 && distanceSquared < 1e290) {  // the common case, exactly
    distance = std::sqrt(distanceSquared);
    toLight = offset / distance;
  } else if (offset != glm::dvec3(0.0)) {
    const auto unit = detail::normalizeRobust(offset);
    if (!unit) return false;
    toLight = unit->unit;
    distance = unit->length;
  }
  return true;
}

glm::dvec3 arrivingDirectional(const PreparedLight& light, glm::dvec3& toLight) {
  toLight = light.direction;
  return light.radiance;
}

// A point light (ConeT = void) or a spot light of one attenuation and cone kind.
template <class AttenuationT, class ConeT>
glm::dvec3 arrivingPositional(const PreparedLight& light, const SurfaceSample& sample,
                              glm::dvec3& toLight) {
  double distance;
  if (!towardLight(light, sample, toLight, distance)) return glm::dvec3(0.0);
  double factor = 1.0;
  if constexpr (!std::is_same_v<AttenuationT, NoAttenuation>) {
    factor = attenuationFactor(*std::get_if<AttenuationT>(&light.attenuation), distance);
  }
  if constexpr (!std::is_void_v<ConeT>) {
    factor *= spotFactor(*std::get_if<ConeT>(&light.cone), glm::dot(-toLight, light.direction));
  }
  return light.radiance * factor;
}

// Any light, tested for its kind.
glm::dvec3 arrivingAny(const PreparedLight& light, const SurfaceSample& sample,
                       glm::dvec3& toLight) {
  if (light.kind == PreparedLight::Kind::Directional) return arrivingDirectional(light, toLight);
  double distance;
  if (!towardLight(light, sample, toLight, distance)) return glm::dvec3(0.0);
  double factor = std::holds_alternative<NoAttenuation>(light.attenuation)
                      ? 1.0
                      : attenuationFactor(light.attenuation, distance);
  if (light.kind == PreparedLight::Kind::Spot) {
    factor *= spotFactor(light.cone, glm::dot(-toLight, light.direction));
  }
  return light.radiance * factor;
}

// Eᵢ of one light at the sample; sets toLight. Zero when no light arrives.
template <detail::LightLoop kLoop>
glm::dvec3 arriving(const PreparedLight& light, const SurfaceSample& sample, glm::dvec3& toLight) {
  using detail::LightLoop;
  if constexpr (kLoop == LightLoop::Directional) {
    return arrivingDirectional(light, toLight);
  } else if constexpr (kLoop == LightLoop::Point) {
    return arrivingPositional<NoAttenuation, void>(light, sample, toLight);
  } else if constexpr (kLoop == LightLoop::PointQuadratic) {
    return arrivingPositional<QuadraticAttenuation, void>(light, sample, toLight);
  } else if constexpr (kLoop == LightLoop::PointFalloff) {
    return arrivingPositional<FalloffDistanceAttenuation, void>(light, sample, toLight);
  } else {
    return arrivingAny(light, sample, toLight);
  }
}

// The loop for these lights: one specialized for their kind and attenuation when they share
// them (the common scenes: a headlight, or point lights of one model), else the mixed one.
detail::LightLoop loopFor(const std::vector<PreparedLight>& lights) {
  using detail::LightLoop;
  const auto all = [&](auto&& predicate) {
    return std::all_of(lights.begin(), lights.end(), predicate);
  };
  const auto point = [&](auto attenuation) {
    return all([&](const PreparedLight& l) {
      return l.kind == PreparedLight::Kind::Point &&
             std::holds_alternative<decltype(attenuation)>(l.attenuation);
    });
  };
  if (all([](const PreparedLight& l) { return l.kind == PreparedLight::Kind::Directional; })) {
    return LightLoop::Directional;
  }
  if (point(NoAttenuation{})) return LightLoop::Point;
  if (point(QuadraticAttenuation{})) return LightLoop::PointQuadratic;
  if (point(FalloffDistanceAttenuation{})) return LightLoop::PointFalloff;
  return LightLoop::Mixed;
}

// VTK's point and spot lights all carry (1, 0, 0): a factor of exactly 1 at every distance the
// shading reaches (towardLight gives a distance ≥ 0 or no light). Named as no attenuation they take
// the loop without a per-polygon attenuation call; the pixels are the same bytes.
Attenuation simplest(const Attenuation& attenuation) {
  const auto* quadratic = std::get_if<QuadraticAttenuation>(&attenuation);
  const bool none = quadratic != nullptr && *quadratic == QuadraticAttenuation{1.0, 0.0, 0.0};
  return none ? Attenuation{NoAttenuation{}} : attenuation;
}

PreparedLight prepare(const Light& light) {
  PreparedLight prepared;
  std::visit(detail::Overloaded{
                 [&](const DirectionalLight& l) {
                   prepared.direction = -detail::normalizeRobust(l.direction)->unit;
                   prepared.radiance = radianceOf(l.color, l.intensity);
                 },
                 [&](const PointLight& l) {
                   prepared.kind = PreparedLight::Kind::Point;
                   prepared.position = l.position;
                   prepared.radiance = radianceOf(l.color, l.intensity);
                   prepared.attenuation = simplest(l.attenuation);
                 },
                 [&](const SpotLight& l) {
                   prepared.kind = PreparedLight::Kind::Spot;
                   prepared.position = l.position;
                   prepared.direction = detail::normalizeRobust(l.direction)->unit;
                   prepared.radiance = radianceOf(l.color, l.intensity);
                   prepared.attenuation = simplest(l.attenuation);
                   prepared.cone = l.cone;
                 },
             },
             light);
  return prepared;
}

}  // namespace

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
  loop_ = loopFor(lights_);
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

Color Shader::shade(const SurfaceSample& sample, const Material& material) const {
  return shade(sample, PreparedMaterial(material));
}

Color Shader::shade(const SurfaceSample& sample, const PreparedMaterial& m) const {
  return routine(m.specular > 0.0)(*this, sample, m);
}

template <detail::LightLoop kLoop, bool kSpecular>
Color Shader::shadeWith(const Shader& shader, const SurfaceSample& sample,
                        const PreparedMaterial& m) {
  const glm::dvec3 surface = capped(sample.color);
  glm::dvec3 diffuseSum{0.0}, specularSum{0.0};
  for (const PreparedLight& light : shader.lights_) {
    glm::dvec3 toLight;
    const glm::dvec3 radiance = arriving<kLoop>(light, sample, toLight);
    if (radiance == glm::dvec3(0.0)) continue;
    const double cosine = glm::dot(sample.normal, toLight);
    diffuseSum += radiance * preparedDiffuseFactor(m, cosine);
    if (kSpecular && cosine > 0.0) {
      specularSum += radiance * specularFactor(m, sample.normal, toLight, sample.toViewer,
                                               std::min(cosine, 1.0));
    }
  }

  const glm::dvec3 ambientTerm = m.ambient * (m.ambientColor ? *m.ambientColor : surface);
  const glm::dvec3 base =
      ambientTerm + surface * shader.ambient_ + m.diffuse * surface * diffuseSum;
  if (m.material.specularMix == SpecularMix::Add) {
    return saturate(Color(base + m.specular * m.specularColor * specularSum));
  }
  const glm::dvec3 unblended(saturate(Color(base)));
  const glm::dvec3 blend = glm::min(m.specular * specularSum, glm::dvec3(1.0));
  return saturate(Color((1.0 - blend) * unblended + blend * m.specularColor));
}

Shader::Routine Shader::routine(bool specular) const {
  using detail::LightLoop;
  static constexpr Routine kRoutines[5][2] = {
      {shadeWith<LightLoop::Directional, false>, shadeWith<LightLoop::Directional, true>},
      {shadeWith<LightLoop::Point, false>, shadeWith<LightLoop::Point, true>},
      {shadeWith<LightLoop::PointQuadratic, false>, shadeWith<LightLoop::PointQuadratic, true>},
      {shadeWith<LightLoop::PointFalloff, false>, shadeWith<LightLoop::PointFalloff, true>},
      {shadeWith<LightLoop::Mixed, false>, shadeWith<LightLoop::Mixed, true>}};
  return kRoutines[static_cast<int>(loop_)][specular];
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
