/**
 * @class   vtkFacetActorTransform
 * @brief   Private: an actor's points in world coordinates, from its full matrix
 *          (vtkProp3D::GetMatrix: position, orientation, scale, origin, user matrix and
 *          user transform).
 *
 * The points are transformed on the CPU, in double precision, into a copy the core reads
 * like any other points; the identity (the filter's case, and most actors) hands the points
 * over untouched, without a copy. Transforming here rather than giving the core a per-mesh
 * matrix keeps the core's one transform phase as it is (world to clip, in double, relative
 * to the eye: the precision that makes data far from the origin render like data at it) and
 * loses nothing: x' = M x in double from float or double input is within an ulp or two of
 * double, far below any input's own precision. What it costs is a copy of 24 bytes a point,
 * made again only when the points or the matrix change, not when the camera or the lights
 * do. A core matrix would save that copy for scenes that move many large actors every frame.
 *
 * A matrix that mirrors (negative determinant) turns outward windings inward, and one with a
 * projective last row may fold space: closed surfaces then lose their closedSurface mark so
 * that the renderer does not skip faces that show. Back faces are decided, and culled, by
 * window-space winding after the transform, as OpenGL decides them for VTK.
 */

#ifndef vtkFacetActorTransform_h
#define vtkFacetActorTransform_h

#include "vtkTimeStamp.h"

#include "facet/Mesh.h"

#include <algorithm>
#include <array>
#include <vector>

class vtkMatrix4x4;

class vtkFacetActorTransform
{
public:
  /**
   * The world points for `points` (model coordinates) under `matrix` (model to world; null:
   * the identity). `pointsChanged` says that the points are not those of the last call
   * even if their address is.
   */
  facet::PointArray Update(const facet::PointArray& points,
    bool pointsChanged,
    vtkMatrix4x4* matrix);

  /// Whether the last matrix keeps outward windings outward: affine with determinant > 0.
  bool KeepsOrientation() const { return this->Orientation; }

  /// Whether the last matrix was the identity (the points are the model points).
  bool IsIdentity() const { return this->Identity; }

  /// The MeshView::version of the last world points, for model points of version `points`:
  /// theirs under the identity, else also when they were last transformed (VTK's clock).
  vtkMTimeType Version(vtkMTimeType points) const
  {
    return this->Identity ? points : std::max(points, this->Transformed.GetMTime());
  }

private:
  std::array<double, 16> Matrix{};
  facet::PointArray Source;
  bool Valid = false;
  bool Identity = true;
  bool Orientation = true;
  vtkTimeStamp Transformed;
  std::vector<double> World; // xyz, for a matrix other than the identity
};

#endif
