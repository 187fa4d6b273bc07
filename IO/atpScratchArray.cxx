#include "atpScratchArray.h"

#include <cerrno>
#include <cstring>
#include <sys/mman.h>

namespace atp
{

ScratchMapping::ScratchMapping(const std::string& directory)
  : File(directory)
{
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
