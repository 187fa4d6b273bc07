// Closes a POSIX file descriptor when it goes out of scope, however the scope is left.
#ifndef atpFileDescriptor_h
#define atpFileDescriptor_h

#include <unistd.h>

namespace atp
{

struct FileDescriptor
{
  int Fd;
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor()
  {
    if (Fd >= 0)
    {
      ::close(Fd);
    }
  }
};

} // namespace atp

#endif
