// A large temporary array in a memory-mapped ScratchFile, so arrays bigger than memory (vertex
// positions, per-vertex sketches of billion-triangle meshes) live in the page cache and the
// kernel can write them out instead of the process running out of memory. The file has no name
// (see ScratchFile): a crash leaves nothing behind.
#ifndef atpScratchArray_h
#define atpScratchArray_h

#include "atpResidentPages.h"
#include "atpScratchFile.h"
#include "vtkATPIOModule.h" // export macro

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace atp
{

/// The untyped part of ScratchArray: a ScratchFile mapped whole, shared and read-write.
class VTKATPIO_EXPORT ScratchMapping
{
public:
  /// Throws std::runtime_error naming the directory when the file cannot be created.
  explicit ScratchMapping(const std::string& directory);
  ~ScratchMapping();
  ScratchMapping(ScratchMapping&& other) noexcept;
  ScratchMapping& operator=(ScratchMapping&& other) noexcept;
  ScratchMapping(const ScratchMapping&) = delete;
  ScratchMapping& operator=(const ScratchMapping&) = delete;

  /// Grows the file to `bytes` and maps all of it; new bytes are zero. Earlier pointers into
  /// the mapping become invalid.
  void Grow(std::size_t bytes);

  void* Data() const { return this->Mapping; }

private:
  void Unmap();

  ScratchFile File;
  void* Mapping = nullptr;
  std::size_t MappedBytes = 0;
};

/// A zero-initialized array of trivially copyable T in a ScratchMapping. Its pages can leave
/// the process (ReleaseResident) and come back from the page cache, or from the file once the
/// kernel has written them out, on the next access: arrays that grow with the input cost the
/// process only the pages it is working on.
template<typename T>
class ScratchArray
{
  static_assert(std::is_trivially_copyable<T>::value, "ScratchArray stores raw bytes");

public:
  explicit ScratchArray(const std::string& directory, std::size_t count = 0)
    : Storage(directory)
  {
    this->Resize(count);
  }
  ScratchArray(ScratchArray&& other) noexcept
    : Storage(std::move(other.Storage))
    , Count(std::exchange(other.Count, 0))
    , EverHeld(std::exchange(other.EverHeld, 0))
    , Capacity(std::exchange(other.Capacity, 0))
  {
  }
  ScratchArray& operator=(ScratchArray&& other) noexcept
  {
    this->Storage = std::move(other.Storage);
    this->Count = std::exchange(other.Count, 0);
    this->EverHeld = std::exchange(other.EverHeld, 0);
    this->Capacity = std::exchange(other.Capacity, 0);
    return *this;
  }

  /// Grows to `count` elements (never shrinks), keeping the existing ones; new ones are zero.
  /// The file grows by at least half at a time, so growing by a few elements at a time remaps
  /// rarely. Invalidates pointers when it remaps.
  void Resize(std::size_t count)
  {
    if (count > this->Capacity)
    {
      const std::size_t most = static_cast<std::size_t>(-1) / sizeof(T);
      if (count > most)
      {
        throw std::length_error("ScratchArray: size overflows the address space");
      }
      const std::size_t capacity = std::min(std::max(count, this->Capacity + this->Capacity / 2), most);
      this->Storage.Grow(capacity * sizeof(T));
      this->Capacity = capacity;
    }
    if (count > this->Count)
    {
      // Only elements an Assign gave up can hold anything: the file's new space reads zero.
      const std::size_t stale = std::min(count, this->EverHeld);
      if (stale > this->Count)
      {
        std::memset(
          static_cast<void*>(this->Data() + this->Count), 0, (stale - this->Count) * sizeof(T));
      }
      this->Count = count;
      this->EverHeld = std::max(this->EverHeld, count);
    }
  }
  /// Resize, the new elements set to `fill`.
  void Resize(std::size_t count, const T& fill)
  {
    const std::size_t old = this->Count;
    this->Resize(count);
    std::fill(this->Data() + old, this->Data() + this->Count, fill);
  }
  void PushBack(const T& value) { this->Resize(this->Count + 1, value); }
  /// Holds exactly `count` elements, all set to `fill`; the file keeps its size. Filled a slice
  /// at a time, each slice given back once written: filling costs one slice of resident memory,
  /// not the array.
  void Assign(std::size_t count, const T& fill)
  {
    constexpr std::size_t slice = std::max<std::size_t>(1, (std::size_t(4) << 20) / sizeof(T));
    // Released up to whole 2 MiB blocks only: the kernel may map a file's pages 2 MiB at a
    // time, and such a block that a release covers in part stays mapped in whole (a third of
    // an array of 12-byte elements stayed resident with releases slice by slice).
    constexpr std::uintptr_t block = std::uintptr_t(2) << 20;
    std::size_t released = 0; // bytes from Data()
    this->Count = 0;
    while (this->Count < count)
    {
      this->Resize(std::min(count, this->Count + slice), fill);
      const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(this->Data());
      const std::uintptr_t written = start + this->Count * sizeof(T);
      const std::uintptr_t upTo = this->Count == count ? written : written / block * block;
      if (upTo > start + released)
      {
        ReleaseResidentPages(reinterpret_cast<const void*>(start + released), upTo - start - released);
        released = upTo - start;
      }
    }
  }
  /// Drops the array's pages from the process's resident memory (ReleaseResidentPages); they
  /// keep their contents.
  void ReleaseResident() const { ReleaseResidentPages(this->Data(), this->Count * sizeof(T)); }

  T* Data() { return static_cast<T*>(this->Storage.Data()); }
  const T* Data() const { return static_cast<const T*>(this->Storage.Data()); }
  std::size_t Size() const { return this->Count; }
  T& operator[](std::size_t i) { return this->Data()[i]; }
  const T& operator[](std::size_t i) const { return this->Data()[i]; }

private:
  ScratchMapping Storage;
  std::size_t Count = 0;
  std::size_t EverHeld = 0; ///< the most elements held: the file is zero beyond
  std::size_t Capacity = 0;
};

} // namespace atp

#endif
