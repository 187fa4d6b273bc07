// VTK reports reader errors to its output window; our readers turn them into InputError
// messages instead, keeping only VTK's message text.
#ifndef atpVtkErrors_h
#define atpVtkErrors_h

#include "atpVtkErrorMessage.h"

#include <vtkCommand.h>

#include <string>

namespace atp
{

/// Observes ErrorEvent (and WarningEvent, when added for it) and keeps the first message.
class VtkErrorCollector : public vtkCommand
{
public:
  static VtkErrorCollector* New() { return new VtkErrorCollector; }

  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    if ((event == vtkCommand::ErrorEvent || event == vtkCommand::WarningEvent) && callData &&
      this->FirstError.empty())
    {
      this->FirstError = VtkErrorMessage(static_cast<const char*>(callData));
    }
  }

  std::string FirstError;
};

} // namespace atp

#endif
