#include "atpVtkErrors.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"

namespace atp
{

namespace
{
void Record(vtkObject*, unsigned long, void* self, void* message)
{
  auto* first = static_cast<FirstVtkError*>(self);
  if (!first->Message.empty() || !message)
  {
    return;
  }
  // VTK's text: "ERROR: In file, line N\nvtkClass (0x...): what went wrong".
  std::string text = static_cast<const char*>(message);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
  {
    text.pop_back();
  }
  const std::size_t line = text.find('\n') + 1; // 0 when there is one line
  const std::size_t object = text.find("): ", line);
  first->Message = object == std::string::npos ? text : text.substr(object + 3);
  first->Message = first->Message.substr(0, first->Message.find('\n'));
}

void Ignore(vtkObject*, unsigned long, void*, void*) {}
} // namespace

FirstVtkError::FirstVtkError()
{
  Command->SetClientData(this);
  Command->SetCallback(Record);
}

void FirstVtkError::Watch(vtkObject* object)
{
  object->AddObserver(vtkCommand::ErrorEvent, Command);
  if (auto* algorithm = vtkAlgorithm::SafeDownCast(object))
  {
    vtkNew<vtkCallbackCommand> ignore;
    ignore->SetCallback(Ignore);
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, ignore);
  }
}

}
