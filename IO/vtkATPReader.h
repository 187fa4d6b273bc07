/**
 * @class   vtkATPReader
 * @brief   opens a .atp multiresolution model for a VTK pipeline
 *
 * Memory-maps the file (it is never read whole) and validates the header, version, byte order,
 * section layout, the node section's checksum and the forest's structure up front, in
 * O(nodes). Patch checksums are checked when each patch is first decoded. The output is a
 * vtkATPModel; its bounds are also published as vtkStreamingDemandDrivenPipeline::BOUNDS() during
 * RequestInformation, so cameras can be reset before anything is drawn.
 *
 * A missing, foreign, truncated or corrupt file is reported as a VTK error naming the file and
 * the problem (GetErrorCode() is then vtkErrorCode::FileFormatError or CannotOpenFileError)
 * and gives an empty output.
 */
#ifndef vtkATPReader_h
#define vtkATPReader_h

#include "vtkATPIOModule.h"
#include "vtkDataObjectAlgorithm.h"

#include <memory>
#include <string>

namespace atp
{
class ModelFile;
}
class vtkATPModel;

class VTKATPIO_EXPORT vtkATPReader : public vtkDataObjectAlgorithm
{
public:
  static vtkATPReader* New();
  vtkTypeMacro(vtkATPReader, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  vtkATPModel* GetOutput();

protected:
  vtkATPReader();
  ~vtkATPReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  char* FileName = nullptr;
  std::shared_ptr<const atp::ModelFile> Opened; ///< from the last RequestInformation

  vtkATPReader(const vtkATPReader&) = delete;
  void operator=(const vtkATPReader&) = delete;
};

#endif
