#include "mpi_session.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <unistd.h>

#include "imunoise/error.hpp"

#ifdef IMUNOISE_HAVE_MPI
#include <mpi.h>
#endif

namespace imunoise::cli::mpi {
namespace {

bool launched_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

#ifdef IMUNOISE_HAVE_MPI

void finalize_at_exit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

// Messages longer than an int can count go in pieces.
constexpr std::size_t kPiece = std::size_t{1} << 30;

class MpiRanks final : public parallel::Ranks {
 public:
  MpiRanks() {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      MPI_Init(nullptr, nullptr);
      std::atexit(finalize_at_exit);
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  double broadcast(double value) override {
    MPI_Bcast(&value, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    return value;
  }

  bool all_ok(bool ok) override {
    int mine = ok ? 1 : 0;
    int all = 0;
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all == 1;
  }

  void send(int destination, int tag, const parallel::Bytes& bytes) override {
    std::uint64_t n = bytes.size();
    MPI_Send(&n, 1, MPI_UINT64_T, destination, tag, MPI_COMM_WORLD);
    for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
      const auto len = static_cast<int>(std::min(kPiece, bytes.size() - at));
      MPI_Send(bytes.data() + at, len, MPI_BYTE, destination, tag, MPI_COMM_WORLD);
    }
  }

  parallel::Bytes receive(int source, int tag, int* actual_source) override {
    std::uint64_t n = 0;
    MPI_Status status;
    MPI_Recv(&n, 1, MPI_UINT64_T, source < 0 ? MPI_ANY_SOURCE : source, tag, MPI_COMM_WORLD, &status);
    if (actual_source != nullptr) *actual_source = status.MPI_SOURCE;
    parallel::Bytes bytes(n);
    for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
      const auto len = static_cast<int>(std::min<std::size_t>(kPiece, bytes.size() - at));
      MPI_Recv(bytes.data() + at, len, MPI_BYTE, status.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
    return bytes;
  }

 private:
  int rank_ = 0;
  int size_ = 1;
};

#else

[[noreturn]] void refuse_without_mpi() {
  throw InputError("this imunoise was built without MPI (IMUNOISE_MPI=OFF or no Open MPI at "
                   "build time), so under mpirun every rank would do the whole job; fix: "
                   "rebuild with libopenmpi-dev installed, or run without mpirun");
}

#endif

}  // namespace

#ifdef IMUNOISE_HAVE_MPI

void hand_over_to_mpi_build(char**) {}

parallel::Ranks& start() {
  static parallel::SingleRank single;
  if (!launched_by_mpirun()) return single;
  static MpiRanks world;
  return world;
}

#else

void hand_over_to_mpi_build(char** argv) {
  if (!launched_by_mpirun()) return;
#ifdef IMUNOISE_MPI_EXECUTABLE
  // /proc/self/exe, not argv[0]: mpirun may have found us through PATH.
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path sibling = self.parent_path() / IMUNOISE_MPI_EXECUTABLE;
  if (!ec) ::execv(sibling.c_str(), argv);
  const std::string why = ec ? "cannot read /proc/self/exe: " + ec.message() : std::strerror(errno);
  throw InputError("started by mpirun, but the MPI build " + sibling.string() + " cannot be run (" +
                   why + "); fix: install imunoise-mpi next to imunoise (it is built with "
                   "IMUNOISE_MPI=ON, target imunoise_cli_mpi), or run without mpirun");
#else
  (void)argv;
  refuse_without_mpi();
#endif
}

parallel::Ranks& start() {
  if (launched_by_mpirun()) refuse_without_mpi();
  static parallel::SingleRank single;
  return single;
}

#endif

}  // namespace imunoise::cli::mpi
