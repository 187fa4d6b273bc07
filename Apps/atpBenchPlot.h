// The flythrough as the paper's figure 7 shows it: charts stacked over the frame number, drawn
// offscreen with VTK's charts.
#ifndef atpBenchPlot_h
#define atpBenchPlot_h

#include "atpRenderStatistics.h"

#include "vtkSmartPointer.h"

#include <vector>

class vtkImageData;

namespace atp
{

/// Four charts over the frame number, top to bottom: frame time in ms (with the
/// full-resolution mapper's, when `fullSeconds` is not empty), triangles per frame, patches per
/// frame, and cache misses per frame with the uploads that followed. The picture is
/// width x height pixels (RGB).
vtkSmartPointer<vtkImageData> PlotFlythrough(const std::vector<double>& seconds,
  const std::vector<RenderStatistics>& statistics, const std::vector<double>& fullSeconds,
  int width, int height);

}

#endif
