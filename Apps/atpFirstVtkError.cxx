#include "atpFirstVtkError.h"
#include "atpVtkErrorMessage.h"

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
  // One line for the command line.
  const std::string text = VtkErrorMessage(static_cast<const char*>(message));
  first->Message = text.substr(0, text.find('\n'));
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
