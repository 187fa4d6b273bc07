#include "atpVtkErrorMessage.h"

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

} // namespace atp
