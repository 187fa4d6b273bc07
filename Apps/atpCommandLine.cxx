#include "atpCommandLine.h"

#include <charconv>
#include <iostream>
#include <sstream>

namespace atp
{

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

void CommandLine::AddPositional(const std::string& name, const std::string& help)
{
  PositionalHelp.emplace_back(name, help);
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
      if (i + 1 >= arguments.size())
      {
        throw UsageError("option " + a + " needs a value (" + o->ValueName + ")");
      }
      Values[o->Long] = arguments[++i];
      continue;
    }
    Positionals.push_back(a);
  }
  if (Positionals.size() != PositionalHelp.size())
  {
    std::ostringstream s;
    s << "expected " << PositionalHelp.size() << " argument(s)";
    for (const auto& p : PositionalHelp)
    {
      s << " " << p.first;
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
    s << " " << p.first;
  }
  s << " [options]\n\n" << Summary << "\n";
  if (!PositionalHelp.empty())
  {
    s << "\narguments:\n";
    for (const auto& p : PositionalHelp)
    {
      s << "  " << p.first << "\n      " << p.second << "\n";
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

}
