#include "atpModelCommands.h"

#include "atpCommandLine.h"
#include "atpModelBoundsCheck.h"
#include "atpModelFile.h"
#include "atpPatchCodec.h"
#include "atpProgressReport.h"
#include "atpTetra.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace atp
{
namespace
{
struct LevelFigures
{
  std::uint64_t Nodes = 0;
  std::uint64_t Triangles = 0;
  std::uint64_t Bytes = 0;
  double SaturatedError = 0;
};

std::map<int, LevelFigures> Levels(const ModelFile& model)
{
  std::map<int, LevelFigures> levels;
  for (std::size_t i = 0; i < model.NodeCount(); ++i)
  {
    const ModelNode& n = model.Node(i);
    LevelFigures& l = levels[TetId{ n.Tet }.Level()];
    ++l.Nodes;
    l.Triangles += n.TriangleCount;
    l.Bytes += n.PatchBytes;
    l.SaturatedError = std::max(l.SaturatedError, double(n.SaturatedError));
  }
  return levels;
}
/// `text` as a JSON string: quoted, with quotes, backslashes and control characters escaped,
/// and any byte that is not part of valid UTF-8 (file names are bytes) as U+FFFD.
std::string JsonString(const std::string& text)
{
  std::string json = "\"";
  for (std::size_t i = 0; i < text.size();)
  {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x80)
    {
      char escaped[8];
      if (c == '"' || c == '\\')
      {
        json += '\\';
        json += char(c);
      }
      else if (c < 0x20)
      {
        std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
        json += escaped;
      }
      else
      {
        json += char(c);
      }
      ++i;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, continuation bytes 10xxxxxx, no overlong
    // two-byte form.
    const std::size_t length = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k)
    {
      valid = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    }
    json += valid ? text.substr(i, length) : "\\ufffd";
    i += valid ? length : 1;
  }
  return json + "\"";
}

} // namespace

int InfoCommand(const std::vector<std::string>& arguments)
{
  CommandLine cl("info", "Describes a model: its input, options, size and levels.");
  cl.AddPositional("MODEL", "a .atp model");
  cl.AddFlag("json", "print one JSON object instead of text");
  if (!cl.Parse(arguments))
  {
    return 0;
  }
  const ModelFile model = ModelFile::Open(cl.Positional(0));
  const ModelHeader& h = model.Header();
  const std::map<int, LevelFigures> levels = Levels(model);
  const double perTriangle = double(h.FileBytes) / double(std::max<std::uint64_t>(1, h.InputTriangles));
  const bool colors = (h.Flags & ModelFlagColors) != 0;
  const char* cacheOrder = (h.Flags & ModelFlagFastCacheOrder) ? "fast" : "best";
  if (cl.Has("json"))
  {
    std::printf("{\"file\": %s, \"version\": %u, \"bytes\": %llu, \"nodes\": %llu, "
                "\"levels\": %u, \"input_triangles\": %llu, \"input_boundary_edges\": %llu, "
                "\"colors\": %s, \"stored_triangles\": %llu, \"bytes_per_input_triangle\": %.3f, "
                "\"leaf_capacity\": %u, \"patch_budget\": %u, \"cache_order\": \"%s\", "
                "\"error_scale\": %g, "
                "\"box_min\": [%.9g, %.9g, %.9g], \"box_max\": [%.9g, %.9g, %.9g], "
                "\"quantization_step\": %.9g, \"per_level\": [",
      JsonString(cl.Positional(0)).c_str(), h.Version, static_cast<unsigned long long>(h.FileBytes),
      static_cast<unsigned long long>(h.NodeCount), h.Depth + 1,
      static_cast<unsigned long long>(h.InputTriangles),
      static_cast<unsigned long long>(h.InputBoundaryEdges), colors ? "true" : "false",
      static_cast<unsigned long long>(h.StoredTriangles), perTriangle, h.LeafCapacity,
      h.PatchBudget, cacheOrder, double(h.ErrorScale), h.BoxMin[0], h.BoxMin[1], h.BoxMin[2],
      h.BoxMax[0], h.BoxMax[1], h.BoxMax[2], h.QuantizationStep);
    const char* separator = "";
    for (const auto& [level, l] : levels)
    {
      std::printf("%s{\"level\": %d, \"nodes\": %llu, \"triangles\": %llu, \"bytes\": %llu, "
                  "\"saturated_error\": %.6g}",
        separator, level, static_cast<unsigned long long>(l.Nodes),
        static_cast<unsigned long long>(l.Triangles), static_cast<unsigned long long>(l.Bytes),
        l.SaturatedError);
      separator = ", ";
    }
    std::printf("]}\n");
    return 0;
  }
  std::printf("%s: ATP model version %u, %.1f MiB\n", cl.Positional(0).c_str(), h.Version,
    double(h.FileBytes) / (1 << 20));
  std::printf("input: %s triangles, %llu boundary edges, %s, box (%g %g %g) - (%g %g %g)\n",
    FormatCount(double(h.InputTriangles)).c_str(),
    static_cast<unsigned long long>(h.InputBoundaryEdges),
    colors ? "vertex colors" : "no colors", h.BoxMin[0], h.BoxMin[1], h.BoxMin[2],
    h.BoxMax[0], h.BoxMax[1], h.BoxMax[2]);
  std::printf("model: %llu nodes, %u levels, %s triangles stored over all levels, %.2f "
              "bytes/input triangle\n",
    static_cast<unsigned long long>(h.NodeCount), h.Depth + 1,
    FormatCount(double(h.StoredTriangles)).c_str(), perTriangle);
  std::printf("options: leaf capacity %u, patch budget %u, %s cache order, error scale %g, "
              "quantization step %g\n",
    h.LeafCapacity, h.PatchBudget, cacheOrder, double(h.ErrorScale), h.QuantizationStep);
  std::printf("%6s %10s %12s %12s %16s\n", "level", "nodes", "triangles", "bytes", "saturated error");
  for (const auto& [level, l] : levels)
  {
    std::printf("%6d %10llu %12llu %12llu %16.6g\n", level, static_cast<unsigned long long>(l.Nodes),
      static_cast<unsigned long long>(l.Triangles), static_cast<unsigned long long>(l.Bytes),
      l.SaturatedError);
  }
  return 0;
}

