// The routines lit by light directions, specular (ShadeLit.h).
#include "ShadeLit.h"

namespace facet::detail {
template ShadeRoutineChoice shading::litRoutine<false, true>(shading::ColorSource);
}  // namespace facet::detail
