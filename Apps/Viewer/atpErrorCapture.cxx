#include "atpErrorCapture.h"
#include "atpVtkErrorMessage.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"

namespace atp
{

ErrorCapture::ErrorCapture(const std::vector<vtkObject*>& objects)
{
  Command->SetClientData(this);
  Command->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* self = static_cast<ErrorCapture*>(client);
    if (self->First.empty())
    {
      self->First = VtkErrorMessage(static_cast<const char*>(call));
    }
  });
  for (vtkObject* object : objects)
  {
    Observed.emplace_back(object, object->AddObserver(vtkCommand::ErrorEvent, Command));
  }
}

ErrorCapture::~ErrorCapture()
{
  for (const auto& [object, tag] : Observed)
  {
    object->RemoveObserver(tag);
  }
}

}
