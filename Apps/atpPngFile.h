// PNG output for the command line: written and read back whole, ready to be put in place.
#ifndef atpPngFile_h
#define atpPngFile_h

class vtkImageData;

namespace atp
{

class PendingFile;

/// Writes `image` to `file`'s partial path with VTK's PNG writer and reads it back (VTK's
/// writer does not always report a full disk); throws file.Failure(reason) when that fails.
/// The caller commits the file.
void WritePng(vtkImageData* image, PendingFile& file);

}

#endif
