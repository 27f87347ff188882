#include "vtkFacetLight.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkFacetLight);

//------------------------------------------------------------------------------
void vtkFacetLight::DeepCopy(vtkLight* light)
{
  this->Superclass::DeepCopy(light);
  if (auto* facet = vtkFacetLight::SafeDownCast(light))
  {
    this->SpotModel = facet->SpotModel;
    this->FullIntensityAngle = facet->FullIntensityAngle;
    this->FalloffAngle = facet->FalloffAngle;
    this->AttenuationModel = facet->AttenuationModel;
    this->FalloffDistance = facet->FalloffDistance;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkFacetLight::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "SpotModel: " << (this->SpotModel == LinearFalloff ? "LinearFalloff" : "ConeWithExponent")
     << "\n";
  os << indent << "FullIntensityAngle: " << this->FullIntensityAngle << "\n";
  os << indent << "FalloffAngle: " << this->FalloffAngle << "\n";
  os << indent << "AttenuationModel: "
     << (this->AttenuationModel == FalloffDistanceModel ? "FalloffDistance" : "Quadratic") << "\n";
  os << indent << "FalloffDistance: " << this->FalloffDistance << "\n";
}
