#include "mpi_session.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>

#include <unistd.h>

#include <fmt/core.h>

#include "imunoise/error.hpp"

#ifdef IMUNOISE_HAVE_MPI
#include <mpi.h>
#endif

namespace imunoise::cli::mpi {

bool launched_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

#ifdef IMUNOISE_HAVE_MPI

namespace {

bool g_started = false;
World g_world;

void finalize_at_exit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

constexpr std::size_t kPiece = std::size_t{1} << 30;

}  // namespace

bool available() { return true; }

void hand_over_to_mpi_build(char**) {}

World start() {
  if (g_started) return g_world;
  g_started = true;
  if (!launched_by_mpirun()) return g_world;
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    MPI_Init(nullptr, nullptr);
    std::atexit(finalize_at_exit);
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &g_world.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_world.size);
  return g_world;
}

double broadcast(double value) {
  if (g_world.size > 1) MPI_Bcast(&value, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return value;
}

bool all_ok(bool ok) {
  if (g_world.size == 1) return ok;
  int mine = ok ? 1 : 0;
  int all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return all == 1;
}

void send_bytes(int destination, int tag, const std::vector<std::uint8_t>& bytes) {
  std::uint64_t n = bytes.size();
  MPI_Send(&n, 1, MPI_UINT64_T, destination, tag, MPI_COMM_WORLD);
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    const auto len = static_cast<int>(std::min(kPiece, bytes.size() - at));
    MPI_Send(bytes.data() + at, len, MPI_BYTE, destination, tag, MPI_COMM_WORLD);
  }
}

std::vector<std::uint8_t> receive_bytes(int source, int tag, int* actual_source) {
  std::uint64_t n = 0;
  MPI_Status status;
  MPI_Recv(&n, 1, MPI_UINT64_T, source < 0 ? MPI_ANY_SOURCE : source, tag, MPI_COMM_WORLD, &status);
  if (actual_source != nullptr) *actual_source = status.MPI_SOURCE;
  std::vector<std::uint8_t> bytes(n);
  for (std::size_t at = 0; at < bytes.size(); at += kPiece) {
    const auto len = static_cast<int>(std::min<std::size_t>(kPiece, bytes.size() - at));
    MPI_Recv(bytes.data() + at, len, MPI_BYTE, status.MPI_SOURCE, tag, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
  }
  return bytes;
}

void abort_all(const std::string& message) {
  fmt::print(stderr, "imunoise: error: {}\n", message);
  std::fflush(stderr);
  if (g_world.size > 1) MPI_Abort(MPI_COMM_WORLD, 1);
  std::exit(1);
}

#else

namespace {
World g_world;
}  // namespace

bool available() { return false; }

namespace {

[[noreturn]] void refuse_without_mpi() {
  throw InputError("this imunoise was built without MPI (IMUNOISE_MPI=OFF or no Open MPI at "
                   "build time), so under mpirun every rank would do the whole job; fix: "
                   "rebuild with libopenmpi-dev installed, or run without mpirun");
}

}  // namespace

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

World start() {
  if (launched_by_mpirun()) refuse_without_mpi();
  return g_world;
}

double broadcast(double value) { return value; }
bool all_ok(bool ok) { return ok; }
void send_bytes(int, int, const std::vector<std::uint8_t>&) {
  throw InputError("MPI message without MPI");
}
std::vector<std::uint8_t> receive_bytes(int, int, int*) {
  throw InputError("MPI message without MPI");
}
void abort_all(const std::string& message) {
  fmt::print(stderr, "imunoise: error: {}\n", message);
  std::exit(1);
}

#endif

void tree_merge(const std::function<std::vector<std::uint8_t>()>& encode,
                const std::function<void(const std::vector<std::uint8_t>&)>& absorb) {
  constexpr int kTag = 17;
  for (int step = 1; step < g_world.size; step *= 2) {
    if (g_world.rank % (2 * step) == step) {
      send_bytes(g_world.rank - step, kTag, encode());
      return;
    }
    if (g_world.rank % (2 * step) == 0 && g_world.rank + step < g_world.size) {
      absorb(receive_bytes(g_world.rank + step, kTag));
    }
  }
}

}  // namespace imunoise::cli::mpi
