#include "facet/RenderPlan.h"

namespace facet {

const char* ruleName(Rule rule) {
  switch (rule) {
    case Rule::LightsThatReachNothing:
      return "lights that reach nothing";
    case Rule::GeometryOutsideView:
      return "geometry outside the view";
    case Rule::HiddenGeometry:
      return "hidden geometry (hierarchical z)";
    case Rule::AmbientOnly:
      return "ambient only";
    case Rule::OneColor:
      return "one color for a whole mesh";
    case Rule::ClosedSurfaces:
      return "closed surfaces";
  }
  return "";
}

bool RenderRules::allows(Rule rule) const {
  switch (rule) {
    case Rule::LightsThatReachNothing:
      return lightsThatReachNothing;
    case Rule::GeometryOutsideView:
      return geometryOutsideView;
    case Rule::HiddenGeometry:
      return hiddenGeometry != HierarchicalZ::Off;
    case Rule::AmbientOnly:
      return ambientOnly;
    case Rule::OneColor:
      return oneColor;
    case Rule::ClosedSurfaces:
      return closedSurfaces;
  }
  return false;
}

}  // namespace facet
