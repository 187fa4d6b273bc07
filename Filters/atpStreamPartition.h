// Partitions a whole triangle stream with reading and partitioning overlapped: one thread
// parses the input while the caller's thread inserts, through a few recycled batches.
#ifndef atpStreamPartition_h
#define atpStreamPartition_h

#include "atpPartitioner.h"
#include "vtkATPFiltersModule.h"

#include <functional>
#include <memory>

namespace atp
{

/// Reads `source` to its end into a new Partitioner, which then applies the source's boundary
/// check to the leaves it reads. `progress(trianglesDone)` runs on the
/// calling thread after every batch; it may throw to cancel. Errors of the reader (InputError)
/// and of the partitioner (scratch disk full) reach the caller; the reader thread is always
/// joined first.
VTKATPFILTERS_EXPORT std::unique_ptr<Partitioner> PartitionStream(TriangleSource& source,
  const PartitionOptions& options, const std::function<void(std::uint64_t)>& progress);

}

#endif
