// A large temporary array in a memory-mapped ScratchFile, so arrays bigger than memory (vertex
// positions, per-vertex sketches of billion-triangle meshes) live in the page cache and the
// kernel can write them out instead of the process running out of memory. The file has no name
// (see ScratchFile): a crash leaves nothing behind.
#ifndef atpScratchArray_h
#define atpScratchArray_h

#include "atpScratchFile.h"
#include "vtkATPIOModule.h" // export macro

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace atp
{

/// The untyped part of ScratchArray: a ScratchFile mapped whole, shared and read-write.
class VTKATPIO_EXPORT ScratchMapping
{
public:
  /// Throws std::runtime_error naming the directory when the file cannot be created.
  explicit ScratchMapping(const std::string& directory);
  ~ScratchMapping();
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

/// A zero-initialized array of trivially copyable T in a ScratchMapping.
template<typename T>
class ScratchArray
{
  static_assert(std::is_trivially_copyable<T>::value, "ScratchArray stores raw bytes");

public:
  ScratchArray(const std::string& directory, std::size_t count)
    : Storage(directory)
  {
    this->Resize(count);
  }

  /// Grows to `count` elements, keeping the existing ones; invalidates pointers.
  void Resize(std::size_t count)
  {
    if (count > this->Count)
    {
      if (count > static_cast<std::size_t>(-1) / sizeof(T))
      {
        throw std::length_error("ScratchArray: size overflows the address space");
      }
      this->Storage.Grow(count * sizeof(T));
      this->Count = count;
    }
  }

  T* Data() { return static_cast<T*>(this->Storage.Data()); }
  const T* Data() const { return static_cast<const T*>(this->Storage.Data()); }
  std::size_t Size() const { return this->Count; }
  T& operator[](std::size_t i) { return this->Data()[i]; }
  const T& operator[](std::size_t i) const { return this->Data()[i]; }

private:
  ScratchMapping Storage;
  std::size_t Count = 0;
};

} // namespace atp

#endif
