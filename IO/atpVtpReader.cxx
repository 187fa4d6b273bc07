#include "atpVtpReader.h"

#include "atpInputFile.h"

#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkXMLPolyDataReader.h>

namespace atp
{
namespace
{
/// Keeps VTK's first error message for our exception instead of the console.
class ErrorCollector : public vtkCommand
{
public:
  static ErrorCollector* New() { return new ErrorCollector; }

  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    if (event == vtkCommand::ErrorEvent && callData && this->FirstError.empty())
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
} // namespace

vtkSmartPointer<vtkPolyData> ReadVtpFile(const std::string& path)
{
  const InputFile file(path); // missing or unreadable files get our message, not VTK's

  vtkNew<vtkXMLPolyDataReader> reader;
  vtkNew<ErrorCollector> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->AddObserver(vtkCommand::WarningEvent, errors);
  reader->SetFileName(path.c_str());
  reader->Update();
  if (!errors->FirstError.empty() || reader->GetErrorCode() != 0)
  {
    file.Fail("not a readable VTK XML PolyData file" +
      (errors->FirstError.empty() ? std::string() : ": " + errors->FirstError));
  }
  return reader->GetOutput();
}

} // namespace atp
