// VTK reports reader errors to its output window; our readers turn them into InputError
// messages instead, keeping only VTK's message text.
#ifndef atpVtkErrors_h
#define atpVtkErrors_h

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
      // VTK's text is "ERROR: In <source>, line <n>\n<class> (<address>): <message>\n":
      // keep the message.
      std::string text = static_cast<const char*>(callData);
      while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
      {
        text.pop_back();
      }
      const std::size_t prefix = text.rfind("): ");
      this->FirstError = prefix == std::string::npos ? text : text.substr(prefix + 3);
    }
  }

  std::string FirstError;
};

} // namespace atp

#endif
