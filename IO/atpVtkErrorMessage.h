// The message of a VTK error or warning event, without VTK's source file, line and object
// prefix: what our readers, commands and viewer show the user.
#ifndef atpVtkErrorMessage_h
#define atpVtkErrorMessage_h

#include "vtkATPIOModule.h" // export macro

#include <string>

namespace atp
{

/// `text` is the event's call data: "ERROR: In FILE, line N\nCLASS (ADDRESS): MESSAGE\n".
/// Returns MESSAGE without trailing line ends (the whole text when it has no such prefix).
VTKATPIO_EXPORT std::string VtkErrorMessage(const char* text);

/// What a writer's vtkErrorCode says, in the system's words where it has them (a full disk:
/// "No space left on device", not "OutOfDiskSpaceError").
VTKATPIO_EXPORT std::string VtkErrorCodeText(unsigned long code);

} // namespace atp

#endif
