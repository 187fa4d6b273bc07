/**
 * @class   vtkATPModel
 * @brief   an opened .atp multiresolution model, as a data object of the VTK pipeline
 *
 * Holds the memory map of a validated model (atp::ModelFile): node records and encoded patches
 * stay in the file and are paged in on demand, so the object is small whatever the model's size.
 * Copies share the map. Produced by vtkATPReader; consumed by vtkATPMapper and
 * vtkATPExtractCut.
 */
#ifndef vtkATPModel_h
#define vtkATPModel_h

#include "vtkATPIOModule.h"
#include "vtkDataObject.h"

#include <memory>

namespace atp
{
class ModelFile;
}

class VTKATPIO_EXPORT vtkATPModel : public vtkDataObject
{
public:
  static vtkATPModel* New();
  vtkTypeMacro(vtkATPModel, vtkDataObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The opened model, or null when empty.
  void SetModelFile(std::shared_ptr<const atp::ModelFile> model);
  const atp::ModelFile* GetModelFile() const { return this->Model.get(); }
  std::shared_ptr<const atp::ModelFile> GetSharedModelFile() const { return this->Model; }

  /// The input mesh's bounds (xmin, xmax, ymin, ymax, zmin, zmax); uninitialized when empty.
  void GetBounds(double bounds[6]);

  void Initialize() override;
  void ShallowCopy(vtkDataObject* source) override;
  void DeepCopy(vtkDataObject* source) override;
  /// Kibibytes of process memory: the map is file-backed and not counted.
  unsigned long GetActualMemorySize() override;

  static vtkATPModel* GetData(vtkInformation* info);
  static vtkATPModel* GetData(vtkInformationVector* v, int i = 0);

protected:
  vtkATPModel() = default;
  ~vtkATPModel() override = default;

private:
  std::shared_ptr<const atp::ModelFile> Model;

  vtkATPModel(const vtkATPModel&) = delete;
  void operator=(const vtkATPModel&) = delete;
};

#endif
