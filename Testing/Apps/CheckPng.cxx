// Checks a PNG the command line wrote: VTK's reader reads it whole, it has the expected size,
// and it is not blank (more than 1% of its pixels differ from the top-left one).
//   CheckPng FILE.png WIDTH HEIGHT
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

int main(int argc, char** argv)
{
  if (argc != 4)
  {
    std::fprintf(stderr, "usage: CheckPng FILE.png WIDTH HEIGHT\n");
    return 2;
  }
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(argv[1]))
  {
    std::printf("%s: not a PNG file\n", argv[1]);
    return 1;
  }
  reader->SetFileName(argv[1]);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int size[3];
  image->GetDimensions(size);
  if (size[0] != std::atoi(argv[2]) || size[1] != std::atoi(argv[3]) ||
    image->GetScalarType() != VTK_UNSIGNED_CHAR)
  {
    std::printf("%s: %dx%d (scalar type %d), expected %sx%s 8-bit\n", argv[1], size[0], size[1],
      image->GetScalarType(), argv[2], argv[3]);
    return 1;
  }
  const int components = image->GetNumberOfScalarComponents();
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  const long count = long(size[0]) * size[1];
  long differing = 0;
  for (long i = 0; i < count; ++i)
  {
    differing += std::memcmp(pixels + i * components, pixels, std::size_t(components)) != 0;
  }
  std::printf("%s: %dx%d, %.1f%% of the pixels differ from the corner\n", argv[1], size[0],
    size[1], 100.0 * double(differing) / double(count));
  return differing * 100 > count ? 0 : 1;
}
