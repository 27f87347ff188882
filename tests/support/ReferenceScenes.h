#pragma once

// The lit scene the reference tests and the convergence sweep share: a warm, shiny surface
// (a specular highlight is the hardest smooth detail to converge) under a directional and a
// point light.

#include "facet/Light.h"
#include "facet/Material.h"

namespace facet::testing {

Material shinyMaterial();
LightSet twoLights();

}  // namespace facet::testing
