// Keeps large memory-mapped arrays from piling up in the process's resident memory: their pages
// stay in the kernel's page cache (cheap to map again) but leave the process, so streaming a
// mesh of any size needs the same resident memory.
#ifndef atpResidentPages_h
#define atpResidentPages_h

#include "vtkATPIOModule.h" // export macro

#include <cstddef>

namespace atp
{

/// Drops the whole pages inside [begin, begin + bytes) from the process. Only for file-backed
/// mappings (an input file, or a ScratchArray): their content comes back from the file on the
/// next access. Never call it on ordinary heap memory, which would read back as zeros.
VTKATPIO_EXPORT void ReleaseResidentPages(const void* begin, std::size_t bytes);

}

#endif
