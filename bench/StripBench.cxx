// atp-bench-strips MODEL.atp [--level N] [--frames F] [--rounds R] [--size WxH]: indexed triangle
// lists against triangle strips, drawn from the same vertex buffer. The construction issue asks
// for strips only if they measure faster; this measures it on whatever draws here (a GPU
// through X or EGL, or Mesa's llvmpipe under xvfb-run).
//
// Every patch of the cut at level N (default: the finest, the whole input) is decoded and laid
// out as vtkATPMapper lays it out (atpRenderPatch.h: 20-byte vertices, 16-bit indices where they
// fit), then drawn whole, frame after frame, with glMultiDrawElementsBaseVertex like the mapper:
// - lists: the triangles as stored (meshopt_optimizeVertexCache's order, the default build);
// - strips of that order: meshopt_stripify on it, primitive restart between strips;
// - strips of the strip order: meshopt_optimizeVertexCacheStrip first, as meshoptimizer
//   recommends for strips (the order a model would have to store to draw strips).
// The shading is a plain headlight, the same for all three: what differs is index processing
// and vertex reuse, not pixels (the pictures are compared). Variants alternate round by round,
// so a drifting clock favors none. Also printed: indices and vertex cache misses per triangle
// (a 16-entry FIFO), the index bytes meshoptimizer's codecs would store, and what making the
// strips costs per triangle on the CPU (a decode thread's work if strips were made on load).
#include "atpModelFile.h"
#include "atpCut.h"
#include "atpOffscreenWindow.h"
#include "atpRenderPatch.h"

#include "vtkRenderWindow.h"
#include "vtk_glew.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

constexpr unsigned CacheSize = 16; // the FIFO meshopt_analyzeVertexCache models
constexpr std::uint32_t Restart32 = ~0u;
constexpr std::uint32_t Restart16 = 0xFFFF;

struct Options
{
  std::string Model;
  int Level = 64;
  int Frames = 10;
  int Rounds = 3;
  int Width = 800;
  int Height = 600;
};

Options Parse(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        throw std::invalid_argument(arg + " needs a value");
      }
      return argv[++i];
    };
    if (arg == "--level")
    {
      o.Level = std::stoi(value());
    }
    else if (arg == "--frames")
    {
      o.Frames = std::max(1, std::stoi(value()));
    }
    else if (arg == "--rounds")
    {
      o.Rounds = std::max(1, std::stoi(value()));
    }
    else if (arg == "--size")
    {
      const std::string size = value();
      if (std::sscanf(size.c_str(), "%dx%d", &o.Width, &o.Height) != 2 || o.Width < 1 || o.Height < 1)
      {
        throw std::invalid_argument("--size wants WIDTHxHEIGHT, not " + size);
      }
    }
    else if (o.Model.empty() && arg[0] != '-')
    {
      o.Model = arg;
    }
    else
    {
      throw std::invalid_argument("unknown argument " + arg);
    }
  }
  if (o.Model.empty())
  {
    throw std::invalid_argument(
      "usage: atp-bench-strips MODEL.atp [--level N] [--frames F] [--rounds R] [--size WxH]");
  }
  return o;
}

/// One way of drawing every patch: its index buffer and, per index type (16 and 32 bits), the
/// arguments of one glMultiDrawElementsBaseVertex.
struct Variant
{
  Variant(const char* name, GLenum mode)
    : Name(name)
    , Mode(mode)
  {
  }
  const char* Name;
  GLenum Mode;
  std::vector<std::uint8_t> Indices;
  struct DrawList
  {
    std::vector<GLsizei> Counts;
    std::vector<const void*> Offsets;
    std::vector<GLint> BaseVertices;
  } Draws[2];
  std::size_t IndexCount = 0;
  double Misses = 0;      // vertex cache misses, summed over patches
  std::size_t Coded = 0;  // bytes of meshoptimizer's index codec
  double MakeSeconds = 0; // CPU time to make this variant's indices from the stored ones
  std::vector<double> FrameSeconds, GpuSeconds;
  std::vector<std::uint8_t> Picture;
  GLuint Buffer = 0;

