/**
 * @class   vtkFacetFieldArray
 * @brief   Private: a one-tuple field data array of named components (`FacetCounts` and the
 *          like) that every execution adds to its output, kept from one execution to the next.
 *
 * The executive empties the output's field data before every execution (PrepareForNewData).
 * An array that nobody else holds then has this object's reference alone: it is refilled in
 * place (its values set, Modified()) rather than built again with its name and the names of
 * its components (a vtkObject, a tuple and a string per component at every Update(), on
 * caches the render has just flushed). An array somebody holds (a ShallowCopy of the output,
 * a Python reference) keeps its values: that execution adds a new one, as vtkFacetImageRenderer
 * does with its planes.
 */

#ifndef vtkFacetFieldArray_h
#define vtkFacetFieldArray_h

#include "vtkFieldData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <initializer_list>
#include <span>
#include <string>
#include <utility>

template<class ArrayType>
class vtkFacetFieldArray
{
public:
  using Value = typename ArrayType::ValueType;

  /// Adds the array `name` to `fieldData`: one tuple, component i named names[i] and valued
  /// valueOf(i).
  template<class ValueOf>
  void AddTo(vtkFieldData* fieldData,
    const char* name,
    std::span<const char* const> names,
    const ValueOf& valueOf)
  {
    this->Fill(
      fieldData, name, names.size(), [&](std::size_t c) { return names[c]; }, valueOf);
  }

  /// The same from (component name, value) pairs.
  void AddTo(vtkFieldData* fieldData,
    const char* name,
    std::initializer_list<std::pair<const char*, Value>> values)
  {
    const std::pair<const char*, Value>* pairs = values.begin();
    this->Fill(
      fieldData,
      name,
      values.size(),
      [&](std::size_t c) { return pairs[c].first; },
      [&](std::size_t c) { return pairs[c].second; });
  }

private:
  template<class NameOf, class ValueOf>
  void Fill(vtkFieldData* fieldData,
    const char* name,
    std::size_t components,
    const NameOf& nameOf,
    const ValueOf& valueOf)
  {
    const int count = static_cast<int>(components);
    // The kept array unless somebody else holds it (or it has another shape): a new one.
    if (!this->Array || this->Array->GetReferenceCount() > 1 ||
      this->Array->GetNumberOfComponents() != count)
    {
      this->Array = vtkSmartPointer<ArrayType>::New();
      this->Array->SetName(name);
      this->Array->SetNumberOfComponents(count);
      this->Array->SetNumberOfTuples(1);
      for (int c = 0; c < count; ++c)
      {
        this->Array->SetComponentName(c, nameOf(static_cast<std::size_t>(c)));
      }
    }
    for (int c = 0; c < count; ++c)
    {
      this->Array->SetTypedComponent(
        0, c, static_cast<Value>(valueOf(static_cast<std::size_t>(c))));
    }
    this->Array->Modified();
    fieldData->AddArray(this->Array);
  }

  vtkSmartPointer<ArrayType> Array;
};

/// A one-value string array (`FacetRenderPlan`), kept alike.
class vtkFacetFieldString
{
public:
  void AddTo(vtkFieldData* fieldData, const char* name, const std::string& value)
  {
    if (!this->Array || this->Array->GetReferenceCount() > 1)
    {
      this->Array = vtkSmartPointer<vtkStringArray>::New();
      this->Array->SetName(name);
      this->Array->SetNumberOfValues(1);
    }
    this->Array->SetValue(0, value);
    this->Array->Modified();
    fieldData->AddArray(this->Array);
  }

private:
  vtkSmartPointer<vtkStringArray> Array;
};

#endif
// VTK-HeaderTest-Exclude: vtkFacetFieldArray.h
