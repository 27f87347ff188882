/**
 * @class   vtkFacetLight
 * @brief   A vtkLight with the light models vtkLight lacks: a linear angular spot falloff
 *          and the "falloff distance" attenuation.
 *
 * vtkFacetLight is a vtkLight: VTK's renderers use it as one (they ignore the extra models),
 * and vtkFacetRenderFilter honours the extras. A plain vtkLight works everywhere too.
 *
 * Spot models (positional lights only):
 * - ConeWithExponent (default): vtkLight's own, cos(angle)^Exponent inside ConeAngle, no cone
 *   when ConeAngle is above 90 degrees.
 * - LinearFalloff: full intensity within FullIntensityAngle of the axis, falling linearly in
 *   angle to zero at FullIntensityAngle + FalloffAngle ("A Light Touch": 20 + 15 degrees).
 *
 * Attenuation models (positional lights only):
 * - Quadratic (default): vtkLight's AttenuationValues, 1 / (a0 + a1 d + a2 d^2).
 * - FalloffDistance: full intensity within FalloffDistance of the light, FalloffDistance / d
 *   beyond (half at twice the distance).
 *
 * @sa vtkLight vtkFacetRenderFilter
 */

#ifndef vtkFacetLight_h
#define vtkFacetLight_h

#include "FacetRenderingModule.h" // For export macro
#include "vtkLight.h"

class FACETRENDERING_EXPORT vtkFacetLight : public vtkLight
{
public:
  static vtkFacetLight* New();
  vtkTypeMacro(vtkFacetLight, vtkLight);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SpotModels
  {
    ConeWithExponent = 0,
    LinearFalloff = 1
  };

  enum AttenuationModels
  {
    Quadratic = 0,
    FalloffDistanceModel = 1
  };

  ///@{
  /**
   * How a positional light's intensity falls off away from its axis (default:
   * ConeWithExponent, vtkLight's ConeAngle and Exponent).
   */
  vtkSetClampMacro(SpotModel, int, ConeWithExponent, LinearFalloff);
  vtkGetMacro(SpotModel, int);
  void SetSpotModelToConeWithExponent() { this->SetSpotModel(ConeWithExponent); }
  void SetSpotModelToLinearFalloff() { this->SetSpotModel(LinearFalloff); }
  ///@}

  ///@{
  /**
   * LinearFalloff: the angle from the axis, in degrees, within which the spot has full
   * intensity (default: 20 degrees).
   */
  vtkSetClampMacro(FullIntensityAngle, double, 0.0, 180.0);
  vtkGetMacro(FullIntensityAngle, double);
  ///@}

  ///@{
  /**
   * LinearFalloff: the angle, in degrees, over which the intensity then falls linearly to
   * zero; 0 gives a hard edge (default: 15 degrees).
   */
  vtkSetClampMacro(FalloffAngle, double, 0.0, 180.0);
  vtkGetMacro(FalloffAngle, double);
  ///@}

  ///@{
  /**
   * How a positional light's intensity falls off with distance (default: Quadratic, using
   * vtkLight's AttenuationValues).
   */
  vtkSetClampMacro(AttenuationModel, int, Quadratic, FalloffDistanceModel);
  vtkGetMacro(AttenuationModel, int);
  void SetAttenuationModelToQuadratic() { this->SetAttenuationModel(Quadratic); }
  void SetAttenuationModelToFalloffDistance() { this->SetAttenuationModel(FalloffDistanceModel); }
  ///@}

  ///@{
  /**
   * FalloffDistance model: the distance, in world units, within which the light has full
   * intensity (default: 100).
   */
  vtkSetClampMacro(FalloffDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(FalloffDistance, double);
  ///@}

  /**
   * Copies the vtkLight settings and, from another vtkFacetLight, the Facet models too.
   */
  void DeepCopy(vtkLight* light);

protected:
  vtkFacetLight() = default;
  ~vtkFacetLight() override = default;

  int SpotModel = ConeWithExponent;
  double FullIntensityAngle = 20.0;
  double FalloffAngle = 15.0;
  int AttenuationModel = Quadratic;
  double FalloffDistance = 100.0;

private:
  vtkFacetLight(const vtkFacetLight&) = delete;
  void operator=(const vtkFacetLight&) = delete;
};

#endif
