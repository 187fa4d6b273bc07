#include "atpModelWriter.h"

#include "atpChecksum.h"

#include <xxhash.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <new>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace atp
{
namespace
{
// Patches are gathered into large writes; a bigger patch is written on its own.
constexpr std::size_t BufferBytes = std::size_t(8) << 20;
/// Nodes written at a time: 1 MiB.
constexpr std::size_t NodeBufferCount = 8192;

std::uint64_t AlignUp(std::uint64_t value, std::uint64_t alignment)
{
  return (value + alignment - 1) / alignment * alignment;
}

std::string DirectoryOf(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return ".";
  }
  return slash == 0 ? "/" : path.substr(0, slash);
}

// The process umask without umask()'s set-and-restore, which races with other threads creating
// files. Linux reports it in /proc/self/status; elsewhere assume the usual 022.
mode_t CurrentUmask()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.compare(0, 6, "Umask:") == 0)
    {
      return mode_t(std::strtoul(line.c_str() + 6, nullptr, 8));
    }
  }
  return 022;
}
} // namespace

struct ModelWriter::SectionHash
{
  XXH3_state_t* State = XXH3_createState();
  ~SectionHash() { XXH3_freeState(State); }
};

std::uint64_t ModelWriter::NodeSectionOffset()
{
  return AlignUp(sizeof(ModelHeader), 64);
}

std::uint64_t ModelWriter::PatchSectionOffset(std::uint64_t nodeCount)
{
  return AlignUp(NodeSectionOffset() + nodeCount * sizeof(ModelNode), 64);
}

ModelWriter::ModelWriter(const std::string& path, std::uint64_t nodeCount)
  : Path(path)
  , NodeCount(nodeCount)
  , PatchStart(PatchSectionOffset(nodeCount))
  , PatchHash(new SectionHash)
  , NodeHash(new SectionHash)
{
  for (SectionHash* hash : { PatchHash.get(), NodeHash.get() })
  {
    if (!hash->State || XXH3_64bits_reset(hash->State) != XXH_OK)
    {
      throw std::bad_alloc();
    }
  }
  // A file without a name until Commit: a build killed at any point (even by SIGKILL) leaves
  // nothing behind. File systems without O_TMPFILE get a named temporary file instead.
  Fd = ::open(DirectoryOf(path).c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0666);
  if (Fd < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL))
  {
    Fd = CreateNamedTemporary();
    // mkstemp makes the file private (0600); the model should get a new file's usual mode.
    if (::fchmod(Fd, 0666 & ~CurrentUmask()) != 0)
    {
      Fail(errno);
    }
  }
  if (Fd < 0)
  {
    Fail(errno);
  }
  Buffer.reserve(BufferBytes);
  NodeBuffer.reserve(NodeBufferCount);
}

int ModelWriter::CreateNamedTemporary()
{
  std::string name = Path + ".partial-XXXXXX";
  const int fd = ::mkstemp(name.data());
  if (fd < 0)
  {
    Fail(errno);
  }
  TempPath = name;
  return fd;
}

void ModelWriter::NameAnonymousFile()
{
  // linkat through /proc needs no privilege (AT_EMPTY_PATH does); a name left by another
  // writer is skipped.
  const std::string source = "/proc/self/fd/" + std::to_string(Fd);
  for (unsigned attempt = 0;; ++attempt)
  {
    const std::string name =
      Path + ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(attempt);
    if (::linkat(AT_FDCWD, source.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0)
    {
      TempPath = name;
      return;
    }
    if (errno != EEXIST)
    {
      Fail(errno);
    }
  }
}

ModelWriter::~ModelWriter()
{
  if (Fd >= 0)
  {
    ::close(Fd);
  }
  if (!Finished && !TempPath.empty())
  {
    ::unlink(TempPath.c_str());
  }
}

void ModelWriter::Fail(int err)
{
  if (Fd >= 0)
  {
    ::close(Fd);
    Fd = -1;
  }
  if (!TempPath.empty())
  {
    ::unlink(TempPath.c_str());
  }
  Finished = true;
  throw std::runtime_error("cannot write " + Path + ": " + std::strerror(err));
}

void ModelWriter::RequireOpen() const
{
  if (Finished)
  {
    throw std::logic_error("ModelWriter for " + Path + " is already committed or failed");
  }
}

void ModelWriter::WriteAt(std::uint64_t offset, const void* data, std::size_t bytes)
{
  const char* p = static_cast<const char*>(data);
  while (bytes > 0)
  {
    const ssize_t n = ::pwrite(Fd, p, bytes, off_t(offset));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n < 0)
    {
      Fail(errno);
    }
    if (n == 0)
    {
      Fail(ENOSPC);
    }
    p += n;
    offset += std::uint64_t(n);
    bytes -= std::size_t(n);
  }
}

void ModelWriter::Flush()
{
  if (!Buffer.empty())
  {
    WriteAt(PatchStart + WrittenEnd, Buffer.data(), Buffer.size());
    WrittenEnd += Buffer.size();
    Buffer.clear();
  }
  if (!NodeBuffer.empty())
  {
    const std::uint64_t first = NodesAdded - NodeBuffer.size();
    WriteAt(NodeSectionOffset() + first * sizeof(ModelNode), NodeBuffer.data(),
      NodeBuffer.size() * sizeof(ModelNode));
    NodeBuffer.clear();
  }
}

