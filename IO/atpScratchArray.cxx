#include "atpScratchArray.h"

#include <cerrno>
#include <cstring>
#include <utility>
#include <sys/mman.h>

namespace atp
{

ScratchMapping::ScratchMapping(const std::string& directory)
  : File(directory)
{
}

ScratchMapping::ScratchMapping(ScratchMapping&& other) noexcept
  : File(std::move(other.File))
  , Mapping(std::exchange(other.Mapping, nullptr))
  , MappedBytes(std::exchange(other.MappedBytes, 0))
{
}

ScratchMapping& ScratchMapping::operator=(ScratchMapping&& other) noexcept
{
  if (this != &other)
  {
    this->Unmap();
    this->File = std::move(other.File);
    this->Mapping = std::exchange(other.Mapping, nullptr);
    this->MappedBytes = std::exchange(other.MappedBytes, 0);
  }
  return *this;
}

ScratchMapping::~ScratchMapping()
{
  this->Unmap();
}

void ScratchMapping::Unmap()
{
  if (this->Mapping)
  {
    ::munmap(this->Mapping, this->MappedBytes);
    this->Mapping = nullptr;
    this->MappedBytes = 0;
  }
}

void ScratchMapping::Grow(std::size_t bytes)
{
  if (bytes <= this->MappedBytes)
  {
    return;
  }
  this->File.Resize(bytes);
  this->Unmap();
  void* mapping =
    ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, this->File.Descriptor(), 0);
  if (mapping == MAP_FAILED)
  {
    throw std::runtime_error(std::string("cannot map a scratch array: ") + std::strerror(errno));
  }
  this->Mapping = mapping;
  this->MappedBytes = bytes;
}

} // namespace atp
