#include "FuzzInput.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace atp
{
namespace fuzz
{

std::string ScratchDirectory()
{
  static const std::string directory = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string name = std::string(tmp && *tmp ? tmp : "/tmp") + "/atp-fuzz-XXXXXX";
    if (!::mkdtemp(name.data()))
    {
      std::perror("atp fuzz: cannot create a directory for inputs");
      std::abort();
    }
    // Removed at exit: the inputs are worth nothing once the run ends.
    static const std::string removal = name;
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(removal, ignored);
    });
    return name;
  }();
  return directory;
}

std::string InputFile(const std::string& name, const std::uint8_t* bytes, std::size_t size)
{
  const std::string path = ScratchDirectory() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes), std::streamsize(size));
  out.close();
  if (!out)
  {
    std::perror(("atp fuzz: cannot write " + path).c_str());
    std::abort();
  }
  return path;
}

} // namespace fuzz
} // namespace atp
