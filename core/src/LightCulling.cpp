#include "LightCulling.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "Overloaded.h"
#include "Radiance.h"
#include "Vector.h"
#include "facet/Lighting.h"

namespace facet::detail {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The box's nearest point is reached at this fraction of its distance or more: attenuation
// is judged a little nearer than any polygon center can be, whatever the rounding.
constexpr double kNearer = 1.0 - 1e-9;

// gap(point) = cos α·|w| − w·axis with w = point − apex: ≤ 0 exactly where the point is in
// the closed cone of half-angle α ≤ 90°, and convex in the point.
struct ConeGap {
  glm::dvec3 apex, axis;
  double cosine;
  double at(const glm::dvec3& point) const {
    const glm::dvec3 w = point - apex;
    return cosine * glm::length(w) - glm::dot(w, axis);
  }
};

double leastAtVertices(const ConeGap& gap, const Box& box) {
  double least = kInfinity;
  for (int i = 0; i < 8; ++i)
    least = std::min(least, gap.at(box.corner(i)));
  return least;
}

// Along an edge (axis e) the gap is stationary where z/√(r² + z²) = axis[e]/cos α, z the
// offset along the edge from the apex's foot, r the apex's distance from the edge's line.
double leastOnEdge(const ConeGap& gap, const Box& box, int e, const glm::dvec3& start) {
  const double along = gap.axis[e];
  const glm::dvec3 w0 = start - gap.apex;
  const double r = std::hypot(w0[(e + 1) % 3], w0[(e + 2) % 3]);
  // r = 0: the apex is on the edge's line, and the minimum at a vertex or the apex itself.
  if (!(std::abs(along) < gap.cosine) || r == 0.0) return kInfinity;
  const double z = along * r / std::sqrt(gap.cosine * gap.cosine - along * along);
  const double s = z - w0[e];
  if (!(s > 0.0 && s < box.high[e] - box.low[e])) return kInfinity;
  glm::dvec3 point = start;
  point[e] += s;
  return gap.at(point);
}

double leastOnEdges(const ConeGap& gap, const Box& box) {
  double least = kInfinity;
  for (int e = 0; e < 3; ++e) {
    for (int corner = 0; corner < 8; ++corner) {
      if (corner & (1 << e)) continue;  // the edges along e start at the low end
      least = std::min(least, leastOnEdge(gap, box, e, box.corner(corner)));
    }
  }
  return least;
}

// On a face (normal axis n, at distance c from the apex) the gap is stationary where the
// in-plane part of w is |w|/cos α times the axis's, |w| = |c| / √(1 − q²/cos² α).
double leastOnFace(const ConeGap& gap, const Box& box, int n, double side) {
  const int u = (n + 1) % 3, v = (n + 2) % 3;
  const double cos2 = gap.cosine * gap.cosine;
  const double q2 = gap.axis[u] * gap.axis[u] + gap.axis[v] * gap.axis[v];
  const double c = side - gap.apex[n];
  if (!(q2 < cos2) || c == 0.0) return kInfinity;
  const double scale = std::abs(c) / std::sqrt(1.0 - q2 / cos2) / gap.cosine;
  glm::dvec3 point;
  point[n] = side;
  point[u] = gap.apex[u] + scale * gap.axis[u];
  point[v] = gap.apex[v] + scale * gap.axis[v];
  if (!(point[u] >= box.low[u] && point[u] <= box.high[u] && point[v] >= box.low[v] &&
        point[v] <= box.high[v])) {
    return kInfinity;
  }
  return gap.at(point);
}

double leastOnFaces(const ConeGap& gap, const Box& box) {
  double least = kInfinity;
  for (int n = 0; n < 3; ++n) {
    least = std::min(least, leastOnFace(gap, box, n, box.low[n]));
    least = std::min(least, leastOnFace(gap, box, n, box.high[n]));
  }
  return least;
}

bool isFinite(const Box& box) {
  const auto finite = [](const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  return finite(box.low) && finite(box.high);
}

// The angle from the axis from which the cone's factor is 0 (degrees); 180 when some light
// may go every way.
double darkFromDegrees(const SpotCone& cone) {
  return std::visit(Overloaded{
                        [](const LinearSpotCone& c) {
                          return c.fullIntensityAngleDegrees + c.falloffAngleDegrees;
                        },
                        [](const ExponentSpotCone& c) {
                          return c.coneAngleDegrees > 90.0 ? 180.0 : c.coneAngleDegrees;
                        },
                    },
                    cone);
}

// The most a unit of light can add to channel c of a polygon of this mesh (Lighting.h's
// formula): Kd·Cd·(largest diffuse factor) + Ks·Cs, where a blended highlight may move the
// color by up to max(Cs, 1) per unit of its factor.
double gainOf(const SceneMesh& mesh, int c) {
  const PreparedMaterial m(mesh.material);
  const double surface = mesh.mesh.polygonColors.empty() ? capped(mesh.material.color[c]) : 1.0;
  const double diffuse =
      m.material.diffuseModel == DiffuseModel::Lambert ? 1.0 : std::max(m.lerpAmbient, m.lerpFull);
  const double highlight = m.material.specularMix == SpecularMix::Add
                               ? m.specularColor[c]
                               : std::max(m.specularColor[c], 1.0);
  return m.diffuse * surface * diffuse + m.specular * highlight;
}

enum class Fate { Kept, Dark, OutsideCone, BelowTolerance };

struct Judgement {
  Fate fate = Fate::Kept;
  double bound = 0.0;  // the most it adds to a channel of any polygon
};

// A positional light against every mesh's box.
Judgement judgePositional(const glm::dvec3& position, const Attenuation& attenuation,
                          const SpotCone* cone, const glm::dvec3& axis, const glm::dvec3& radiance,
                          const LightTargets& targets, double tolerance) {
  bool reaches = false, contributes = false;
  double bound = 0.0;
  for (std::size_t m = 0; m < targets.meshes.size(); ++m) {
    const Box& box = targets.bounds[m];
    if (box.empty()) continue;
    if (!isFinite(box)) return {};
    if (cone && coneMissesBox(position, axis, darkFromDegrees(*cone), box)) continue;
    reaches = true;
    // normalizeRobust's length: a distance beyond ~1e154 is finite although its square is not.
    const auto toBox = detail::normalizeRobust(box.closestPoint(position) - position);
    const double distance = (toBox ? toBox->length : 0.0) * kNearer;
    const double factor = attenuationFactor(attenuation, distance);
    for (int c = 0; c < 3; ++c) {
      const double gain = gainOf(targets.meshes[m], c);
      contributes |= radiance[c] > 0.0 && factor > 0.0 && gain > 0.0;
      bound = std::max(bound, radiance[c] * factor * gain);
    }
  }
  if (!reaches) return {cone ? Fate::OutsideCone : Fate::BelowTolerance, 0.0};
  if (!contributes) return {Fate::BelowTolerance, 0.0};
  if (bound < tolerance) return {Fate::BelowTolerance, bound};
  return {};
}

Judgement judge(const Light& light, const LightTargets& targets, double tolerance) {
  return std::visit(Overloaded{
                        [&](const DirectionalLight& l) -> Judgement {
                          if (radianceOf(l.color, l.intensity) == glm::dvec3(0.0))
                            return {Fate::Dark};
                          return {};
                        },
                        [&](const PointLight& l) -> Judgement {
                          const glm::dvec3 radiance = radianceOf(l.color, l.intensity);
                          if (radiance == glm::dvec3(0.0)) return {Fate::Dark};
                          if (targets.bounds.empty()) return {};
                          return judgePositional(l.position, l.attenuation, nullptr,
                                                 glm::dvec3(0.0), radiance, targets, tolerance);
                        },
                        [&](const SpotLight& l) -> Judgement {
                          const glm::dvec3 radiance = radianceOf(l.color, l.intensity);
                          if (radiance == glm::dvec3(0.0)) return {Fate::Dark};
                          if (targets.bounds.empty()) return {};
                          return judgePositional(l.position, l.attenuation, &l.cone,
                                                 normalizeRobust(l.direction)->unit, radiance,
                                                 targets, tolerance);
                        },
                    },
                    light);
}

void count(Fate fate, std::size_t index, double bound, RenderPlan::LightCulling& report) {
  report.dark += fate == Fate::Dark;
  report.outsideCone += fate == Fate::OutsideCone;
  report.belowTolerance += fate == Fate::BelowTolerance;
  report.errorBound += bound;
  if (index < 64) report.culledMask |= std::uint64_t{1} << index;
}

}  // namespace

bool coneMissesBox(const glm::dvec3& apex, const glm::dvec3& axis, double halfAngleDegrees,
                   const Box& box) {
  if (box.empty()) return true;
  const double angle = halfAngleDegrees + kConeMarginDegrees;
  if (angle >= 180.0 || !isFinite(box) || box.contains(apex)) return false;
  if (angle < 90.0) {
    const ConeGap gap{apex, axis, std::cos(glm::radians(angle))};
    return std::min({leastAtVertices(gap, box), leastOnEdges(gap, box), leastOnFaces(gap, box)}) >
           0.0;
  }
  // Wider than a half-space: the lit part is not convex, its complement is (the cone of
  // 180° − α around −axis, open). The box misses the light when that cone holds its corners.
  const ConeGap dark{apex, -axis, std::cos(glm::radians(180.0 - angle))};
  for (int i = 0; i < 8; ++i) {
    if (!(dark.at(box.corner(i)) < 0.0)) return false;
  }
  return true;
}

bool lightCullingNeedsBounds(const LightSet& lights, double tolerance) {
  return std::any_of(lights.lights.begin(), lights.lights.end(), [&](const Light& light) {
    return std::holds_alternative<SpotLight>(light) ||
           (tolerance > 0.0 && std::holds_alternative<PointLight>(light));
  });
}

void cullLights(const LightSet& lights, const LightTargets& targets, double tolerance,
                LightSet& kept, RenderPlan::LightCulling& report) {
  kept.ambient = lights.ambient;
  kept.lights.clear();
  report = {};
  report.lights = lights.lights.size();
  report.tolerance = tolerance;
  for (std::size_t i = 0; i < lights.lights.size(); ++i) {
    const Judgement judgement = judge(lights.lights[i], targets, tolerance);
    if (judgement.fate == Fate::Kept) {
      kept.lights.push_back(lights.lights[i]);
    } else {
      count(judgement.fate, i, judgement.bound, report);
    }
  }
  // Rounding to bytes may tip one step more (Color.h, toByte); 1e-4 of a step covers the
  // float rounding of 255·x.
  report.errorBound8Bit = report.errorBound > 0.0
                              ? static_cast<int>(std::floor(255.0 * report.errorBound + 1e-4)) + 1
                              : 0;
}

}  // namespace facet::detail
