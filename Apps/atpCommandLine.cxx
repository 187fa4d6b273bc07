#include "atpCommandLine.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace atp
{

std::string FileExtension(const std::string& path)
{
  const std::size_t dot = path.rfind('.');
  const std::size_t slash = path.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return {};
  }
  std::string extension = path.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

CameraFault CheckCamera(const double eye[3], const double focalPoint[3], const double up[3])
{
  constexpr double Farthest = 1e30;
  for (int a = 0; a < 3; ++a)
  {
    if (!(std::abs(eye[a]) <= Farthest) || !(std::abs(focalPoint[a]) <= Farthest))
    {
      return CameraFault::TooFar;
    }
  }
  const double direction[3] = { focalPoint[0] - eye[0], focalPoint[1] - eye[1], focalPoint[2] - eye[2] };
  if (direction[0] == 0 && direction[1] == 0 && direction[2] == 0)
  {
    return CameraFault::NoDirection;
  }
  const double across[3] = { up[1] * direction[2] - up[2] * direction[1],
    up[2] * direction[0] - up[0] * direction[2], up[0] * direction[1] - up[1] * direction[0] };
  const auto length = [](const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); };
  return length(across) > 1e-9 * length(up) * length(direction) ? CameraFault::None : CameraFault::UpAlongView;
}

CommandLine::CommandLine(std::string command, std::string summary)
  : Command(std::move(command))
  , Summary(std::move(summary))
{
}

void CommandLine::AddOption(const std::string& longName, const std::string& shortName,
  const std::string& valueName, const std::string& help, const std::string& fallback)
{
  Options.push_back({ longName, shortName, valueName, help, fallback, false });
}

void CommandLine::AddFlag(const std::string& longName, const std::string& help)
{
  Options.push_back({ longName, "", "", help, "", true });
}

void CommandLine::AddPositional(const std::string& name, const std::string& help, bool optional)
{
  PositionalHelp.push_back({ name, help, optional });
}

const CommandLine::Option* CommandLine::FindOption(const std::string& name) const
{
  for (const Option& o : Options)
  {
    if (name == "--" + o.Long || (!o.Short.empty() && name == "-" + o.Short))
    {
      return &o;
    }
  }
  return nullptr;
}

bool CommandLine::Parse(const std::vector<std::string>& arguments)
{
  for (std::size_t i = 0; i < arguments.size(); ++i)
  {
    const std::string& a = arguments[i];
    if (a == "--help" || a == "-h")
    {
      std::cout << Help();
      return false;
    }
    if (a.size() > 1 && a[0] == '-')
    {
      const Option* o = FindOption(a);
      if (!o)
      {
        throw UsageError("unknown option " + a + " (see atp " + Command + " --help)");
      }
      if (o->IsFlag)
      {
        Values[o->Long] = "1";
        continue;
      }
      if (i + 1 >= arguments.size() || arguments[i + 1].empty())
      {
        throw UsageError("option " + a + " needs a value (" + o->ValueName + ")");
      }
      Values[o->Long] = arguments[++i];
      continue;
    }
    Positionals.push_back(a);
  }
  std::size_t required = 0;
  for (const auto& p : PositionalHelp)
  {
    required += p.Optional ? 0 : 1;
  }
  if (Positionals.size() < required || Positionals.size() > PositionalHelp.size())
  {
    std::ostringstream s;
    s << "expected ";
    if (required != PositionalHelp.size())
    {
      s << "from " << required << " to ";
    }
    s << PositionalHelp.size() << " argument(s)";
    for (const auto& p : PositionalHelp)
    {
      s << " " << (p.Optional ? "[" + p.Name + "]" : p.Name);
    }
    s << ", got " << Positionals.size() << " (see atp " << Command << " --help)";
    throw UsageError(s.str());
  }
  return true;
}

std::string CommandLine::Help() const
{
  std::ostringstream s;
  s << "usage: atp " << Command;
  for (const auto& p : PositionalHelp)
  {
    s << " " << (p.Optional ? "[" + p.Name + "]" : p.Name);
  }
  s << " [options]\n\n" << Summary << "\n";
  if (!PositionalHelp.empty())
  {
    s << "\narguments:\n";
    for (const auto& p : PositionalHelp)
    {
      s << "  " << p.Name << "\n      " << p.Help << "\n";
    }
  }
  s << "\noptions:\n";
  for (const Option& o : Options)
  {
    s << "  " << (o.Short.empty() ? "" : "-" + o.Short + ", ") << "--" << o.Long
      << (o.IsFlag ? "" : " " + o.ValueName) << "\n      " << o.Help;
    if (!o.Fallback.empty())
    {
      s << " (default: " << o.Fallback << ")";
    }
    s << "\n";
  }
  s << "  -h, --help\n      show this help\n";
  return s.str();
}

bool CommandLine::Has(const std::string& longName) const
{
  return Values.count(longName) > 0;
}

std::string CommandLine::Get(const std::string& longName) const
{
  const auto found = Values.find(longName);
  if (found != Values.end())
  {
    return found->second;
  }
  for (const Option& o : Options)
  {
    if (o.Long == longName)
    {
      return o.Fallback;
    }
  }
  return {};
}

long long CommandLine::GetInteger(const std::string& longName, long long low, long long high) const
{
  const std::string text = Get(longName);
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < low || value > high)
  {
    throw UsageError("--" + longName + " must be a whole number from " + std::to_string(low) +
      " to " + std::to_string(high) + ", got '" + text + "'");
  }
  return value;
}

std::string FormatNumber(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

namespace
{
/// The whole of `text` as a finite number, or false.
bool ParseNumber(const std::string& text, double& value)
{
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && std::isfinite(value);
}
} // namespace

double CommandLine::GetNumber(const std::string& longName, double low, double high) const
{
  const std::string text = Get(longName);
  double value = 0;
  if (!ParseNumber(text, value) || value < low || value > high)
  {
    throw UsageError("--" + longName + " must be a number from " + FormatNumber(low) + " to " +
      FormatNumber(high) + ", got '" + text + "'");
  }
  return value;
}

std::vector<double> CommandLine::GetNumbers(const std::string& longName, std::size_t count) const
{
  const std::string text = Get(longName);
  std::vector<double> values;
  std::size_t start = 0;
  for (;;)
  {
    const std::size_t comma = text.find(',', start);
    double value = 0;
    if (!ParseNumber(text.substr(start, comma - start), value))
    {
      break;
    }
    values.push_back(value);
    if (comma == std::string::npos)
    {
      break;
    }
    start = comma + 1;
  }
  if (values.size() != count || std::count(text.begin(), text.end(), ',') != std::ptrdiff_t(count - 1))
  {
    throw UsageError("--" + longName + " must be " + std::to_string(count) +
      " comma-separated numbers, got '" + text + "'");
  }
  return values;
}

void CommandLine::GetSize(const std::string& longName, int& width, int& height) const
{
  const std::string text = Get(longName);
  const char* end = text.data() + text.size();
  const auto w = std::from_chars(text.data(), end, width);
  const bool haveX = w.ec == std::errc() && w.ptr != end && *w.ptr == 'x';
  const auto h = haveX ? std::from_chars(w.ptr + 1, end, height) : w;
  if (!haveX || h.ec != std::errc() || h.ptr != end || width < 16 || height < 16 ||
    width > 8192 || height > 8192)
  {
    throw UsageError("--" + longName + " must be WIDTHxHEIGHT with each from 16 to 8192, got '" +
      text + "'");
  }
}

}
