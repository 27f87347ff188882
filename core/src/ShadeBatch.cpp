// ShadeBatch.h: Shader::shade (Lighting.cpp) in SIMD lanes, compiled once per instruction set
// by Highway's foreach_target (this file includes itself) and dispatched at run time, as
// SetupBatch.cpp. Each operation below is shade()'s on the same double operands in the same
// order (glm's dot products add (x + y) + z; a vector over a scalar divides each component);
// IEEE addition, multiplication, division and square root are correctly rounded on every
// instruction set, and the file is compiled without contraction into fused multiply-adds
// (core/CMakeLists.txt, as Lighting.cpp), so a lane gives shade()'s color and toRgba8's bytes.
//
// Without a specular term shade()'s last step is saturate(Color(base + 0)) for the additive
// mix and saturate(Color((1 − 0)·saturate(Color(base)) + 0)) for the blend: both the bytes of
// saturate(Color(base)) (adding +0 only turns a −0 into +0, which saturates to 0 alike).

#include <algorithm>
#include <cstdint>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "ShadeBatch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "ShadeBatch.h"
#include "ShaderAccess.h"

HWY_BEFORE_NAMESPACE();
namespace facet::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;
using DF = hn::Rebind<float, D>;
using DI = hn::Rebind<std::int32_t, D>;
using DU = hn::Rebind<std::uint32_t, D>;

static_assert(kShadeBatchSize * sizeof(double) % HWY_MAX_BYTES == 0,
              "a batch's columns hold whole groups of lanes");

// Radiance.h's capped(): x > 0 ? min(x, kMaxRadiance) : 0, NaN → 0.
HWY_INLINE V capped(D d, V x) {
  return hn::IfThenElseZero(x > hn::Zero(d), hn::Min(x, hn::Set(d, kMaxRadiance)));
}

// Color.h's toByte(saturate(x)) of each lane's channel.
HWY_INLINE hn::Vec<DU> toBytes(V channel) {
  const DF df;
  const hn::Vec<DF> x = hn::DemoteTo(df, channel);  // Color(base): rounded to float
  const hn::Vec<DF> saturated = hn::IfThenElseZero(x > hn::Zero(df), hn::Min(x, hn::Set(df, 1.0f)));
  const hn::Vec<DF> scaled = saturated * hn::Set(df, 255.0f) + hn::Set(df, 0.5f);
  return hn::BitCast(DU(), hn::ConvertTo(DI(), scaled));  // truncation, as static_cast
}

// One light's contribution to the diffuse sums of the lanes' samples: radiance ·
// diffuseFactor(N · L). `ordinary` loses the lanes whose light direction shade() would take
// by its rare branch (towardLight: a squared distance outside (1e-290, 1e290)).
HWY_INLINE void addLight(const PreparedLight& light, bool directional, const PreparedMaterial& m,
                         const V (&position)[3], const V (&normal)[3], V (&sum)[3], M& ordinary) {
  const D d;
  V toLight[3];
  if (directional) {
    for (int c = 0; c < 3; ++c)
      toLight[c] = hn::Set(d, light.direction[c]);
  } else {
    V offset[3];
    for (int c = 0; c < 3; ++c)
      offset[c] = hn::Set(d, light.position[c]) - position[c];
    const V squared = (offset[0] * offset[0] + offset[1] * offset[1]) + offset[2] * offset[2];
    ordinary =
        hn::And(ordinary, hn::And(squared > hn::Set(d, 1e-290), squared < hn::Set(d, 1e290)));
    const V distance = hn::Sqrt(squared);
    for (int c = 0; c < 3; ++c)
      toLight[c] = offset[c] / distance;
  }
  const V cosine = (normal[0] * toLight[0] + normal[1] * toLight[1]) + normal[2] * toLight[2];
  const V lit = hn::IfThenElseZero(cosine > hn::Zero(d), hn::Min(cosine, hn::Set(d, 1.0)));
  const V factor = m.material.diffuseModel == DiffuseModel::Lambert
                       ? lit
                       : hn::Set(d, m.lerpAmbient) + hn::Set(d, m.lerpFull - m.lerpAmbient) * lit;
  for (int c = 0; c < 3; ++c)
    sum[c] = sum[c] + hn::Set(d, light.radiance[c]) * factor;
}

