// This process's memory, for the summaries of the commands.
#ifndef atpProcessMemory_h
#define atpProcessMemory_h

namespace atp
{

/// Resident memory now, in MiB.
double ResidentMiB();
/// The largest resident memory so far, in MiB.
double PeakResidentMiB();
/// Resident memory now by kind, in MiB: anonymous (the heap, and what graphics drivers keep
/// in main memory) and mapped from files (libraries, and pages of memory-mapped models).
struct ResidentKinds
{
  double AnonymousMiB = 0, FileMiB = 0;
};
ResidentKinds ResidentByKind();

}

#endif
