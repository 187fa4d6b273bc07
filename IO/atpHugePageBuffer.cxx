#include "atpHugePageBuffer.h"

#include <cstdint>
#include <new>
#include <sys/mman.h>
#include <utility>

namespace atp
{

HugePageBuffer::HugePageBuffer(std::size_t bytes)
  : Bytes(bytes)
{
  if (bytes == 0)
  {
    return;
  }
  // One huge page more than asked for, to start on a huge page boundary.
  const std::size_t rounded = (bytes + HugePageBytes - 1) / HugePageBytes * HugePageBytes;
  if (rounded < bytes || rounded + HugePageBytes < rounded)
  {
    throw std::bad_alloc();
  }
  this->MappedBytes = rounded + HugePageBytes;
  void* mapping = ::mmap(nullptr, this->MappedBytes, PROT_READ | PROT_WRITE,
    MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapping == MAP_FAILED)
  {
    throw std::bad_alloc();
  }
  this->Mapping = mapping;
  const std::uintptr_t start = std::uintptr_t(mapping);
  this->Aligned =
    reinterpret_cast<void*>((start + HugePageBytes - 1) / HugePageBytes * HugePageBytes);
  // Advice only: without huge pages (disabled, or another kernel) the buffer works the same.
  ::madvise(this->Aligned, rounded, MADV_HUGEPAGE);
}

HugePageBuffer::~HugePageBuffer()
{
  this->Release();
}

HugePageBuffer::HugePageBuffer(HugePageBuffer&& other) noexcept
{
  *this = std::move(other);
}

HugePageBuffer& HugePageBuffer::operator=(HugePageBuffer&& other) noexcept
{
  if (this != &other)
  {
    this->Release();
    this->Mapping = std::exchange(other.Mapping, nullptr);
    this->MappedBytes = std::exchange(other.MappedBytes, 0);
    this->Aligned = std::exchange(other.Aligned, nullptr);
    this->Bytes = std::exchange(other.Bytes, 0);
  }
  return *this;
}

void HugePageBuffer::Release()
{
  if (this->Mapping)
  {
    ::munmap(this->Mapping, this->MappedBytes);
    this->Mapping = nullptr;
  }
}

} // namespace atp
