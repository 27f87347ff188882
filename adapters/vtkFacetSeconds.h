/**
 * Private: the seconds since a steady-clock time point, for the adapters' timings
 * (FacetRenderSeconds, FacetPhaseSeconds, the compositor's costs).
 */

#ifndef vtkFacetSeconds_h
#define vtkFacetSeconds_h

#include <chrono>

inline double vtkFacetSecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

#endif