void ModelWriter::Add(ModelNode node, const void* data, std::size_t bytes)
{
  RequireOpen();
  if (NodesAdded >= NodeCount)
  {
    throw std::logic_error("ModelWriter for " + Path + ": more than the " +
      std::to_string(NodeCount) + " nodes");
  }
  if (bytes > UINT32_MAX)
  {
    throw std::length_error("ModelWriter for " + Path + ": a patch of " + std::to_string(bytes) +
      " bytes exceeds the format's 4 GiB limit");
  }
  node.PatchOffset = PatchEnd;
  node.PatchBytes = std::uint32_t(bytes);
  node.PatchChecksum = Checksum(data, bytes);
  std::fill(std::begin(node.Reserved), std::end(node.Reserved), std::uint8_t(0));
  XXH3_64bits_update(NodeHash->State, &node, sizeof(node));
  if (NodeBuffer.size() == NodeBufferCount)
  {
    Flush();
  }
  NodeBuffer.push_back(node);
  ++NodesAdded;

  // Zero padding keeps every patch start aligned for the decoders; the section checksum covers
  // it, so the padding is part of the hashed stream.
  static const std::uint8_t zeros[PatchAlignment] = {};
  const std::size_t padding = std::size_t(AlignUp(bytes, PatchAlignment) - bytes);
  XXH3_64bits_update(PatchHash->State, data, bytes);
  XXH3_64bits_update(PatchHash->State, zeros, padding);
  if (Buffer.size() + bytes + padding > BufferBytes)
  {
    Flush();
  }
  if (bytes + padding > BufferBytes)
  {
    WriteAt(PatchStart + WrittenEnd, data, bytes);
    WriteAt(PatchStart + WrittenEnd + bytes, zeros, padding);
    WrittenEnd += bytes + padding;
  }
  else
  {
    const std::uint8_t* p = static_cast<const std::uint8_t*>(data);
    Buffer.insert(Buffer.end(), p, p + bytes);
    Buffer.insert(Buffer.end(), zeros, zeros + padding);
  }
  PatchEnd += bytes + padding;
}

void ModelWriter::Commit(ModelHeader header)
{
  RequireOpen();
  if (NodesAdded != NodeCount)
  {
    throw std::logic_error("ModelWriter for " + Path + ": " + std::to_string(NodeCount) +
      " nodes expected, got " + std::to_string(NodesAdded));
  }
  Flush();
  const std::uint64_t nodeBytes = NodeCount * sizeof(ModelNode);

  std::memcpy(header.Magic, ModelMagic, sizeof(header.Magic));
  header.Version = ModelVersion;
  header.ByteOrder = ModelByteOrderMark;
  header.HeaderBytes = sizeof(ModelHeader);
  header.NodeBytes = sizeof(ModelNode);
  header.NodeCount = NodeCount;
  header.NodeSectionOffset = NodeSectionOffset();
  header.NodeSectionBytes = nodeBytes;
  header.PatchSectionOffset = PatchStart;
  header.PatchSectionBytes = PatchEnd;
  header.FileBytes = PatchStart + PatchEnd;
  header.NodeSectionChecksum = XXH3_64bits_digest(NodeHash->State);
  header.PatchSectionChecksum = XXH3_64bits_digest(PatchHash->State);
  std::fill(std::begin(header.Reserved), std::end(header.Reserved), std::uint8_t(0));
  header.HeaderChecksum = Checksum(&header, offsetof(ModelHeader, HeaderChecksum));

  // Gaps between sections were never written and read back as zeros; ftruncate sets the exact
  // length even when the last patches are empty.
  WriteAt(0, &header, sizeof(header));
  if (::ftruncate(Fd, off_t(header.FileBytes)) != 0 || ::fsync(Fd) != 0)
  {
    Fail(errno);
  }
  // Named only now, complete and on disk, and renamed over the target at once.
  if (TempPath.empty())
  {
    NameAnonymousFile();
  }
  const int fd = Fd;
  Fd = -1;
  if (::close(fd) != 0)
  {
    Fail(errno);
  }
  if (::rename(TempPath.c_str(), Path.c_str()) != 0)
  {
    Fail(errno);
  }
  Finished = true;

  // The rename is durable only once the directory is on disk. The model is already in place
  // here, so a failure is reported but nothing is removed.
  const std::string directory = DirectoryOf(Path);
  const int dirFd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dirFd < 0)
  {
    throw std::runtime_error("cannot write " + Path + ": " + std::strerror(errno));
  }
  // Some file systems cannot sync a directory (EINVAL); they have nothing to flush.
  const int synced = ::fsync(dirFd);
  const int err = errno;
  ::close(dirFd);
  if (synced != 0 && err != EINVAL)
  {
    throw std::runtime_error("cannot write " + Path + ": " + std::strerror(err));
  }
}

} // namespace atp
