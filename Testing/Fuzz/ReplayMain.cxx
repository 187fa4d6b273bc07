// The main of a fuzz target outside a fuzzing build: runs the target once on every file named
// (directories: every file inside), so the seed corpus and the crashers kept as regression inputs
// run in CTest with any compiler. Options libFuzzer would take (-runs=0 ...) are ignored.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace
{
void Run(const std::filesystem::path& file)
{
  std::ifstream in(file, std::ios::binary);
  const std::vector<std::uint8_t> bytes(
    (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::printf("%s (%zu bytes)\n", file.c_str(), bytes.size());
  std::fflush(stdout); // a crash should name its input
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
}
} // namespace

int main(int argc, char** argv)
{
  std::size_t inputs = 0;
  for (int i = 1; i < argc; ++i)
  {
    const std::filesystem::path path = argv[i];
    if (argv[i][0] == '-')
    {
      continue;
    }
    if (std::filesystem::is_directory(path))
    {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(path))
      {
        if (entry.is_regular_file())
        {
          Run(entry.path());
          ++inputs;
        }
      }
    }
    else
    {
      Run(path);
      ++inputs;
    }
  }
  if (inputs == 0)
  {
    std::fprintf(stderr, "no inputs: a replay must run something\n");
    return 1;
  }
  std::printf("%zu inputs ran\n", inputs);
  return 0;
}
