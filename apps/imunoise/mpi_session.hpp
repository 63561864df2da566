#pragma once
// The few MPI operations the commands use (fleet, dev/fit --mpi), behind one small interface so
// that the executable builds and runs without MPI. MPI is initialised only when a command needs
// it and the process was started by mpirun; a plain `imunoise ...` never touches MPI.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace imunoise::cli::mpi {

/// True when this process was started by mpirun/mpiexec (Open MPI or PMIx environment).
bool launched_by_mpirun();

/// True when the executable was built with MPI (IMUNOISE_MPI).
bool available();

/// In the executable without MPI: when started by mpirun, replaces this process (execv, same
/// arguments and environment, same pid for mpirun) by the MPI build next to it, so that
/// `mpirun imunoise ...` works while a plain run never loads Open MPI. Returns when there is
/// nothing to hand over (not under mpirun, or this is the MPI build); InputError when under
/// mpirun and the MPI build is absent or cannot be run.
void hand_over_to_mpi_build(char** argv);

/// Initialises MPI when launched by mpirun (once; finalised at exit) and returns this
/// process's rank and the number of ranks; {0, 1} for a plain run. InputError when launched by
/// mpirun but built without MPI (every rank would otherwise do the whole job).
struct World {
  int rank = 0;
  int size = 1;
};
World start();

/// Rank 0's value on every rank.
double broadcast(double value);

/// True on every rank when `ok` is true on every rank (a collective error check: a rank that
/// failed has printed its message; all ranks then leave together instead of hanging).
bool all_ok(bool ok);

/// Point-to-point byte messages (any length; sent in pieces below 2^31 bytes); source -1 is any.
void send_bytes(int destination, int tag, const std::vector<std::uint8_t>& bytes);
std::vector<std::uint8_t> receive_bytes(int source, int tag, int* actual_source = nullptr);

/// Binary-tree reduction: at level s, rank r (r % 2s == 0) receives the image of rank r + s
/// (the records that follow its own) and hands it to absorb(); rank r % 2s == s sends
/// encode() to rank r - s and leaves. log2(P) levels; rank 0 ends with everything absorbed.
void tree_merge(const std::function<std::vector<std::uint8_t>()>& encode,
                const std::function<void(const std::vector<std::uint8_t>&)>& absorb);

/// Ends every rank with exit code 1 after printing `message` (MPI_Abort when MPI is running).
[[noreturn]] void abort_all(const std::string& message);

}  // namespace imunoise::cli::mpi
