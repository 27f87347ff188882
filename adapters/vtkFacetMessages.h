/**
 * @class   vtkFacetMessages
 * @brief   Private: the errors and warnings of one execution, collected from every piece
 *          that converts a scene and reported once, on the algorithm.
 *
 * The pieces (geometry, coloring, material, transform, camera, lights) add what they find
 * here instead of reporting it themselves. At the end of RequestData the algorithm calls
 * Report, which sends all errors in one vtkErrorMacro and all warnings in one
 * vtkWarningMacro on the algorithm (so observers of its ErrorEvent and WarningEvent see
 * them), and starts over for the next execution. A message added twice is said once.
 *
 * Two kinds of warnings:
 * - AddWarning: about this execution's data (skipped cells, a missing color array): said
 *   at every execution that finds it;
 * - AddWarningOnce: about what Facet does not render yet (translucency, shadows, a
 *   camera's view shear, volumes): said once in the algorithm's life, not at every frame.
 *
 * SetContext names what the following messages are about ("actor 2 (vtkActor): "), for a
 * front end that converts many actors.
 */

#ifndef vtkFacetMessages_h
#define vtkFacetMessages_h

#include <set>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;

class vtkFacetMessages
{
public:
  void AddError(const std::string& message);
  void AddWarning(const std::string& message);
  void AddWarningOnce(const std::string& message);

  /// Prefixed to the messages added next (default: none).
  void SetContext(const std::string& context) { this->Context = context; }

  bool HasErrors() const { return !this->Errors.empty(); }

  /// "a", "a and b", "a, b and c": for messages that name several things.
  static std::string List(const std::vector<std::string>& items);

  /**
   * Reports the errors and warnings on `algorithm`, forgets them (not the warnings said
   * once) and returns RequestData's value: 1 without errors, else 0 with `output` emptied
   * (valid, without data).
   */
  int Report(vtkAlgorithm* algorithm, vtkDataObject* output);

private:
  static void AddOnce(std::vector<std::string>& messages, const std::string& message);

  std::string Context;
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
  std::set<std::string> SaidOnce;
};

#endif
