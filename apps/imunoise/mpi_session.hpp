#pragma once
// The ranks of a run under mpirun (fleet, dev/fit --mpi): the library's message-passing
// interface (imunoise/parallel/ranks.hpp) over MPI, so that the executable builds and runs
// without MPI. MPI is initialised only when a command needs it and the process was started by
// mpirun; a plain `imunoise ...` never touches MPI.
#include "imunoise/parallel/ranks.hpp"

namespace imunoise::cli::mpi {

/// In the executable without MPI: when started by mpirun, replaces this process (execv, same
/// arguments and environment, same pid for mpirun) by the MPI build next to it, so that
/// `mpirun imunoise ...` works while a plain run never loads Open MPI. Returns when there is
/// nothing to hand over (not under mpirun, or this is the MPI build); InputError when under
/// mpirun and the MPI build is absent or cannot be run.
void hand_over_to_mpi_build(char** argv);

/// This process's ranks: MPI's (initialised once, finalised at exit) when launched by
/// mpirun, one rank for a plain run. InputError when launched by mpirun but built without MPI
/// (every rank would otherwise do the whole job).
parallel::Ranks& start();

}  // namespace imunoise::cli::mpi
