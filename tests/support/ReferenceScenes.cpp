#include "ReferenceScenes.h"

namespace facet::testing {

Material shinyMaterial() {
  Material material;
  material.color = {0.9f, 0.7f, 0.5f};
  material.specular = 0.4;
  material.specularPower = 20.0;
  return material;
}

LightSet twoLights() {
  LightSet lights;
  lights.lights.push_back(DirectionalLight{{-1, -1, -2}, Color(0.8f)});
  lights.lights.push_back(PointLight{{2, 1, 3}, Color(0.6f, 0.6f, 0.9f)});
  return lights;
}

}  // namespace facet::testing
