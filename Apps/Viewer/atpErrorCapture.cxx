#include "atpErrorCapture.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"

namespace atp
{

std::string ErrorEventMessage(const void* callData)
{
  std::string text = static_cast<const char*>(callData);
  const std::size_t object = text.find("): ");
  if (object != std::string::npos)
  {
    text = text.substr(object + 3);
  }
  text.erase(text.find_last_not_of('\n') + 1);
  return text;
}

ErrorCapture::ErrorCapture(const std::vector<vtkObject*>& objects)
{
  Command->SetClientData(this);
  Command->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* self = static_cast<ErrorCapture*>(client);
    if (self->First.empty())
    {
      self->First = ErrorEventMessage(call);
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
