// VTK-HeaderTest-Exclude: vtkFacetActorTransform.h
#include "vtkFacetActorTransform.h"

#include "vtkMatrix4x4.h"

#include <span>

namespace {
constexpr std::array<double, 16>
  IdentityElements = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };

bool IsAffine(const double m[16])
{
  return m[12] == 0.0 && m[13] == 0.0 && m[14] == 0.0 && m[15] == 1.0;
}

template<class Real>
void TransformPoints(const Real* xyz, std::size_t count, const double m[16], double* out)
{
  const bool affine = IsAffine(m);
  for (std::size_t i = 0; i < count; ++i, xyz += 3, out += 3)
  {
    const double x = xyz[0], y = xyz[1], z = xyz[2];
    const double w = affine ? 1.0 : m[12] * x + m[13] * y + m[14] * z + m[15];
    for (int row = 0; row < 3; ++row)
    {
      const double* r = m + 4 * row;
      const double value = r[0] * x + r[1] * y + r[2] * z + r[3];
      out[row] = affine ? value : value / w; // w = 0: infinite, and the cells are skipped
    }
  }
}
}

//------------------------------------------------------------------------------
facet::PointArray vtkFacetActorTransform::Update(const facet::PointArray& points,
  bool pointsChanged,
  vtkMatrix4x4* matrix)
{
  std::array<double, 16> elements = IdentityElements;
  if (matrix)
  {
    std::copy(&matrix->Element[0][0], &matrix->Element[0][0] + 16, elements.begin());
  }
  this->Identity = elements == IdentityElements;
  if (this->Identity)
  {
    this->Orientation = true;
    this->World.clear();
    this->Valid = false;
    return points;
  }
  if (this->Valid && !pointsChanged && elements == this->Matrix &&
    points.data == this->Source.data && points.count == this->Source.count &&
    points.type == this->Source.type)
  {
    return facet::PointArray::ofXyz(std::span<const double>(this->World));
  }
  const double* m = elements.data();
  this->Orientation = IsAffine(m) && vtkMatrix4x4::Determinant(m) > 0.0;
  this->World.resize(3 * points.count);
  if (points.type == facet::PointArray::Type::Float32)
  {
    TransformPoints(static_cast<const float*>(points.data), points.count, m, this->World.data());
  }
  else
  {
    TransformPoints(static_cast<const double*>(points.data), points.count, m, this->World.data());
  }
  this->Matrix = elements;
  this->Source = points;
  this->Valid = true;
  this->Transformed.Modified();
  return facet::PointArray::ofXyz(std::span<const double>(this->World));
}
