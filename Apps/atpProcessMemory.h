// This process's memory, for the summaries of the commands.
#ifndef atpProcessMemory_h
#define atpProcessMemory_h

namespace atp
{

/// Resident memory now, in MiB.
double ResidentMiB();
/// The largest resident memory so far, in MiB.
double PeakResidentMiB();

}

#endif
