// The routines lit at polygon centers, diffuse (ShadeLit.h).
#include "ShadeLit.h"

namespace facet::detail {
template ShadeRoutineChoice shading::litRoutine<true, false>(shading::ColorSource);
}  // namespace facet::detail
