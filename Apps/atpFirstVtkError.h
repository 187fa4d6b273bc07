// VTK errors as one line for the command line: the first message of the observed objects,
// instead of VTK's output window.
#ifndef atpFirstVtkError_h
#define atpFirstVtkError_h

#include "vtkCallbackCommand.h"
#include "vtkNew.h"

#include <string>

class vtkObject;

namespace atp
{

/// Observe objects with `AddObserver(vtkCommand::ErrorEvent, errors.Command)`; Message is the
/// first error's text without VTK's file, line and object prefix.
struct FirstVtkError
{
  vtkNew<vtkCallbackCommand> Command;
  std::string Message;

  FirstVtkError();
  /// Observes `object`'s errors (and its executive's, which only repeat that it failed, at
  /// length: they are dropped).
  void Watch(vtkObject* object);
};

}

#endif