  /// Appends a patch's indices (restart values included) as 16-bit when `shortIndices`.
  void Add(const std::vector<std::uint32_t>& indices, bool shortIndices, GLint baseVertex)
  {
    const std::size_t bytes = shortIndices ? 2 : 4;
    // Offsets must be multiples of the index size: 32-bit runs start 4-byte aligned.
    Indices.resize((Indices.size() + bytes - 1) / bytes * bytes);
    const std::size_t offset = Indices.size();
    Indices.resize(offset + bytes * indices.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
    {
      if (shortIndices)
      {
        const std::uint16_t s = indices[i] == Restart32 ? std::uint16_t(Restart16) : std::uint16_t(indices[i]);
        std::memcpy(&Indices[offset + 2 * i], &s, 2);
      }
      else
      {
        std::memcpy(&Indices[offset + 4 * i], &indices[i], 4);
      }
    }
    DrawList& list = Draws[shortIndices ? 0 : 1];
    list.Counts.push_back(GLsizei(indices.size()));
    list.Offsets.push_back(reinterpret_cast<const void*>(offset));
    list.BaseVertices.push_back(baseVertex);
    IndexCount += indices.size();
  }
};

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values.empty() ? 0 : values[values.size() / 2];
}

GLuint Compile(GLenum type, const char* source)
{
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok)
  {
    char log[2048] = "";
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    throw std::runtime_error(std::string("shader: ") + log);
  }
  return shader;
}

const char* const VertexShader = R"(#version 150
in vec3 position;
in vec4 normal;
uniform mat4 modelViewProjection;
uniform mat3 normalToView;
out vec3 normalView;
void main()
{
  normalView = normalToView * normal.xyz;
  gl_Position = modelViewProjection * vec4(position, 1.0);
}
)";

const char* const FragmentShader = R"(#version 150
in vec3 normalView;
out vec4 color;
void main()
{
  float lit = abs(normalize(normalView).z);
  color = vec4(vec3(0.1 + 0.85 * lit), 1.0);
}
)";

/// Column-major view and projection looking at the box from a corner direction, the box filling
/// the view.
void Camera(const atp::ModelHeader& header, double aspect, float mvp[16], float normal[9])
{
  double center[3], radius = 0;
  for (int a = 0; a < 3; ++a)
  {
    center[a] = (header.BoxMin[a] + header.BoxMax[a]) / 2;
    radius += (header.BoxMax[a] - header.BoxMin[a]) * (header.BoxMax[a] - header.BoxMin[a]) / 4;
  }
  radius = std::max(std::sqrt(radius), 1e-30);
  const double fovY = 30 * M_PI / 180;
  const double distance = radius / std::sin(fovY / 2);
  const double toEye[3] = { 0.48, 0.36, 0.8 }; // unit length
  // Rows of the view rotation: right, up, back (toward the eye).
  double back[3] = { toEye[0], toEye[1], toEye[2] };
  double right[3] = { back[2], 0, -back[0] }; // (0, 1, 0) x back
  const double rn = std::sqrt(right[0] * right[0] + right[2] * right[2]);
  right[0] /= rn;
  right[2] /= rn;
  const double up[3] = { back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
    back[0] * right[1] - back[1] * right[0] };
  const double* rows[3] = { right, up, back };
  double view[4][4] = {}; // [row][column]
  for (int r = 0; r < 3; ++r)
  {
    double t = 0;
    for (int c = 0; c < 3; ++c)
    {
      view[r][c] = rows[r][c];
      t -= rows[r][c] * (center[c] + toEye[c] * distance);
    }
    view[r][3] = t;
  }
  view[3][3] = 1;
  const double nearZ = std::max(distance - radius, distance * 1e-3), farZ = distance + radius;
  const double f = 1 / std::tan(fovY / 2);
  double projection[4][4] = {};
  projection[0][0] = f / aspect;
  projection[1][1] = f;
  projection[2][2] = (farZ + nearZ) / (nearZ - farZ);
  projection[2][3] = 2 * farZ * nearZ / (nearZ - farZ);
  projection[3][2] = -1;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      double sum = 0;
      for (int k = 0; k < 4; ++k)
      {
        sum += projection[r][k] * view[k][c];
      }
      mvp[4 * c + r] = float(sum);
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      normal[3 * c + r] = float(view[r][c]); // a rotation: its own inverse transpose
    }
  }
}

