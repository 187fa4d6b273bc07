// The fields of a NIfTI header that decide whether VTK's reader can take the file at all. VTK
// 9.1's vtkNIFTIImageReader crashes on some datatype codes (FLOAT128, unknown ones): they are
// refused here first, with a message.
#ifndef atpNiftiHeader_h
#define atpNiftiHeader_h

#include <string>

namespace atp
{

/// Why the NIfTI-1 or NIfTI-2 file (.nii, or .nii.gz) at `path` cannot be read as a volume of
/// one scalar per voxel, or an empty string: a header that is no NIfTI header, or a datatype
/// other than 8, 16, 32 or 64-bit integers or 32 or 64-bit floats, or whose bits per voxel
/// disagree with it, or more voxels than the file holds (or, gzipped, could hold).
std::string NiftiHeaderProblem(const std::string& path);

} // namespace atp

#endif
