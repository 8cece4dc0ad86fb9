// A sweep's runs over MPI ranks (ARCHITECTURE.md, "Beyond one machine"), for `mpirun -n N fretwear sweep ...` and
// `srun fretwear sweep ...`. Rank 0 owns the sweep's folder and tables; it hands out run indices one at a time as
// ranks become free (runs differ in cost by orders of magnitude, so a fixed split would leave ranks idle) and runs
// runs itself on a second thread meanwhile; every rank writes the folders of its runs into rank 0's staging folder,
// which all ranks must see (one machine, or a shared file system on a cluster). Only the program links MPI: the
// engine library and the tests built on it do not.
#pragma once

#include <memory>

#include "engine/sweep.hpp"

namespace fretwear {

class MpiSweep : public SweepDispatch {
 public:
  ~MpiSweep() override = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // After a failure in rank 0 past the point where the ranks part ways: the other ranks are ended with it
  // (MPI_Abort, with `code`) instead of waiting for work that will not come.
  virtual void abandon(int code) = 0;
};

// MPI for a sweep, when an MPI launcher started this process (its environment says so): MPI started, ended when the
// result is destroyed (once every rank is done). Null when no launcher started it: the sweep runs on threads, and
// MPI is never touched. Throws InputError when a launcher started several processes but this fretwear was built
// without MPI (each would run the whole sweep).
std::unique_ptr<MpiSweep> start_mpi_if_launched(int jobs);

}  // namespace fretwear
