// Keeps the VTK errors some objects report, instead of letting VTK print them, so the viewer
// can show the first one to the person in a message box.
#ifndef atpErrorCapture_h
#define atpErrorCapture_h

#include "vtkNew.h"

#include <string>
#include <utility>
#include <vector>

class vtkCallbackCommand;
class vtkObject;

namespace atp
{

class ErrorCapture
{
public:
  /// Observes the objects' error events for as long as it lives (the objects must outlive it).
  explicit ErrorCapture(const std::vector<vtkObject*>& objects);
  ~ErrorCapture();
  ErrorCapture(const ErrorCapture&) = delete;
  ErrorCapture& operator=(const ErrorCapture&) = delete;

  /// The first error reported (empty when none): the one nearest the cause, since a failing
  /// algorithm reports before the pipeline and the algorithms downstream do.
  const std::string& Message() const { return First; }

private:
  vtkNew<vtkCallbackCommand> Command;
  std::vector<std::pair<vtkObject*, unsigned long>> Observed;
  std::string First;
};

}

#endif
