// What VTK's XML readers (.vtp, .vti) take on trust from a file, checked from its XML structure
// before they read its data: VTK 9.1 crashes on a string array where it expects numbers,
// allocates what a compressed array's header claims (2 GB for a 631-byte file), sizes arrays by
// the counts a piece declares, and falls back silently on an image's non-finite origin or
// spacing.
#ifndef atpVtkXmlCheck_h
#define atpVtkXmlCheck_h

class vtkXMLReader;

namespace atp
{

class InputFile;

/// Call after reader->UpdateInformation() on `file`, before the data is read. Throws InputError
/// naming the file and the problem when: an array of points or cells, or one of point or cell
/// data named as an attribute (the scalars, ...), is not of a numeric type; the points do not have 3 components; an image's origin, spacing or
/// direction is not finite; a compressed array's header claims more blocks or bytes than the file
/// holds, or blocks that decompress beyond what the compressor can reach; or a piece declares more
/// points or cells than the file could hold. A file VTK cannot parse is left to VTK's own error.
void CheckVtkXmlFile(vtkXMLReader* reader, const InputFile& file);

} // namespace atp

#endif
