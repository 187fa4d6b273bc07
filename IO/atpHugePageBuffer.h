// Large working memory backed by transparent huge pages where the kernel allows it (its
// "madvise" mode, as on Debian): the partitioner's bucket pool and its corner lookups (the
// forest's nodes and the bucket table grow with the input and live in scratch mappings
// instead, atpScratchArray.h). Filling memory 4 KiB page
// by page costs a page fault each, about 12 microseconds on virtual machines that shadow the
// page tables (65,000 of them for a 256 MiB pool), and random access over 4 KiB pages misses
// the TLB; a 2 MiB page takes one fault and one TLB entry.
#ifndef atpHugePageBuffer_h
#define atpHugePageBuffer_h

#include "vtkATPIOModule.h" // export macro

#include <cstddef>

namespace atp
{

constexpr std::size_t HugePageBytes = std::size_t(2) << 20;

/// Memory for `bytes`: from operator new below a huge page, otherwise a fresh (zero) mapping
/// aligned to and advised for huge pages. Throws std::bad_alloc.
VTKATPIO_EXPORT void* AllocateLarge(std::size_t bytes);
/// Gives back what AllocateLarge(bytes) returned, with the same `bytes`.
VTKATPIO_EXPORT void FreeLarge(void* memory, std::size_t bytes) noexcept;

/// A fixed-size, zero-filled buffer from AllocateLarge; memory is taken as pages are first
/// touched, so a large pool costs only what is used.
class VTKATPIO_EXPORT HugePageBuffer
{
public:
  HugePageBuffer() = default;
  explicit HugePageBuffer(std::size_t bytes);
  ~HugePageBuffer() { FreeLarge(this->Memory, this->Bytes); }
  HugePageBuffer(HugePageBuffer&& other) noexcept;
  HugePageBuffer& operator=(HugePageBuffer&& other) noexcept;
  HugePageBuffer(const HugePageBuffer&) = delete;
  HugePageBuffer& operator=(const HugePageBuffer&) = delete;

  void* Data() const { return this->Memory; }
  std::size_t Size() const { return this->Bytes; }
  /// Takes the page faults of [offset, offset + bytes) now, on the calling thread, so that a
  /// busier thread writing there later finds the memory mapped. Thread-safe with writes to the
  /// range. Does nothing where the kernel cannot (before Linux 5.14).
  void Prefault(std::size_t offset, std::size_t bytes) const;
  /// Gives the memory of [offset, offset + bytes) back to the system (the whole pages within
  /// it; any partial page at its ends is zeroed instead): the range reads as zeros after.
  /// Call StopHugePages first when a buffer shrinks piece by piece.
  void Release(std::size_t offset, std::size_t bytes);
  /// No more huge pages for this buffer: otherwise the kernel's khugepaged, which by default
  /// collapses a 2 MiB range holding a single 4 KiB page, fills released pieces back in.
  void StopHugePages();

private:
  void* Memory = nullptr;
  std::size_t Bytes = 0;
};

} // namespace atp

#endif
