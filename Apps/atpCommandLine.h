// A small option parser for the atp subcommands: --name VALUE, --flag, positional arguments,
// and a generated --help text, so every subcommand documents every option the same way.
#ifndef atpCommandLine_h
#define atpCommandLine_h

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace atp
{

/// A mistake in the command line: the message says which option and what is wrong.
class UsageError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// A number as %g prints it (for messages).
std::string FormatNumber(double value);

/// The extension of a file name, lowercased, with its dot (".ply"); empty when it has none.
/// Options naming files are told apart by it, as the builder's readers do.
std::string FileExtension(const std::string& path);

/// What makes a camera (eye, focal point, view up) unusable, checked where one is given.
enum class CameraFault
{
  None,
  TooFar,      ///< a coordinate beyond +-1e30: the camera's arithmetic squares distances
  NoDirection, ///< the eye is the focal point
  UpAlongView  ///< the view up is zero or along the view direction
};
CameraFault CheckCamera(const double eye[3], const double focalPoint[3], const double up[3]);

class CommandLine
{
public:
  CommandLine(std::string command, std::string summary);

  /// An option taking a value; `fallback` empty means the option has no default.
  void AddOption(const std::string& longName, const std::string& shortName,
    const std::string& valueName, const std::string& help, const std::string& fallback = "");
  void AddFlag(const std::string& longName, const std::string& help);
  /// A positional argument; optional ones come after the required ones.
  void AddPositional(const std::string& name, const std::string& help, bool optional = false);

  /// Parses arguments (after the subcommand). Returns false when --help was asked (the help
  /// is printed). Throws UsageError.
  bool Parse(const std::vector<std::string>& arguments);

  std::string Help() const;
  bool Has(const std::string& longName) const;
  std::string Get(const std::string& longName) const;
  /// The option's value as an integer in [low, high]; throws UsageError otherwise.
  long long GetInteger(const std::string& longName, long long low, long long high) const;
  /// The option's value as a real number in [low, high]; throws UsageError otherwise.
  double GetNumber(const std::string& longName, double low, double high) const;
  /// `count` comma-separated finite real numbers ("1,2.5,-3"); throws UsageError otherwise.
  std::vector<double> GetNumbers(const std::string& longName, std::size_t count) const;
  /// WIDTHxHEIGHT, each from 16 to 8192; throws UsageError otherwise.
  void GetSize(const std::string& longName, int& width, int& height) const;
  const std::string& Positional(std::size_t i) const { return Positionals.at(i); }
  std::size_t PositionalCount() const { return Positionals.size(); }

private:
  struct Option
  {
    std::string Long, Short, ValueName, Help, Fallback;
    bool IsFlag = false;
  };
  const Option* FindOption(const std::string& name) const;

  std::string Command, Summary;
  std::vector<Option> Options;
  struct PositionalArgument
  {
    std::string Name, Help;
    bool Optional = false;
  };
  std::vector<PositionalArgument> PositionalHelp;
  std::vector<std::string> Positionals;
  std::map<std::string, std::string> Values;
};

}

#endif
