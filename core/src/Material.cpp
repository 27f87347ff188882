#include "facet/Material.h"

#include "Validate.h"

namespace facet {

void validate(const Material& material) {
  detail::requireColor(material.color, "Material.color");
  if (material.ambientColor) detail::requireColor(*material.ambientColor, "Material.ambientColor");
  detail::requireColor(material.specularColor, "Material.specularColor");
  detail::requireNonNegative(material.ambient, "Material.ambient");
  detail::requireNonNegative(material.diffuse, "Material.diffuse");
  detail::requireNonNegative(material.specular, "Material.specular");
  detail::requireNonNegative(material.specularPower, "Material.specularPower");
  detail::requireNonNegative(material.lerpAmbient, "Material.lerpAmbient");
  detail::requireNonNegative(material.lerpFull, "Material.lerpFull");
}

}  // namespace facet
