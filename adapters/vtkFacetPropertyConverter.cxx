// VTK-HeaderTest-Exclude: vtkFacetPropertyConverter.h
#include "vtkFacetPropertyConverter.h"

#include "vtkFacetMessages.h"
#include "vtkProperty.h"

#include <sstream>
#include <vector>

namespace {
// VTK's unlit fragment color, ambientColor + diffuseColor = Ka·Ca + Kd·Cd, as an ambient
// term: with scalars (Ca = Cd = the scalar color) a coefficient, else a color.
void MakeUnlit(facet::Material& m, vtkProperty* property, bool scalarColoring)
{
  if (scalarColoring)
  {
    m.ambient = property->GetAmbient() + property->GetDiffuse();
  }
  else
  {
    m.ambientColor = vtkFacetPropertyConverter::ToColor(property->GetAmbientColor()) *
        static_cast<float>(property->GetAmbient()) +
      vtkFacetPropertyConverter::ToColor(property->GetDiffuseColor()) *
        static_cast<float>(property->GetDiffuse());
    m.ambient = 1.0;
  }
  m.diffuse = 0.0;
  m.specular = 0.0;
}
}

//------------------------------------------------------------------------------
facet::Material vtkFacetPropertyConverter::Convert(vtkProperty* property,
  bool scalarColoring,
  vtkFacetSceneConverter::Lighting lighting)
{
  facet::Material m;
  m.color = vtkFacetPropertyConverter::ToColor(property->GetDiffuseColor());
  if (!scalarColoring)
  {
    m.ambientColor = vtkFacetPropertyConverter::ToColor(property->GetAmbientColor());
  }
  m.specularColor = vtkFacetPropertyConverter::ToColor(property->GetSpecularColor());
  m.ambient = property->GetAmbient();
  m.diffuse = property->GetDiffuse();
  m.specular = property->GetSpecular();
  m.specularPower = property->GetSpecularPower();
  m.backfaceCulling = property->GetBackfaceCulling() != 0;
  if (lighting == vtkFacetSceneConverter::Lighting::Headlight)
  {
    m.specularModel = facet::SpecularModel::BlinnPhong;
  }
  if (lighting == vtkFacetSceneConverter::Lighting::Unlit || !property->GetLighting())
  {
    MakeUnlit(m, property, scalarColoring);
  }
  return m;
}

//------------------------------------------------------------------------------
std::string vtkFacetPropertyConverter::Unrendered(vtkProperty* property)
{
  std::vector<std::string> asks;
  if (property->GetInterpolation() == VTK_PBR)
  {
    asks.push_back(
      std::string(property->GetInterpolationAsString()) + " interpolation (shown flat)");
  }
  if (property->GetOpacity() < 1.0)
  {
    std::ostringstream opacity;
    opacity << "opacity " << property->GetOpacity();
    asks.push_back(opacity.str());
  }
  if (property->GetRepresentation() != VTK_SURFACE)
  {
    asks.push_back(std::string(property->GetRepresentationAsString()) + " representation");
  }
  if (property->GetEdgeVisibility())
  {
    asks.push_back("edge visibility");
  }
  if (property->GetNumberOfTextures() > 0)
  {
    asks.push_back("textures");
  }
  return vtkFacetMessages::List(asks);
}

facet::Color vtkFacetPropertyConverter::ToColor(const double rgb[3])
{
  return { static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2]) };
}
