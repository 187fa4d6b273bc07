// PNG output for the command line: written, read back whole, then put in place.
#ifndef atpPngFile_h
#define atpPngFile_h

class vtkImageData;

namespace atp
{

class PendingFile;

/// Writes `image` to `file`'s partial path with VTK's PNG writer, reads it back (VTK's writer
/// does not report a full disk) and commits it; throws file.Failure(reason) otherwise.
void WritePng(vtkImageData* image, PendingFile& file);

}

#endif
