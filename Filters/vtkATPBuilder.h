/**
 * @class   vtkATPBuilder
 * @brief   Builds an Adaptive TetraPuzzles multiresolution model from a triangle mesh.
 *
 * Input is either a mesh file streamed from disk (SetFileName: PLY, OBJ, STL, VTP), which never
 * needs to fit in memory, or a vtkPolyData on input port 0. The triangles are partitioned out of
 * core into a forest of tetrahedra (longest-edge bisection, 6 roots): each triangle goes to the
 * leaf holding its centroid and a leaf with more than LeafCapacity triangles splits with its
 * whole diamond. Progress events report the fraction of triangles processed.
 *
 * Build() runs the pipeline and returns 1 on success; on failure it returns 0, reports a
 * vtkErrorMacro naming the input and the problem, and GetErrorMessage() holds that message.
 */
#ifndef vtkATPBuilder_h
#define vtkATPBuilder_h

#include "vtkATPFiltersModule.h"
#include "vtkAlgorithm.h"

#include <memory>
#include <string>

class vtkPolyData;

namespace atp
{
struct PartitionStats;
struct InputStats;
}

class VTKATPFILTERS_EXPORT vtkATPBuilder : public vtkAlgorithm
{
public:
  static vtkATPBuilder* New();
  vtkTypeMacro(vtkATPBuilder, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The mesh to build from, when it is already in memory (or use SetInputConnection).
  void SetInputData(vtkPolyData* mesh);

  ///@{
  /// Mesh file to stream (used instead of input port 0 when set).
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Most triangles a leaf tetrahedron holds before it splits (default 4000).
  vtkSetClampMacro(LeafCapacity, int, 1, 1 << 30);
  vtkGetMacro(LeafCapacity, int);
  ///@}

  ///@{
  /// Memory for in-memory triangle buckets, in MiB (default 256); the rest stays on disk.
  vtkSetClampMacro(BucketMemoryMiB, int, 1, 1 << 20);
  vtkGetMacro(BucketMemoryMiB, int);
  ///@}

  ///@{
  /// Directory for temporary files (default: $TMPDIR or /tmp). They are unlinked on creation,
  /// so nothing is left behind even if the process is killed.
  vtkSetStringMacro(ScratchDirectory);
  vtkGetStringMacro(ScratchDirectory);
  ///@}

  /// Runs the build. Returns 1 on success, 0 on failure (see GetErrorMessage()).
  int Build();
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

  /// Triangles the running build expects to read (from the input's header), for progress
  /// observers that show a rate; 0 before the input is open or when unknown.
  vtkGetMacro(ExpectedTriangles, vtkTypeUInt64);

  ///@{
  /// Figures of the last successful build.
  const atp::InputStats& GetInputStats() const;
  const atp::PartitionStats& GetPartitionStats() const;
  ///@}

protected:
  vtkATPBuilder();
  ~vtkATPBuilder() override;

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*);

  char* FileName = nullptr;
  char* ScratchDirectory = nullptr;
  int LeafCapacity = 4000;
  int BucketMemoryMiB = 256;
  vtkTypeUInt64 ExpectedTriangles = 0;

private:
  vtkATPBuilder(const vtkATPBuilder&) = delete;
  void operator=(const vtkATPBuilder&) = delete;

  struct Results;
  std::unique_ptr<Results> Last;
  std::string ErrorMessage;
};

#endif