int VerifyCommand(const std::vector<std::string>& arguments)
{
  CommandLine cl("verify",
    "Checks a model completely: header, node structure and invariants, the checksum of every\n"
    "section and patch, that every patch decodes to what its node says (triangle and vertex\n"
    "counts, a sphere holding its vertices, a cone holding its face normals), and the\n"
    "saturation (equal over each diamond, spheres nested down the tree).\n"
    "Exit code 0: valid; 1: not.");
  cl.AddPositional("MODEL", "a .atp model");
  if (!cl.Parse(arguments))
  {
    return 0;
  }
  const std::string& path = cl.Positional(0);
  ModelFile model = [&]() {
    try
    {
      return ModelFile::Open(path);
    }
    catch (const ModelError& e)
    {
      throw std::runtime_error(std::string(e.what()) + "\n" + path + ": INVALID");
    }
  }();
  std::vector<std::string> problems = model.Verify();
  const auto note = [&](const std::vector<std::string>& found) {
    for (const std::string& problem : found)
    {
      problems.push_back(path + ": " + problem);
    }
  };
  if (problems.empty())
  {
    try
    {
      note(SaturationProblems(model, CutIndex(model)));
    }
    catch (const ModelError& e)
    {
      problems.push_back(e.what());
    }
    PatchMesh patch;
    for (std::size_t i = 0; i < model.NodeCount(); ++i)
    {
      try
      {
        model.DecodePatch(i, patch);
        note(PatchProblems(model.Header(), i, model.Node(i), patch));
      }
      catch (const PatchFormatError& e)
      {
        problems.push_back(path + ": node " + std::to_string(i) + ": " + e.what());
      }
      catch (const ModelError& e)
      {
        problems.push_back(e.what());
      }
    }
  }
  for (const std::string& p : problems)
  {
    std::fprintf(stderr, "%s\n", p.c_str());
  }
  if (!problems.empty())
  {
    std::printf("%s: INVALID (%zu problems)\n", path.c_str(), problems.size());
    return 1;
  }
  std::printf("%s: valid (%zu nodes, every checksum and patch checked)\n", path.c_str(),
    model.NodeCount());
  return 0;
}

} // namespace atp
