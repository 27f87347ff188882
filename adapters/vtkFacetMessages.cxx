// VTK-HeaderTest-Exclude: vtkFacetMessages.h
#include "vtkFacetMessages.h"

#include "vtkAlgorithm.h"
#include "vtkDataObject.h"

#include <algorithm>

namespace {
std::string Lines(const std::vector<std::string>& messages)
{
  std::string text;
  for (const std::string& message : messages)
  {
    text += (text.empty() ? "" : "\n") + message;
  }
  return text;
}
}

//------------------------------------------------------------------------------
std::string vtkFacetMessages::List(const std::vector<std::string>& items)
{
  std::string list;
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    list += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  }
  return list;
}

//------------------------------------------------------------------------------
void vtkFacetMessages::AddOnce(std::vector<std::string>& messages, const std::string& message)
{
  if (std::find(messages.begin(), messages.end(), message) == messages.end())
  {
    messages.push_back(message);
  }
}

//------------------------------------------------------------------------------
void vtkFacetMessages::AddError(const std::string& message)
{
  AddOnce(this->Errors, this->Context + message);
}

void vtkFacetMessages::AddWarning(const std::string& message)
{
  AddOnce(this->Warnings, this->Context + message);
}

void vtkFacetMessages::AddWarningOnce(const std::string& message)
{
  if (this->SaidOnce.insert(this->Context + message).second)
  {
    this->AddWarning(message);
  }
}

//------------------------------------------------------------------------------
int vtkFacetMessages::Report(vtkAlgorithm* algorithm, vtkDataObject* output)
{
  const bool failed = this->HasErrors();
  if (failed)
  {
    vtkErrorWithObjectMacro(algorithm, << Lines(this->Errors));
    output->Initialize();
  }
  if (!this->Warnings.empty())
  {
    vtkWarningWithObjectMacro(algorithm, << Lines(this->Warnings));
  }
  this->Errors.clear();
  this->Warnings.clear();
  this->Context.clear();
  return failed ? 0 : 1;
}
