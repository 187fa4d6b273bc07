#include "atpHugePageBuffer.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <new>
#include <sys/mman.h>
#include <unistd.h>
#include <utility>

namespace atp
{
namespace
{
std::uintptr_t RoundUp(std::uintptr_t value, std::uintptr_t step)
{
  return (value + step - 1) / step * step;
}

/// The mapping of a large block: whole huge pages.
std::size_t RoundedToHugePages(std::size_t bytes)
{
  const std::size_t rounded = RoundUp(bytes, HugePageBytes);
  if (rounded < bytes || rounded + HugePageBytes < rounded)
  {
    throw std::bad_alloc();
  }
  return rounded;
}
} // namespace

void* AllocateLarge(std::size_t bytes)
{
  if (bytes < HugePageBytes)
  {
    return ::operator new(bytes == 0 ? 1 : bytes);
  }
  // A huge page more than needed, then the unaligned ends cut off.
  const std::size_t rounded = RoundedToHugePages(bytes);
  const std::size_t mapped = rounded + HugePageBytes;
  void* mapping = ::mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapping == MAP_FAILED)
  {
    throw std::bad_alloc();
  }
  const std::uintptr_t start = std::uintptr_t(mapping);
  const std::uintptr_t aligned = RoundUp(start, HugePageBytes);
  if (aligned > start)
  {
    ::munmap(mapping, aligned - start);
  }
  if (start + mapped > aligned + rounded)
  {
    ::munmap(reinterpret_cast<void*>(aligned + rounded), start + mapped - (aligned + rounded));
  }
  // Advice only: without huge pages (disabled, or another kernel) the memory works the same.
  ::madvise(reinterpret_cast<void*>(aligned), rounded, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
}

void FreeLarge(void* memory, std::size_t bytes) noexcept
{
  if (!memory)
  {
    return;
  }
  if (bytes < HugePageBytes)
  {
    ::operator delete(memory);
    return;
  }
  ::munmap(memory, RoundedToHugePages(bytes)); // cannot throw: AllocateLarge rounded it
}

HugePageBuffer::HugePageBuffer(std::size_t bytes)
  : Memory(bytes == 0 ? nullptr : AllocateLarge(bytes))
  , Bytes(bytes)
{
  if (bytes < HugePageBytes && this->Memory)
  {
    std::memset(this->Memory, 0, bytes); // a fresh mapping is zero already
  }
}

void HugePageBuffer::Prefault(std::size_t offset, std::size_t bytes) const
{
  if (offset >= this->Bytes || this->Bytes < HugePageBytes)
  {
    return; // nothing there, or ordinary heap memory
  }
  bytes = std::min(bytes, this->Bytes - offset);
  // madvise wants a page-aligned start.
  static const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
  const std::uintptr_t begin = (std::uintptr_t(this->Memory) + offset) / page * page;
  const std::uintptr_t end = std::uintptr_t(this->Memory) + offset + bytes;
#ifdef MADV_POPULATE_WRITE
  ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)begin;
  (void)end;
#endif
}

void HugePageBuffer::StopHugePages()
{
  if (this->Bytes >= HugePageBytes)
  {
    ::madvise(this->Memory, RoundedToHugePages(this->Bytes), MADV_NOHUGEPAGE);
  }
}

void HugePageBuffer::Release(std::size_t offset, std::size_t bytes)
{
  if (offset >= this->Bytes)
  {
    return;
  }
  bytes = std::min(bytes, this->Bytes - offset);
  unsigned char* const start = static_cast<unsigned char*>(this->Memory) + offset;
  if (this->Bytes < HugePageBytes)
  {
    std::memset(start, 0, bytes); // heap memory: nothing to give back
    return;
  }
  static const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
  const std::uintptr_t begin = std::uintptr_t(start), end = begin + bytes;
  const std::uintptr_t wholeBegin = (begin + page - 1) / page * page;
  const std::uintptr_t wholeEnd = std::max(wholeBegin, end / page * page);
  std::memset(start, 0, std::min(end, wholeBegin) - begin);
  std::memset(reinterpret_cast<void*>(wholeEnd), 0, end - wholeEnd);
  // A private anonymous mapping reads back zero-filled pages after MADV_DONTNEED.
  if (wholeEnd > wholeBegin &&
    ::madvise(reinterpret_cast<void*>(wholeBegin), wholeEnd - wholeBegin, MADV_DONTNEED) != 0)
  {
    std::memset(reinterpret_cast<void*>(wholeBegin), 0, wholeEnd - wholeBegin);
  }
}

HugePageBuffer::HugePageBuffer(HugePageBuffer&& other) noexcept
  : Memory(std::exchange(other.Memory, nullptr))
  , Bytes(std::exchange(other.Bytes, 0))
{
}

HugePageBuffer& HugePageBuffer::operator=(HugePageBuffer&& other) noexcept
{
  if (this != &other)
  {
    FreeLarge(this->Memory, this->Bytes);
    this->Memory = std::exchange(other.Memory, nullptr);
    this->Bytes = std::exchange(other.Bytes, 0);
  }
  return *this;
}

} // namespace atp
