#include "atpVtkErrorMessage.h"

#include "vtkErrorCode.h"

#include <cerrno>
#include <cstring>

namespace atp
{

std::string VtkErrorMessage(const char* text)
{
  std::string message = text ? text : "";
  while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
  {
    message.pop_back();
  }
  // The object prefix is on the line after "In FILE, line N" (a one-line text: from its start).
  const std::size_t line = message.find('\n') + 1;
  const std::size_t object = message.find("): ", line);
  return object == std::string::npos ? message : message.substr(object + 3);
}

std::string VtkErrorCodeText(unsigned long code)
{
  if (code == vtkErrorCode::OutOfDiskSpaceError)
  {
    return std::strerror(ENOSPC);
  }
  const char* text = vtkErrorCode::GetStringFromErrorCode(code);
  return text ? text : "error " + std::to_string(code);
}

} // namespace atp
