// The routines lit at polygon centers, specular (ShadeLit.h).
#include "ShadeLit.h"

namespace facet::detail {
template ShadeRoutineChoice shading::litRoutine<true, true>(shading::ColorSource);
}  // namespace facet::detail
