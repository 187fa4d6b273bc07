// Large, long-lived working memory (the partitioner's bucket pool) backed by transparent huge
// pages where the kernel allows it (its "madvise" mode, as on Debian). Filling memory 4 KiB
// page by page costs a page fault each, and on virtual machines that shadow the page tables a
// fault costs about 12 microseconds: 65,000 of them for a 256 MiB pool, most of a second on
// the partitioning thread. A 2 MiB page takes one.
#ifndef atpHugePageBuffer_h
#define atpHugePageBuffer_h

#include "vtkATPIOModule.h" // export macro

#include <cstddef>

namespace atp
{

class VTKATPIO_EXPORT HugePageBuffer
{
public:
  HugePageBuffer() = default;
  /// Zero-filled; memory is taken as pages are first touched, as with any allocation.
  /// Throws std::bad_alloc when the address space cannot be reserved.
  explicit HugePageBuffer(std::size_t bytes);
  ~HugePageBuffer();
  HugePageBuffer(HugePageBuffer&& other) noexcept;
  HugePageBuffer& operator=(HugePageBuffer&& other) noexcept;
  HugePageBuffer(const HugePageBuffer&) = delete;
  HugePageBuffer& operator=(const HugePageBuffer&) = delete;

  /// Aligned to a huge page (2 MiB).
  void* Data() const { return this->Aligned; }
  std::size_t Size() const { return this->Bytes; }

  static constexpr std::size_t HugePageBytes = std::size_t(2) << 20;

private:
  void Release();

  void* Mapping = nullptr;
  std::size_t MappedBytes = 0;
  void* Aligned = nullptr;
  std::size_t Bytes = 0;
};

} // namespace atp

#endif
