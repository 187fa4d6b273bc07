// In-place edits of an existing .atp model that touch only its header, so a calibration can
// be stored without rewriting (or even reading) the patches.
#ifndef atpModelEdit_h
#define atpModelEdit_h

#include "vtkATPIOModule.h"

#include <string>

namespace atp
{

/// Validates the model at `path` (as ModelFile::Open does), then rewrites its header with
/// ErrorScale = `scale` and a recomputed HeaderChecksum: one write of the header, then fsync.
/// Every other byte of the file is left as it was. Throws ModelError (a std::runtime_error)
/// naming the file when it is no valid model, when `scale` is not finite and non-negative, or
/// when the write fails; an invalid file is never written to.
VTKATPIO_EXPORT void SetModelErrorScale(const std::string& path, float scale);

} // namespace atp

#endif
