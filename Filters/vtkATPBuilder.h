/**
 * @class   vtkATPBuilder
 * @brief   Builds an Adaptive TetraPuzzles multiresolution model from a triangle mesh.
 *
 * Input is either a mesh file streamed from disk (SetInputFileName: PLY, OBJ, STL, VTP), which
 * never needs to fit in memory, a volume file (NIfTI .nii/.nii.gz, VTK .vti, or raw voxels
 * described by SetRawVolumeLayout) whose isosurface at IsoValue is contoured slab by slab, or a
 * vtkPolyData on input port 0; the model is written to
 * FileName (.atp), like a vtkWriter. The triangles are partitioned out of core into a forest of
 * tetrahedra (longest-edge bisection, 6 roots): each triangle goes to the leaf holding its
 * centroid and a leaf with more than LeafCapacity triangles splits with its whole diamond. Then,
 * bottom-up, every diamond simplifies its children's patches to at most PatchBudget triangles
 * per member, and at most half of the member's children's, with its external boundary locked, and errors, spheres and normal cones are saturated.
 * Progress events report the fraction done; GetProgressText() names the phase.
 *
 * Build() runs the pipeline and returns 1 on success; on failure it returns 0, reports a
 * vtkErrorMacro naming the input and the problem, GetErrorMessage() holds that message, and no
 * file that looks like a model is left at FileName (an existing one is untouched).
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
class PatchJobRunner;
struct ConstructionStats;
struct PartitionStats;
struct InputStats;
struct RawVolumeLayout;
struct SlabContourStats;
class TriangleSource;
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
  /// Mesh file to stream (used instead of input port 0 when set: the port's data is not read,
  /// but a pipeline still connected there runs first, and its failure fails the build).
  vtkSetStringMacro(InputFileName);
  vtkGetStringMacro(InputFileName);
  ///@}

  ///@{
  /// For a volume InputFileName: the value whose isosurface is built. Required for volumes and
  /// refused for meshes; NaN (the default) means none.
  vtkSetMacro(IsoValue, double);
  vtkGetMacro(IsoValue, double);
  ///@}

  ///@{
  /// Z slices per slab when contouring a volume (default 64, at least 2): memory holds one slab.
  vtkSetClampMacro(SlabSlices, int, 2, 1 << 20);
  vtkGetMacro(SlabSlices, int);
  ///@}

  /// Reads InputFileName as raw voxels of this layout, whatever its extension (nullptr, the
  /// default: the extension says what the file is).
  void SetRawVolumeLayout(const atp::RawVolumeLayout* layout);

  ///@{
  /// The model file to write (.atp).
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Most triangles a tetrahedron of a simplified level holds (default 2000).
  vtkSetClampMacro(PatchBudget, int, 16, 1 << 20);
  vtkGetMacro(PatchBudget, int);
  ///@}

  ///@{
  /// Orders each patch's triangles with meshoptimizer's FIFO vertex-cache optimizer instead of
  /// its default one (default off): the build takes about 12% less time, the model about 6% more
  /// bytes and decoding it about 8% more time (docs/construction.md).
  vtkSetMacro(FastCacheOrder, bool);
  vtkGetMacro(FastCacheOrder, bool);
  vtkBooleanMacro(FastCacheOrder, bool);
  ///@}

  ///@{
  /// Worker threads for simplification and encoding (default 0: every core). The model is
  /// byte-identical whatever the count.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /// Where the leaf and diamond jobs run (not owned; must outlive Build()): nullptr (default)
  /// runs them on NumberOfThreads threads, `atp build --mpi` on MPI worker processes. The model
  /// is byte-identical either way.
  void SetJobRunner(atp::PatchJobRunner* runner) { this->JobRunner = runner; }
  atp::PatchJobRunner* GetJobRunner() const { return this->JobRunner; }

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
  /// What the last successful build found wrong with its input without failing (also sent as
  /// a vtkWarningMacro), or an empty string: triangles wound either way at random, which the
  /// model keeps and which shade speckled.
  const char* GetWarningMessage() const { return this->WarningMessage.c_str(); }

  /// Triangles the running build expects to read (from the input's header), for progress
  /// observers that show a rate; 0 before the input is open or when unknown.
  vtkGetMacro(ExpectedTriangles, vtkTypeUInt64);

  ///@{
  /// Figures of the last successful build.
  const atp::InputStats& GetInputStats() const;
  const atp::PartitionStats& GetPartitionStats() const;
  const atp::ConstructionStats& GetConstructionStats() const;
  /// The volume's figures when the input was a volume; nullptr otherwise.
  const atp::SlabContourStats* GetVolumeStats() const;
  /// Wall-clock seconds of the partitioning phase (reading included) and of construction.
  double GetPartitionSeconds() const;
  double GetConstructionSeconds() const;
  /// CPU seconds of this process, all threads together, in each phase (construction's steps:
  /// GetConstructionStats().Cpu).
  double GetPartitionCpuSeconds() const;
  double GetConstructionCpuSeconds() const;
  ///@}

protected:
  vtkATPBuilder();
  ~vtkATPBuilder() override;

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  /// Observers cancel with SetAbortExecute(1); the build stops at the next progress report.
  void ThrowIfAborted();

  char* InputFileName = nullptr;
  char* FileName = nullptr;
  char* ScratchDirectory = nullptr;
  double IsoValue;
  int SlabSlices;
  int LeafCapacity = 4000;
  int PatchBudget = 2000;
  bool FastCacheOrder = false;
  int NumberOfThreads = 0;
  int BucketMemoryMiB = 256;
  atp::PatchJobRunner* JobRunner = nullptr;
  vtkTypeUInt64 ExpectedTriangles = 0;

private:
  vtkATPBuilder(const vtkATPBuilder&) = delete;
  void operator=(const vtkATPBuilder&) = delete;

  struct Results;
  /// The triangles of the input file or of the polydata on port 0, a volume's figures noted in
  /// `running`; throws std::exception.
  std::unique_ptr<atp::TriangleSource> OpenSource(vtkInformationVector** inputs, Results& running);
  /// What a build needs and is not set (an input, an output FileName), or an empty string.
  std::string MissingSetting();

  std::unique_ptr<Results> Last;
  std::unique_ptr<atp::RawVolumeLayout> RawLayout;
  std::string ErrorMessage;
  std::string WarningMessage;
};

#endif