int Run(const Options& o)
{
  const atp::ModelFile model = atp::ModelFile::Open(o.Model);
  const std::vector<std::uint32_t> nodes = atp::SelectLevel(model, o.Level);

  constexpr std::size_t Stride = atp::RenderPatchStride(false);
  std::vector<std::uint8_t> vertices;
  Variant variants[3] = { Variant("lists (stored order)", GL_TRIANGLES),
    Variant("strips of the stored order", GL_TRIANGLE_STRIP),
    Variant("strips of the strip order", GL_TRIANGLE_STRIP) };
  atp::PatchMesh mesh;
  std::size_t triangles = 0, vertexCount = 0;
  std::vector<std::uint32_t> reordered, strip, unstripped;
  std::vector<unsigned char> coded;
  for (const std::uint32_t node : nodes)
  {
    model.DecodePatch(node, mesh);
    if (mesh.Indices.empty())
    {
      continue;
    }
    mesh.Colors.clear(); // one layout for every model: colors are not what is measured
    const atp::RenderPatch patch = atp::MakeRenderPatch(mesh, node);
    const GLint base = GLint(vertices.size() / Stride);
    vertices.insert(vertices.end(), patch.Vertices.begin(), patch.Vertices.end());
    const std::size_t n = mesh.Indices.size(), v = mesh.VertexCount();
    triangles += n / 3;
    vertexCount += v;

    Variant& lists = variants[0];
    lists.Add(mesh.Indices, patch.ShortIndices, base);
    lists.Misses += meshopt_analyzeVertexCache(mesh.Indices.data(), n, v, CacheSize, 0, 0).acmr * (n / 3);
    coded.resize(meshopt_encodeIndexBufferBound(n, v));
    lists.Coded += meshopt_encodeIndexBuffer(coded.data(), coded.size(), mesh.Indices.data(), n);

    for (int k = 1; k < 3; ++k)
    {
      Variant& strips = variants[k];
      const Clock::time_point start = Clock::now();
      const std::uint32_t* order = mesh.Indices.data();
      if (k == 2)
      {
        reordered.resize(n);
        meshopt_optimizeVertexCacheStrip(reordered.data(), mesh.Indices.data(), n, v);
        order = reordered.data();
      }
      strip.resize(meshopt_stripifyBound(n));
      strip.resize(meshopt_stripify(strip.data(), order, n, v, Restart32));
      strips.MakeSeconds += Seconds(start);
      // 0xFFFF restarts 16-bit strips, so a patch using vertex 65535 needs 32-bit indices.
      strips.Add(strip, v < Restart16, base);
      unstripped.resize(meshopt_unstripifyBound(strip.size()));
      unstripped.resize(meshopt_unstripify(unstripped.data(), strip.data(), strip.size(), Restart32));
      strips.Misses += meshopt_analyzeVertexCache(unstripped.data(), unstripped.size(), v, CacheSize, 0, 0).acmr * (n / 3);
      coded.resize(meshopt_encodeIndexSequenceBound(strip.size(), v));
      strips.Coded += meshopt_encodeIndexSequence(coded.data(), coded.size(), strip.data(), strip.size());
    }
  }
  if (triangles == 0)
  {
    throw std::runtime_error("level " + std::to_string(o.Level) + " of the model holds no triangle");
  }

  vtkSmartPointer<vtkRenderWindow> window = atp::NewOffscreenWindow(o.Width, o.Height);
  window->Render(); // makes the context
  window->MakeCurrent();
  std::printf("renderer: %s\n", atp::RendererName(window).c_str());

  // Our own framebuffer: the same for every variant, whatever VTK keeps bound.
  GLuint framebuffer = 0, renderbuffers[2] = { 0, 0 };
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glGenRenderbuffers(2, renderbuffers);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[0]);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, o.Width, o.Height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers[0]);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[1]);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, o.Width, o.Height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
  {
    throw std::runtime_error("the framebuffer is incomplete");
  }
  glViewport(0, 0, o.Width, o.Height);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);

  const GLuint program = glCreateProgram();
  glAttachShader(program, Compile(GL_VERTEX_SHADER, VertexShader));
  glAttachShader(program, Compile(GL_FRAGMENT_SHADER, FragmentShader));
  glBindAttribLocation(program, 0, "position");
  glBindAttribLocation(program, 1, "normal");
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (!linked)
  {
    throw std::runtime_error("the shaders did not link");
  }
  glUseProgram(program);
  float mvp[16], normal[9];
  Camera(model.Header(), double(o.Width) / o.Height, mvp, normal);
  glUniformMatrix4fv(glGetUniformLocation(program, "modelViewProjection"), 1, GL_FALSE, mvp);
  glUniformMatrix3fv(glGetUniformLocation(program, "normalToView"), 1, GL_FALSE, normal);

  GLuint layout = 0, vertexBuffer = 0;
  glGenVertexArrays(1, &layout);
  glBindVertexArray(layout);
  glGenBuffers(1, &vertexBuffer);
  glBindBuffer(GL_ARRAY_BUFFER, vertexBuffer);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size()), vertices.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, GLsizei(Stride),
    reinterpret_cast<const void*>(atp::RenderPatchPositionOffset));
  glVertexAttribPointer(1, 4, GL_SHORT, GL_TRUE, GLsizei(Stride),
    reinterpret_cast<const void*>(atp::RenderPatchNormalOffset));
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  for (Variant& variant : variants)
  {
    glGenBuffers(1, &variant.Buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, variant.Buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(variant.Indices.size()), variant.Indices.data(), GL_STATIC_DRAW);
  }
  GLuint query = 0;
  glGenQueries(1, &query);

  const GLenum types[2] = { GL_UNSIGNED_SHORT, GL_UNSIGNED_INT };
  const GLuint restarts[2] = { Restart16, Restart32 };
  const auto draw = [&](Variant& variant) {
    glClearColor(0.2f, 0.3f, 0.4f, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, variant.Buffer);
    const bool strips = variant.Mode == GL_TRIANGLE_STRIP;
    if (strips)
    {
      glEnable(GL_PRIMITIVE_RESTART);
    }
    for (int type = 0; type < 2; ++type)
    {
      Variant::DrawList& list = variant.Draws[type];
      if (list.Counts.empty())
      {
        continue;
      }
      if (strips)
      {
        glPrimitiveRestartIndex(restarts[type]);
      }
      glMultiDrawElementsBaseVertex(variant.Mode, list.Counts.data(), types[type],
        const_cast<void**>(list.Offsets.data()), GLsizei(list.Counts.size()), list.BaseVertices.data());
    }
    glDisable(GL_PRIMITIVE_RESTART);
  };

  for (Variant& variant : variants) // warm up, and the picture each one draws
  {
    draw(variant);
    glFinish();
    variant.Picture.resize(std::size_t(4) * o.Width * o.Height);
    glReadPixels(0, 0, o.Width, o.Height, GL_RGBA, GL_UNSIGNED_BYTE, variant.Picture.data());
  }
  for (int round = 0; round < o.Rounds; ++round)
  {
    for (Variant& variant : variants)
    {
      for (int frame = 0; frame < o.Frames; ++frame)
      {
        const Clock::time_point start = Clock::now();
        glBeginQuery(GL_TIME_ELAPSED, query);
        draw(variant);
        glEndQuery(GL_TIME_ELAPSED);
        glFinish();
        variant.FrameSeconds.push_back(Seconds(start));
        GLuint64 nanoseconds = 0;
        glGetQueryObjectui64v(query, GL_QUERY_RESULT, &nanoseconds);
        variant.GpuSeconds.push_back(nanoseconds * 1e-9);
      }
    }
  }
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
  {
    throw std::runtime_error("OpenGL error " + std::to_string(error));
  }

  std::printf("model: %s, level %d: %zu patches, %zu triangles, %zu vertices; %dx%d, %d rounds of %d "
              "frames each\n",
    o.Model.c_str(), o.Level, nodes.size(), triangles, vertexCount, o.Width, o.Height, o.Rounds,
    o.Frames);
  std::printf("%-28s %8s %9s %9s %10s %9s %9s %9s %8s %9s\n", "", "indices", "index", "misses",
    "coded", "make", "frame", "GPU", "Mtri/s", "pixels");
  std::printf("%-28s %8s %9s %9s %10s %9s %9s %9s %8s %9s\n", "", "/tri", "MiB", "/tri (16)",
    "bytes/tri", "ns/tri", "ms", "ms", "", "differ");
  for (const Variant& variant : variants)
  {
    std::size_t differ = 0;
    for (std::size_t p = 0; p < variant.Picture.size(); p += 4)
    {
      differ += std::memcmp(&variant.Picture[p], &variants[0].Picture[p], 4) != 0;
    }
    const double frame = Median(variant.FrameSeconds);
    std::printf("%-28s %8.2f %9.1f %9.3f %10.2f %9.1f %9.2f %9.2f %8.1f %9zu\n", variant.Name,
      double(variant.IndexCount) / triangles, variant.Indices.size() / 1048576.0,
      variant.Misses / triangles, double(variant.Coded) / triangles,
      variant.MakeSeconds * 1e9 / triangles, frame * 1e3, Median(variant.GpuSeconds) * 1e3,
      triangles / frame / 1e6, differ);
  }
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  try
  {
    return Run(Parse(argc, argv));
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "atp-bench-strips: %s\n", e.what());
    return 1;
  }
}
