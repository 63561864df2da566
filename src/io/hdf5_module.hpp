#pragma once
// The interface between the library's HDF5 reader (hdf5_reader.cpp) and the module that links
// libhdf5 (src/plugins/hdf5, libimunoise_hdf5.so), which the reader loads with dlopen on the
// first HDF5 file: a process that reads no HDF5 never loads libhdf5 and what it pulls in. The
// module only asks libhdf5 and reports what it found; messages, units and timestamps stay in the
// library. Both sides are built together (same compiler and standard library), so C++ types
// cross the boundary; kVersion refuses a module left over from another build.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "imunoise/io/imu_containers.hpp"

namespace imunoise::io::hdf5_module {

inline constexpr int kVersion = 1;
inline constexpr const char* kEntryPoint = "imunoise_hdf5_module";
inline constexpr const char* kFileName = "libimunoise_hdf5.so";

/// What a path names in the file.
enum class Lookup { dataset, missing, not_a_dataset };

struct DatasetInfo {
  Lookup lookup = Lookup::missing;
  bool numeric = false;  ///< integer or float class
  bool integer = false;
  int rank = 0;
  std::vector<std::uint64_t> dims;
  std::optional<std::string> unit;  ///< string attribute "units" (or "unit")
};

struct Api {
  int version;
  /// Opens a file read-only; nullptr when it fails (`*not_hdf5`: it is no HDF5 file at all).
  void* (*open)(const char* path, bool* not_hdf5);
  void (*close)(void* file);
  DatasetInfo (*inspect)(void* file, const std::string& path);
  /// Every dataset in the file, for messages.
  std::vector<StreamInfo> (*list)(void* file);
  /// Reads the whole dataset converted by libhdf5 into `out` (as many values as inspect's dims).
  bool (*read_double)(void* file, const std::string& path, double* out);
  bool (*read_int64)(void* file, const std::string& path, std::int64_t* out);
};

/// The module's only exported symbol (kEntryPoint).
using EntryPoint = const Api* (*)();

/// Library side: the module, loaded once per process (hdf5_module_loader.cpp). Looked for at
/// $IMUNOISE_HDF5_MODULE when set (only there), else next to the program or Python module that
/// holds this code, in ../<libdir>/imunoise/ from there, next to /proc/self/exe, in the build
/// tree and in the install prefix. InputError naming `source`, the places tried and the fix when
/// it cannot be loaded.
const Api& load(const std::string& source);

}  // namespace imunoise::io::hdf5_module