// The terms of shade()'s base color: base = constant + perSum · (the lights' diffuse sum), with
// constant = m.ambient · (ambient color or Cd) + Cd · ambient light and perSum = m.diffuse · Cd,
// the same operations in the same order as base's expression.
HWY_INLINE void baseTerms(const PreparedMaterial& m, const glm::dvec3& ambient,
                          const V (&surface)[3], V (&constant)[3], V (&perSum)[3]) {
  const D d;
  for (int c = 0; c < 3; ++c) {
    const V ambientTerm = m.ambientColor ? hn::Set(d, m.ambient * (*m.ambientColor)[c])
                                         : hn::Set(d, m.ambient) * surface[c];
    constant[c] = ambientTerm + surface[c] * hn::Set(d, ambient[c]);
    perSum[c] = hn::Set(d, m.diffuse) * surface[c];
  }
}

// The lanes' colors as words (alpha toByte(1)) from the base terms and the diffuse sums.
HWY_INLINE hn::Vec<DU> colorWords(const V (&constant)[3], const V (&perSum)[3], const V (&sum)[3]) {
  hn::Vec<DU> word = hn::Set(DU(), 0xFF000000u);
  for (int c = 0; c < 3; ++c)
    word = hn::Or(word, hn::ShiftLeftSame(toBytes(constant[c] + perSum[c] * sum[c]), 8 * c));
  return word;
}

// Whether a lane among the first `valid` left `ordinary` (shade()'s rare branch).
HWY_INLINE bool anyRare(M ordinary, std::size_t valid) {
  const D d;
  return !hn::AllTrue(d, hn::Or(ordinary, hn::Not(hn::FirstN(d, valid))));
}

void ShadeLanes(const Shader& shader, const PreparedMaterial& m, const ShadeBatch& batch,
                ShadeBatchColors& out, ShadeBatchCenters* centers) {
  Rgba8* colors = out.data();
  const D d;
  const DF df;
  const std::size_t lanes = hn::Lanes(d);
  const std::vector<PreparedLight>& lights = ShaderAccess::lights(shader);
  const bool directional = ShaderAccess::loop(shader) == LightLoop::Directional;
  const glm::dvec3& ambient = ShaderAccess::ambient(shader);
  for (std::size_t i = 0; i < batch.count; i += lanes) {  // the columns hold whole groups
    V position[3], normal[3], surface[3], sum[3];
    for (int c = 0; c < 3; ++c) {
      position[c] = hn::Load(d, batch.cornerSum[c] + i) / hn::Load(d, batch.corners + i);
      normal[c] = hn::Load(d, batch.normal[c] + i);
      surface[c] = capped(d, hn::PromoteTo(d, hn::LoadU(df, batch.color[c] + i)));
      sum[c] = hn::Zero(d);
      if (centers) hn::Store(position[c], d, centers->xyz[c] + i);
    }
    M ordinary = hn::FirstN(d, batch.count - i);
    for (const PreparedLight& light : lights)
      addLight(light, directional, m, position, normal, sum, ordinary);
    V constant[3], perSum[3];
    baseTerms(m, ambient, surface, constant, perSum);
    hn::StoreU(colorWords(constant, perSum, sum), DU(),
               reinterpret_cast<std::uint32_t*>(colors + i));
    const std::size_t end = std::min(i + lanes, batch.count);
    if (anyRare(ordinary, end - i)) {
      const ShaderAccess::Routine shade = ShaderAccess::routine(shader, false);
      for (std::size_t j = i; j < end; ++j)  // a rare branch: shade() itself
        colors[j] = toRgba8(shade(shader, batch.sample(j), m));
    }
  }
}

using DU64 = hn::RebindToUnsigned<D>;

