// An output file written beside its final name and renamed into place only when complete: a
// failed or interrupted command (SIGINT, SIGTERM, SIGQUIT, SIGHUP, SIGPIPE, ...: any signal but
// SIGKILL that ends it by default and is no crash) leaves no half-written file, and an existing
// one untouched.
#ifndef atpPendingFile_h
#define atpPendingFile_h

#include <stdexcept>
#include <string>
#include <vector>

namespace atp
{

/// Removes the partial files of every PendingFile not yet committed. Async-signal-safe: for a
/// handler that ends the process without unwinding.
void RemovePendingFiles();

class PendingFile
{
public:
  /// Creates the partial file at once, so an unwritable place is reported before any long
  /// work (as is any other OutputPathProblem; `inputs` are the files the command reads).
  /// `what` names the content for messages ("mesh", "plot"). Throws std::runtime_error
  /// "PATH: cannot write the WHAT: reason".
  PendingFile(std::string path, std::string what, const std::vector<std::string>& inputs = {});
  /// Removes the partial file unless committed.
  ~PendingFile();

  const std::string& Path() const { return FinalPath; }
  /// Where to write: beside Path() and ending with its extension (VTK's PLY writer appends
  /// .ply to names without it).
  const std::string& PartialPath() const { return Partial; }
  /// The error to throw when writing failed: "PATH: cannot write the WHAT" and the reason.
  std::runtime_error Failure(const std::string& reason) const;
  /// Renames the partial file into place; throws Failure() when that fails.
  void Commit();

  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

private:
  std::string FinalPath, What, Partial;
  int Slot = -1; ///< where a signal handler finds the partial file to remove it
  bool Committed = false;
};

}

#endif
