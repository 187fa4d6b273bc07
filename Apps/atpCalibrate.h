// atp calibrate: finds a model's error scale as the paper does (section 5.2), the smallest
// scale at which view-dependent cuts at a sub-pixel tolerance look the same as the full
// resolution from random views, and stores it in the model (docs/calibration.md).
#ifndef atpCalibrate_h
#define atpCalibrate_h

#include <string>
#include <vector>

namespace atp
{

/// Returns the process exit code; arguments follow the command name.
int CalibrateCommand(const std::vector<std::string>& arguments);

}

#endif
