// HDF5 through the C library (Debian libhdf5-dev), which only the module libimunoise_hdf5.so
// links (hdf5_module.hpp); this file turns what the module reports into a Recording. A dataset
// is 1-D (N samples, one channel named after the dataset) or 2-D (N x C: C channels
// "<name>[j]"); any integer or float type is read converted by the library to double (exact for
// every float32/float64 and integer up to 2^53). An optional time dataset holds N timestamps:
// integers are nanoseconds when they look like epoch ns (above 1e15) and seconds otherwise,
// floats are seconds; a string attribute "units" (or "unit") of s, ms, us or ns overrides. The
// same attribute on the data dataset gives the channels' unit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "hdf5_module.hpp"
#include "imunoise/error.hpp"
#include "imunoise/io/imu_containers.hpp"
#include "imunoise/io/timestamps.hpp"

namespace imunoise::io {
namespace {

namespace h5 = hdf5_module;

// An open file of the module, closed on scope exit.
class File {
 public:
  File(const h5::Api& api, const std::string& source) : api_(api) {
    bool not_hdf5 = false;
    file_ = api_.open(source.c_str(), &not_hdf5);
    if (not_hdf5) {
      throw InputError(source + ": not a readable HDF5 file (corrupt or truncated); fix: copy it again");
    }
    if (file_ == nullptr) throw InputError(source + ": cannot open as HDF5 (corrupt or truncated); fix: copy it again");
  }
  ~File() { api_.close(file_); }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
  [[nodiscard]] const h5::Api& api() const { return api_; }
  [[nodiscard]] void* get() const { return file_; }

 private:
  const h5::Api& api_;
  void* file_ = nullptr;
};

std::string list_datasets(const File& file) {
  return describe_streams(file.api().list(file.get()), "dataset");
}

struct Dataset {
  std::vector<std::uint64_t> dims;
  bool integer = false;
  std::optional<std::string> unit;
};

Dataset open_dataset(const File& file, const std::string& path, const std::string& source, const char* option) {
  if (path.empty()) {
    throw InputError(source + ": no " + std::string(option) + " given; fix: pass " + option +
                     " /path with one of the datasets the file holds:\n" + list_datasets(file));
  }
  const h5::DatasetInfo info = file.api().inspect(file.get(), path);
  if (info.lookup == h5::Lookup::missing) {
    throw InputError(source + ": no dataset " + path + "; fix: pass one the file holds:\n" + list_datasets(file));
  }
  if (info.lookup == h5::Lookup::not_a_dataset) {
    throw InputError(source + ": " + path + " is not a dataset (a group?); fix: pass one the file holds:\n" + list_datasets(file));
  }
  if (!info.numeric) {
    throw InputError(source + ": dataset " + path + " is not numeric (integer or float); fix: pass one the file holds:\n" +
                     list_datasets(file));
  }
  if (info.rank < 1 || info.rank > 2) {
    throw InputError(source + ": dataset " + path + " has " + std::to_string(info.rank) +
                     " dimensions; fix: pass a 1-D (N) or 2-D (N x channels) dataset");
  }
  return Dataset{info.dims, info.integer, info.unit};
}

}  // namespace

Recording read_hdf5(const std::filesystem::path& path, std::string_view dataset, std::string_view time_dataset) {
  const std::string source = path.string();
  const File file(h5::load(source), source);
  const std::string name(dataset);
  const Dataset d = open_dataset(file, name, source, "--dataset");
  const std::uint64_t n = d.dims[0];
  const std::uint64_t channels = d.dims.size() == 2 ? d.dims[1] : 1;
  if (n == 0 || channels == 0) throw InputError(source + ": dataset " + name + " is empty; fix: pass a dataset with samples");
  if (channels > 4096) {
    throw InputError(source + ": dataset " + name + " has " + std::to_string(channels) +
                     " columns; fix: store it as N x channels, samples along the first dimension (transpose it)");
  }
  std::vector<double> all(static_cast<std::size_t>(n * channels));
  if (!file.api().read_double(file.get(), name, all.data())) {
    throw InputError(source + ": cannot read dataset " + name + " (corrupt or truncated file); fix: copy it again");
  }
  Recording r;
  r.source = source;
  r.format = RecordingFormat::hdf5;
  r.stream = name;
  std::optional<Unit> unit;
  if (d.unit && !d.unit->empty()) {
    try {
      unit = parse_unit(*d.unit);
    } catch (const InputError&) {
      throw InputError(source + ": dataset " + name + " has units attribute '" + *d.unit +
                       "', not a unit imunoise knows; fix: correct the attribute");
    }
  }
  const std::string base = name.substr(name.rfind('/') == std::string::npos ? 0 : name.rfind('/') + 1);
  for (std::uint64_t j = 0; j < channels; ++j) {
    Channel c;
    c.name = channels == 1 ? base : base + "[" + std::to_string(j) + "]";
    c.unit = unit;
    c.values.resize(static_cast<std::size_t>(n));
    for (std::uint64_t i = 0; i < n; ++i) c.values[i] = all[i * channels + j];
    r.channels.push_back(std::move(c));
  }
  if (!time_dataset.empty()) {
    const std::string tname(time_dataset);
    const Dataset t = open_dataset(file, tname, source, "--time-dataset");
    if (t.dims.size() != 1 || t.dims[0] != n) {
      throw InputError(source + ": time dataset " + tname + " must be 1-D with " + std::to_string(n) +
                       " values; fix: pass the timestamps of " + name);
    }
    std::optional<Unit> tunit;
    if (t.unit) {
      tunit = parse_unit(*t.unit);
      if (tunit->quantity != Quantity::time) {
        throw InputError(source + ": time dataset " + tname + " has units '" + *t.unit + "', not a time unit; fix: set it to s, ms, us or ns");
      }
    }
    if (t.integer) {
      std::vector<std::int64_t> raw(static_cast<std::size_t>(n));
      if (!file.api().read_int64(file.get(), tname, raw.data())) {
        throw InputError(source + ": cannot read time dataset " + tname + "; fix: copy the file again");
      }
      const bool ns = tunit ? tunit->name == "ns" : std::llabs(raw[0]) > 1'000'000'000'000'000LL;
      const Unit u = tunit ? *tunit : parse_unit(ns ? "ns" : "s");
      std::vector<SplitTime> split(raw.size());
      for (std::size_t i = 0; i < raw.size(); ++i) split[i] = SplitTime{raw[i], 0.0, true};
      r.time_s = relative_seconds(split, u.to_si);
      r.time_origin = std::to_string(raw[0]) + " " + u.name;
    } else {
      std::vector<double> raw(static_cast<std::size_t>(n));
      if (!file.api().read_double(file.get(), tname, raw.data())) {
        throw InputError(source + ": cannot read time dataset " + tname + "; fix: copy the file again");
      }
      const double to_s = tunit ? tunit->to_si : 1.0;
      r.time_s.resize(raw.size());
      for (std::size_t i = 0; i < raw.size(); ++i) {
        if (!std::isfinite(raw[i])) {
          throw InputError(source + ": time dataset " + tname + " row " + std::to_string(i) + " is not finite; fix: repair the timestamps");
        }
        r.time_s[i] = (raw[i] - raw[0]) * to_s;
      }
      char origin[40];
      std::snprintf(origin, sizeof origin, "%.17g", raw[0]);
      r.time_origin = std::string(origin) + " " + (tunit ? tunit->name : "s");
    }
  }
  return r;
}

}  // namespace imunoise::io
