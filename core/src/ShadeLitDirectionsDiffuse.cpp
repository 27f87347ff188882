// The routines lit by light directions, diffuse (ShadeLit.h).
#include "ShadeLit.h"

namespace facet::detail {
template ShadeRoutineChoice shading::litRoutine<false, false>(shading::ColorSource);
}  // namespace facet::detail
