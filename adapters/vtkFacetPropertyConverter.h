/**
 * @class   vtkFacetPropertyConverter
 * @brief   Private: a vtkProperty as Facet's material, meaning what VTK's OpenGL renderer
 *          makes of it.
 *
 * Lit surfaces use Ambient, Diffuse, Specular, SpecularPower, AmbientColor, DiffuseColor,
 * SpecularColor and BackfaceCulling; with scalar coloring the scalars replace the ambient
 * and diffuse colors, as in VTK. Unlit surfaces (the property's Lighting off, or, in a
 * vtkRenderer, no light switched on) show what VTK's shaders show without lights,
 * Ka·Ca + Kd·Cd: the material's ambient term carries that color, its diffuse and specular
 * terms are 0 (a scene ambient light, which VTK does not have, still adds to it). Under a
 * headlight alone VTK's shader takes the highlight as (N·V)^power, with N·V in view space:
 * Blinn-Phong's (N·H)^power, H being V when the light is at the eye; the material then asks
 * for Blinn-Phong (under other lights VTK's, and the material's, is Phong's).
 *
 * Not rendered yet, and named by Unrendered: PBR interpolation (rendered flat; Gouraud and
 * Phong are rendered, vtkFacetQuality), opacity below 1 (opaque), the wireframe and points
 * representations and edge visibility (rendered as surfaces), textures.
 */

#ifndef vtkFacetPropertyConverter_h
#define vtkFacetPropertyConverter_h

#include "vtkFacetSceneConverter.h"

#include "facet/Material.h"

#include <string>

class vtkProperty;

class vtkFacetPropertyConverter
{
public:
  static facet::Material Convert(vtkProperty* property,
    bool scalarColoring,
    vtkFacetSceneConverter::Lighting lighting);

  /**
   * What the property asks for that Facet does not render yet, as a phrase ("Physically
   * based rendering interpolation (shown flat) and opacity 0.5"); empty when it asks for nothing of
   * the kind.
   */
  static std::string Unrendered(vtkProperty* property);

  /// A VTK color (three doubles in [0, 1], as vtkProperty and vtkLight hold them) as Facet's.
  static facet::Color ToColor(const double rgb[3]);
};

#endif
