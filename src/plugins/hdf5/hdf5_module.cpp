// libimunoise_hdf5.so: the only code that calls the HDF5 C library (Debian libhdf5-dev). Loaded
// by src/io/hdf5_reader.cpp on the first HDF5 file (interface: src/io/hdf5_module.hpp). It
// reports what it finds and throws nothing; the reader turns that into data and messages.
#include <hdf5.h>

#include <cstring>

#include "hdf5_module.hpp"

namespace imunoise::io::hdf5_module {
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

hid_t id_of(void* file) { return static_cast<hid_t>(reinterpret_cast<std::intptr_t>(file)); }

herr_t visit(hid_t root, const char* name, const H5O_info_t* info, void* data) {
  if (info->type != H5O_TYPE_DATASET) return 0;
  auto* listing = static_cast<std::vector<StreamInfo>*>(data);
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
  listing->push_back({"/" + std::string(name), kind + " [" + shape + "]",
                      rank >= 1 ? static_cast<std::uint64_t>(dims[0]) : 1});
  return 0;
}

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

// H5Lexists fails on a missing intermediate group: each level is checked.
bool path_exists(hid_t file, const std::string& path) {
  std::size_t start = !path.empty() && path.front() == '/' ? 1 : 0;
  while (start <= path.size()) {
    const auto slash = path.find('/', start);
    const std::string prefix = path.substr(0, slash);
    if (!prefix.empty() && prefix != "/" && H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return true;
}

void* open_file(const char* path, bool* not_hdf5) {
  // The library prints its error stack to stderr by default; the reader reports errors.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  *not_hdf5 = H5Fis_hdf5(path) <= 0;
  if (*not_hdf5) return nullptr;
  const hid_t id = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) return nullptr;
  return reinterpret_cast<void*>(static_cast<std::intptr_t>(id));
}

void close_file(void* file) { H5Fclose(id_of(file)); }

DatasetInfo inspect(void* file, const std::string& path) {
  DatasetInfo info;
  if (!path_exists(id_of(file), path)) return info;
  Handle ds(H5Dopen2(id_of(file), path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.ok()) {
    info.lookup = Lookup::not_a_dataset;
    return info;
  }
  info.lookup = Lookup::dataset;
  Handle space(H5Dget_space(ds.get()), H5Sclose);
  Handle type(H5Dget_type(ds.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  info.numeric = cls == H5T_FLOAT || cls == H5T_INTEGER;
  info.integer = cls == H5T_INTEGER;
  info.rank = H5Sget_simple_extent_ndims(space.get());
  if (info.rank >= 1 && info.rank <= 8) {
    std::vector<hsize_t> dims(static_cast<std::size_t>(info.rank));
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    info.dims.assign(dims.begin(), dims.end());
  }
  info.unit = unit_attribute(ds.get());
  return info;
}

std::vector<StreamInfo> list(void* file) {
  std::vector<StreamInfo> listing;
  H5Ovisit2(id_of(file), H5_INDEX_NAME, H5_ITER_INC, visit, &listing, H5O_INFO_BASIC);
  return listing;
}

bool read_as(void* file, const std::string& path, hid_t memory_type, void* out) {
  Handle ds(H5Dopen2(id_of(file), path.c_str(), H5P_DEFAULT), H5Dclose);
  return ds.ok() && H5Dread(ds.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) >= 0;
}

bool read_double(void* file, const std::string& path, double* out) {
  return read_as(file, path, H5T_NATIVE_DOUBLE, out);
}

bool read_int64(void* file, const std::string& path, std::int64_t* out) {
  return read_as(file, path, H5T_NATIVE_INT64, out);
}

const Api kApi{kVersion, open_file, close_file, inspect, list, read_double, read_int64};

}  // namespace
}  // namespace imunoise::io::hdf5_module

extern "C" __attribute__((visibility("default"))) const imunoise::io::hdf5_module::Api* imunoise_hdf5_module() {
  return &imunoise::io::hdf5_module::kApi;
}
