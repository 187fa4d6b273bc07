// Fuzz target: the streaming mesh readers (PLY ASCII and binary, OBJ, STL ASCII and binary)
// through OpenTriangleSource, as `atp build` reads them. The first byte picks the format; every
// triangle is read. Any input must end in triangles or an InputError, never a crash, a hang or
// an allocation the file's size does not justify.
#include "FuzzInput.h"
#include "atpTriangleSource.h"

#include <cstddef>
#include <cstdint>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  static const char* const names[] = { "input.ply", "input.obj", "input.stl" };
  const std::string path = atp::fuzz::InputFile(names[data[0] % 3], data + 1, size - 1);
  try
  {
    const auto source = atp::OpenTriangleSource(path, atp::fuzz::ScratchDirectory());
    std::vector<atp::SoupTriangle> triangles(256);
    while (source->Read(triangles.data(), triangles.size()) > 0)
    {
    }
  }
  catch (const atp::InputError&)
  {
  }
  return 0;
}
