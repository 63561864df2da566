// HDF5 through the C library (Debian libhdf5-dev). A dataset is 1-D (N samples, one channel
// named after the dataset) or 2-D (N x C: C channels "<name>[j]"); any integer or float type is
// read converted by the library to double (exact for every float32/float64 and integer up to
// 2^53). An optional time dataset holds N timestamps: integers are nanoseconds when they look
// like epoch ns (above 1e15) and seconds otherwise, floats are seconds; a string attribute
// "units" (or "unit") of s, ms, us or ns overrides. The same attribute on the data dataset
// gives the channels' unit.
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>

#include <cstdio>
#include "imunoise/error.hpp"
#include "imunoise/io/imu_containers.hpp"
#include "imunoise/io/timestamps.hpp"

namespace imunoise::io {
namespace {

// Owns an HDF5 identifier.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  [[nodiscard]] hid_t get() const { return id_; }
  [[nodiscard]] bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

struct Listing {
  std::vector<StreamInfo> datasets;
};

herr_t visit(hid_t root, const char* name, const H5O_info_t* info, void* data) {
  if (info->type != H5O_TYPE_DATASET) return 0;
  auto* listing = static_cast<Listing*>(data);
  Handle ds(H5Dopen2(root, name, H5P_DEFAULT), H5Dclose);
  if (!ds.ok()) return 0;
  Handle space(H5Dget_space(ds.get()), H5Sclose);
  Handle type(H5Dget_type(ds.get()), H5Tclose);
  hsize_t dims[8] = {};
  const int rank = space.ok() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  std::string shape;
  if (rank >= 0 && rank <= 8) {
    H5Sget_simple_extent_dims(space.get(), dims, nullptr);
    for (int i = 0; i < rank; ++i) shape += (i ? " x " : "") + std::to_string(dims[i]);
  }
  const H5T_class_t cls = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
  const std::string kind = cls == H5T_FLOAT ? "float" : cls == H5T_INTEGER ? "integer" : "non-numeric";
  listing->datasets.push_back({"/" + std::string(name), kind + " [" + shape + "]",
                               rank >= 1 ? static_cast<std::uint64_t>(dims[0]) : 1});
  return 0;
}

std::string list_datasets(hid_t file) {
  Listing listing;
  H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, visit, &listing, H5O_INFO_BASIC);
  return describe_streams(listing.datasets, "dataset");
}

// A string attribute "units" or "unit", if any.
std::optional<std::string> unit_attribute(hid_t object) {
  for (const char* name : {"units", "unit"}) {
    if (H5Aexists(object, name) <= 0) continue;
    Handle attr(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
    Handle type(H5Aget_type(attr.get()), H5Tclose);
    if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING) continue;
    if (H5Tis_variable_str(type.get()) > 0) {
      Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(mem.get(), H5T_VARIABLE);
      H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
      char* value = nullptr;
      if (H5Aread(attr.get(), mem.get(), &value) < 0 || value == nullptr) continue;
      std::string out(value);
      H5free_memory(value);
      return out;
    }
    const std::size_t size = H5Tget_size(type.get());
    if (size == 0 || size > 256) continue;
    std::string out(size, '\0');
    if (H5Aread(attr.get(), type.get(), out.data()) < 0) continue;
    out.resize(std::strlen(out.c_str()));
    return out;
  }
  return std::nullopt;
}

struct Dataset {
  std::vector<hsize_t> dims;
  bool integer = false;
  std::optional<std::string> unit;
};

Dataset open_dataset(hid_t file, const std::string& path, const std::string& source, const char* option,
                     Handle& out_ds) {
  if (path.empty()) {
    throw InputError(source + ": no " + std::string(option) + " given; fix: pass " + option +
                     " /path with one of the datasets the file holds:\n" + list_datasets(file));
  }
  // H5Lexists fails on a missing intermediate group; check each level.
  std::string prefix;
  std::size_t start = path.front() == '/' ? 1 : 0;
  while (start <= path.size()) {
    const auto slash = path.find('/', start);
    prefix = path.substr(0, slash);
    if (!prefix.empty() && prefix != "/" && H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) {
      throw InputError(source + ": no dataset " + path + "; fix: pass one the file holds:\n" + list_datasets(file));
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  new (&out_ds) Handle(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!out_ds.ok()) {
    throw InputError(source + ": " + path + " is not a dataset (a group?); fix: pass one the file holds:\n" + list_datasets(file));
  }
  Dataset d;
  Handle space(H5Dget_space(out_ds.get()), H5Sclose);
  Handle type(H5Dget_type(out_ds.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) {
    throw InputError(source + ": dataset " + path + " is not numeric (integer or float); fix: pass one the file holds:\n" +
                     list_datasets(file));
  }
  d.integer = cls == H5T_INTEGER;
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 1 || rank > 2) {
    throw InputError(source + ": dataset " + path + " has " + std::to_string(rank) +
                     " dimensions; fix: pass a 1-D (N) or 2-D (N x channels) dataset");
  }
  d.dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), d.dims.data(), nullptr);
  d.unit = unit_attribute(out_ds.get());
  return d;
}

}  // namespace

Recording read_hdf5(const std::filesystem::path& path, std::string_view dataset, std::string_view time_dataset) {
  const std::string source = path.string();
  // The library prints its error stack to stderr by default; errors are reported by us.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    throw InputError(source + ": not a readable HDF5 file (corrupt or truncated); fix: copy it again");
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok()) throw InputError(source + ": cannot open as HDF5 (corrupt or truncated); fix: copy it again");

  Handle ds(-1, H5Dclose);
  const std::string name(dataset);
  const Dataset d = open_dataset(file.get(), name, source, "--dataset", ds);
  const hsize_t n = d.dims[0];
  const hsize_t channels = d.dims.size() == 2 ? d.dims[1] : 1;
  if (n == 0 || channels == 0) throw InputError(source + ": dataset " + name + " is empty; fix: pass a dataset with samples");
  if (channels > 4096) {
    throw InputError(source + ": dataset " + name + " has " + std::to_string(channels) +
                     " columns; fix: store it as N x channels, samples along the first dimension (transpose it)");
  }
  std::vector<double> all(static_cast<std::size_t>(n * channels));
  if (H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()) < 0) {
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
  for (hsize_t j = 0; j < channels; ++j) {
    Channel c;
    c.name = channels == 1 ? base : base + "[" + std::to_string(j) + "]";
    c.unit = unit;
    c.values.resize(static_cast<std::size_t>(n));
    for (hsize_t i = 0; i < n; ++i) c.values[i] = all[i * channels + j];
    r.channels.push_back(std::move(c));
  }
  if (!time_dataset.empty()) {
    Handle ts(-1, H5Dclose);
    const std::string tname(time_dataset);
    const Dataset t = open_dataset(file.get(), tname, source, "--time-dataset", ts);
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
      if (H5Dread(ts.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) < 0) {
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
      if (H5Dread(ts.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) < 0) {
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