std::uint64_t ShadeTriangleLanes(const Shader& shader, const PreparedMaterial& m,
                                 const ShownTriangleBatch& batch, const Color& color, bool centers,
                                 ShadeBatchColors& out) {
  Rgba8* colors = out.data();
  const D d;
  const DU64 du;
  const std::size_t lanes = hn::Lanes(d);
  const std::vector<PreparedLight>& lights = ShaderAccess::lights(shader);
  const bool directional = ShaderAccess::loop(shader) == LightLoop::Directional;
  V surface[3], constant[3], perSum[3];
  for (int c = 0; c < 3; ++c)
    surface[c] = capped(d, hn::Set(d, static_cast<double>(color[c])));
  baseTerms(m, ShaderAccess::ambient(shader), surface, constant, perSum);
  const V origin = hn::Zero(d);
  std::uint64_t zeroNormals = 0;
  for (std::size_t i = 0; i < batch.count; i += lanes) {  // the columns hold whole groups
    const hn::Vec<DU64> flip = hn::Load(du, batch.flip + i);
    V position[3], normal[3], sum[3];
    for (int c = 0; c < 3; ++c) {
      normal[c] = hn::PromoteTo(d, hn::LoadU(DF(), batch.normal[c] + i));
      sum[c] = origin;
    }
    const M zero = hn::And(hn::And(normal[0] == origin, normal[1] == origin), normal[2] == origin);
    for (int c = 0; c < 3; ++c) {
      normal[c] = hn::BitCast(d, hn::Xor(hn::BitCast(du, normal[c]), flip));
      position[c] = origin;  // without centers: the origin over 1
    }
    if (centers) {
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 3; ++k)
          position[c] = position[c] + hn::Load(d, batch.corner[k][c] + i);
        position[c] = position[c] / hn::Set(d, 3.0);
      }
    }
    const std::size_t valid = std::min(lanes, batch.count - i);
    M ordinary = hn::FirstN(d, valid);
    for (const PreparedLight& light : lights)
      addLight(light, directional, m, position, normal, sum, ordinary);
    hn::StoreU(colorWords(constant, perSum, sum), DU(),
               reinterpret_cast<std::uint32_t*>(colors + i));
    const M zeroShown = hn::And(zero, hn::FirstN(d, valid));
    if (!hn::AllFalse(d, zeroShown)) {
      std::uint8_t bits[8] = {};
      hn::StoreMaskBits(d, zeroShown, bits);
      zeroNormals |= std::uint64_t{bits[0]} << i;
    }
    if (anyRare(ordinary, valid)) {  // a rare branch: shade() itself
      alignas(64) double xyz[2][3][HWY_MAX_BYTES / sizeof(double)];
      for (int c = 0; c < 3; ++c) {
        hn::Store(position[c], d, xyz[0][c]);
        hn::Store(normal[c], d, xyz[1][c]);
      }
      const ShaderAccess::Routine shade = ShaderAccess::routine(shader, false);
      for (std::size_t j = 0; j < valid; ++j) {
        SurfaceSample sample;
        sample.position = {xyz[0][0][j], xyz[0][1][j], xyz[0][2][j]};
        sample.normal = {xyz[1][0][j], xyz[1][1][j], xyz[1][2][j]};
        sample.color = color;
        colors[i + j] = toRgba8(shade(shader, sample, m));
      }
    }
  }
  return zeroNormals;
}

}  // namespace facet::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace facet::detail {

HWY_EXPORT(ShadeLanes);
HWY_EXPORT(ShadeTriangleLanes);

SurfaceSample ShadeBatch::sample(std::size_t i) const {
  SurfaceSample s;
  s.position = glm::dvec3(cornerSum[0][i], cornerSum[1][i], cornerSum[2][i]) / corners[i];
  s.normal = {normal[0][i], normal[1][i], normal[2][i]};
  s.color = {color[0][i], color[1][i], color[2][i]};
  return s;
}

bool shadesInBatches(const Shader& shader) {
  const LightLoop loop = ShaderAccess::loop(shader);
  return loop == LightLoop::Directional || loop == LightLoop::Point;
}

void shadeBatch(const Shader& shader, const PreparedMaterial& material, const ShadeBatch& batch,
                ShadeBatchColors& colors, ShadeBatchCenters* centers) {
  HWY_DYNAMIC_DISPATCH(ShadeLanes)(shader, material, batch, colors, centers);
}

std::uint64_t shadeTriangleBatch(const Shader& shader, const PreparedMaterial& material,
                                 const ShownTriangleBatch& batch, const Color& surface,
                                 bool centers, ShadeBatchColors& colors) {
  return HWY_DYNAMIC_DISPATCH(ShadeTriangleLanes)(shader, material, batch, surface, centers,
                                                  colors);
}

}  // namespace facet::detail
#endif  // HWY_ONCE
