#pragma once

/// @file Material.h
/// Surface material: the coefficients mean what vtkProperty's do. The formula that uses them
/// is in Lighting.h.

#include <optional>

#include "facet/Color.h"

namespace facet {

/// How a light's angle of incidence scales its diffuse contribution.
enum class DiffuseModel {
  /// max(0, N·L): Lambert's cosine law (Sixth 3D, VTK).
  Lambert,
  /// lerpAmbient + (lerpFull − lerpAmbient)·clamp(N·L, 0, 1): the "Lighting and Shadows"
  /// note's linear interpolation between an unlit and a fully lit level.
  Lerp,
};

/// How the specular highlight is measured.
enum class SpecularModel {
  /// max(0, R·V)^power with R the light direction mirrored about N (VTK's shaders).
  Phong,
  /// max(0, N·H)^power with H the unit half vector of L and V.
  BlinnPhong,
};

/// How the specular term joins the rest of the color.
enum class SpecularMix {
  /// Added: + specular · specularColor ⊙ Σ light (VTK, OpenGL).
  Add,
  /// The "Lighting and Shadows" note's blend f·light + (1 − f)·diffuse, f the specular
  /// factor: a highlight replaces the surface color instead of adding to it.
  Blend,
};

/// A surface material. Defaults are vtkProperty's, which also make the formula Sixth 3D's.
struct Material {
  /// Base (diffuse) color; per-polygon colors replace it. (default: white)
  Color color{1.0f};
  /// Color of the Ka term. Unset means "the surface color", as vtkProperty::SetColor and
  /// scalar coloring make it. (default: unset)
  std::optional<Color> ambientColor;
  Color specularColor{1.0f};   ///< (default: white, as vtkProperty)
  double ambient = 0.0;        ///< Ka, vtkProperty::Ambient (default: 0)
  double diffuse = 1.0;        ///< Kd, vtkProperty::Diffuse (default: 1)
  double specular = 0.0;       ///< Ks, vtkProperty::Specular (default: 0)
  double specularPower = 1.0;  ///< shininess n ≥ 0, vtkProperty::SpecularPower (default: 1)

  DiffuseModel diffuseModel = DiffuseModel::Lambert;  ///< (default: Lambert)
  double lerpAmbient = 0.0;  ///< Lerp model's unlit level a (default: 0, so Lerp = Lambert)
  double lerpFull = 1.0;     ///< Lerp model's fully lit level f (default: 1)
  SpecularModel specularModel = SpecularModel::Phong;  ///< (default: Phong, as VTK)
  SpecularMix specularMix = SpecularMix::Add;          ///< (default: Add, as VTK)

  /// Skip polygons whose window-space winding is clockwise (vtkProperty::BackfaceCulling).
  /// (default: off)
  bool backfaceCulling = false;
  friend bool operator==(const Material&, const Material&) = default;
};

/// Throws facet::Error naming the first invalid value: a non-finite number, a negative
/// coefficient, power or color channel.
void validate(const Material& material);

}  // namespace facet
