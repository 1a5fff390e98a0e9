#include "engine/store/h5.h"

#include <algorithm>
#include <cstring>
#include <regex>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::store::h5 {

namespace {

// HDF5 prints every failure to stderr by default; the store reports failures itself, with the
// file's name, so the automatic printing is switched off (per thread in a thread-safe build).
void SilenceAutomaticErrorPrinting() {
  thread_local bool silenced = false;
  if (!silenced) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    silenced = true;
  }
}

herr_t CollectMessage(unsigned /*n*/, const H5E_error2_t* error, void* data) {
  auto* messages = static_cast<std::vector<std::string>*>(data);
  if (error->desc != nullptr && error->desc[0] != '\0') messages->emplace_back(error->desc);
  return 0;
}

hid_t MemoryType(ElementType type) {
  switch (type) {
    case ElementType::kFloat32:
      return H5T_NATIVE_FLOAT;
    case ElementType::kFloat64:
      return H5T_NATIVE_DOUBLE;
    case ElementType::kUInt8:
      return H5T_NATIVE_UINT8;
    case ElementType::kInt64:
      return H5T_NATIVE_INT64;
  }
  return H5T_NATIVE_FLOAT;
}

// Little-endian file types, the same on every machine (h5py writes these too).
hid_t FileType(ElementType type) {
  switch (type) {
    case ElementType::kFloat32:
      return H5T_IEEE_F32LE;
    case ElementType::kFloat64:
      return H5T_IEEE_F64LE;
    case ElementType::kUInt8:
      return H5T_STD_U8LE;
    case ElementType::kInt64:
      return H5T_STD_I64LE;
  }
  return H5T_IEEE_F32LE;
}

Handle VariableLengthString() {
  Handle type(H5Tcopy(H5T_C_S1));
  H5Tset_size(type.id(), H5T_VARIABLE);
  H5Tset_cset(type.id(), H5T_CSET_UTF8);
  return type;
}

Handle OpenDataset(const File& file, hid_t location, const std::string& name) {
  SilenceAutomaticErrorPrinting();
  if (!Exists(location, name)) Fail(file.path(), "missing dataset '" + name + "'");
  Handle dataset(H5Dopen2(location, name.c_str(), H5P_DEFAULT));
  if (!dataset.valid()) Fail(file.path(), "cannot open dataset '" + name + "'");
  return dataset;
}

Handle OpenAttribute(const File& file, hid_t location, const std::string& name) {
  SilenceAutomaticErrorPrinting();
  if (H5Aexists(location, name.c_str()) <= 0) Fail(file.path(), "missing attribute '" + name + "'");
  Handle attribute(H5Aopen(location, name.c_str(), H5P_DEFAULT));
  if (!attribute.valid()) Fail(file.path(), "cannot open attribute '" + name + "'");
  return attribute;
}

// What a read error of a checksummed dataset says.
std::string DamagedDataset(const std::string& name) {
  return "dataset '" + name +
         "' is damaged (its data does not match its checksum, or the file is truncated)";
}

// Chunks of a checksummed array hold at most this many bytes (whole rows, at least one).
constexpr hsize_t kChunkBytes = 1 << 20;

// Whether a dataset's chunks carry Fletcher-32 checksums (files written before they did do not).
bool HasChecksum(hid_t dataset) {
  const Handle properties(H5Dget_create_plist(dataset));
  unsigned flags = 0;
  size_t values = 0;
  unsigned config = 0;
  return properties.valid() && H5Pget_filter_by_id2(properties.id(), H5Z_FILTER_FLETCHER32, &flags,
                                                    &values, nullptr, 0, nullptr, &config) >= 0;
}

template <typename T>
std::vector<T> ReadWhole(const File& file, hid_t location, const std::string& name,
                         hid_t memory_type) {
  const Handle dataset = OpenDataset(file, location, name);
  const Handle space(H5Dget_space(dataset.id()));
  const hssize_t count = H5Sget_simple_extent_npoints(space.id());
  if (count < 0) Fail(file.path(), "cannot read the shape of dataset '" + name + "'");
  std::vector<T> values(static_cast<size_t>(count));
  const bool checksummed = HasChecksum(dataset.id());  // asked first: HDF5 calls reset the errors
  if (count > 0 &&
      H5Dread(dataset.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    Fail(file.path(), checksummed
                          ? DamagedDataset(name)
                          : "cannot read dataset '" + name + "' (truncated or corrupt file?)");
  }
  return values;
}

void WriteScalarAttribute(const File& file, hid_t location, const std::string& name,
                          hid_t file_type, hid_t memory_type, const void* value) {
  SilenceAutomaticErrorPrinting();
  if (H5Aexists(location, name.c_str()) > 0) H5Adelete(location, name.c_str());
  const Handle space(H5Screate(H5S_SCALAR));
  const Handle attribute(
      H5Acreate2(location, name.c_str(), file_type, space.id(), H5P_DEFAULT, H5P_DEFAULT));
  if (!attribute.valid() || H5Awrite(attribute.id(), memory_type, value) < 0) {
    Fail(file.path(), "cannot write attribute '" + name + "'");
  }
}

}  // namespace

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    Reset();
    id_ = other.id_;
    other.id_ = H5I_INVALID_HID;
  }
  return *this;
}

void Handle::Reset() {
  if (id_ < 0) return;
  switch (H5Iget_type(id_)) {
    case H5I_FILE:
      H5Fclose(id_);
      break;
    case H5I_GROUP:
      H5Gclose(id_);
      break;
    case H5I_DATASET:
      H5Dclose(id_);
      break;
    case H5I_ATTR:
      H5Aclose(id_);
      break;
    case H5I_DATATYPE:
      H5Tclose(id_);
      break;
    case H5I_DATASPACE:
      H5Sclose(id_);
      break;
    case H5I_GENPROP_LST:
      H5Pclose(id_);
      break;
    default:
      break;
  }
  id_ = H5I_INVALID_HID;
}

File File::Create(const std::string& path) {
  SilenceAutomaticErrorPrinting();
  // At most the 1.8 format (not "latest") so that h5py and HDF5 1.8 tools, which robomimic
  // users may still have, can read what we write. At least the earliest, not 1.8: HDF5 1.10's
  // image of an in-memory file (below) carries a stale checksum in a 1.8 (version 2) superblock.
  Handle access(H5Pcreate(H5P_FILE_ACCESS));
  H5Pset_libver_bounds(access.id(), H5F_LIBVER_EARLIEST, H5F_LIBVER_V18);
  // The file is built in memory (the core driver, no backing store) and written in one piece by
  // Close. HDF5 1.10 does not survive a failing disk: after a write error (a full disk) its
  // close fails, and closing the half-closed file again, or the library's own clean-up at exit,
  // crashes the process. In memory, HDF5 never meets the disk; our own write says what failed.
  H5Pset_fapl_core(access.id(), /*increment=*/size_t{1} << 20, /*backing_store=*/0);
  H5Pset_fclose_degree(access.id(), H5F_CLOSE_STRONG);
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.id()));
  if (!file.valid()) Fail(path, "cannot create HDF5 file");
  return File(std::move(file), path, /*writable=*/true);
}

File File::OpenReadOnly(const std::string& path) {
  RefuseNonRegularFile(path);
  SilenceAutomaticErrorPrinting();
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!file.valid()) Fail(path, "cannot open as HDF5 (missing, truncated or not an HDF5 file)");
  return File(std::move(file), path, /*writable=*/false);
}

void File::Close() {
  if (!handle_.valid()) return;
  SilenceAutomaticErrorPrinting();
  // Released first: whatever H5Fclose answers, the id must not be closed again by ~Handle.
  const hid_t id = handle_.Release();
  std::string image;
  bool built = true;
  if (writable_) {
    built = H5Fflush(id, H5F_SCOPE_LOCAL) >= 0;
    const ssize_t size = built ? H5Fget_file_image(id, nullptr, 0) : -1;
    built = size > 0;
    if (built) {
      image.resize(static_cast<size_t>(size));
      built = H5Fget_file_image(id, image.data(), image.size()) == size;
    }
  }
  const bool closed = H5Fclose(id) >= 0;
  if (!built || !closed) Fail(path_, "cannot build the HDF5 file");
  if (writable_) WriteWholeFile(path_, image);
}

std::string LastErrorDetail() {
  std::vector<std::string> messages;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, CollectMessage, &messages);
  std::string detail;
  for (size_t i = 0; i < messages.size() && i < 3; ++i) {
    if (!detail.empty()) detail += "; ";
    detail += messages[i];
  }
  return detail;
}

namespace {

// The operating system's reason when HDF5 failed on a system call: its file driver reports
// "..., errno = 28, error message = 'No space left on device', ...". 0 when there is none.
int SystemErrorOf(const std::string& detail) {
  static const std::regex kErrno("errno = ([0-9]+)");
  std::smatch match;
  if (!std::regex_search(detail, match, kErrno)) return 0;
  return std::stoi(match[1].str());
}

std::string AllMessages() {
  std::vector<std::string> messages;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, CollectMessage, &messages);
  std::string all;
  for (const std::string& m : messages) all += m + "\n";
  return all;
}

}  // namespace

void Fail(const std::string& file, const std::string& what) {
  const int system_error = SystemErrorOf(AllMessages());
  const std::string detail = LastErrorDetail();
  H5Eclear2(H5E_DEFAULT);
  // A full disk or a read-only medium is said in the system's plain words, not HDF5's stack.
  if (system_error != 0) throw UserError(file + ": " + what + ": " + std::strerror(system_error));
  throw UserError(file + ": " + what + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}

bool Exists(hid_t location, const std::string& path) {
  SilenceAutomaticErrorPrinting();
  // H5Lexists checks one link at a time: walk the path so "obs/image" works without "obs".
  std::string prefix;
  size_t start = 0;
  while (start <= path.size()) {
    const size_t slash = path.find('/', start);
    const size_t end = slash == std::string::npos ? path.size() : slash;
    prefix += (prefix.empty() ? "" : "/") + path.substr(start, end - start);
    if (H5Lexists(location, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return H5Oexists_by_name(location, path.c_str(), H5P_DEFAULT) > 0;
}

Handle CreateGroup(const File& file, hid_t location, const std::string& name) {
  SilenceAutomaticErrorPrinting();
  Handle group(H5Gcreate2(location, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  if (!group.valid()) Fail(file.path(), "cannot create group '" + name + "'");
  return group;
}

Handle OpenGroup(const File& file, hid_t location, const std::string& name) {
  SilenceAutomaticErrorPrinting();
  if (!Exists(location, name)) Fail(file.path(), "missing group '" + name + "'");
  Handle group(H5Gopen2(location, name.c_str(), H5P_DEFAULT));
  if (!group.valid()) Fail(file.path(), "'" + name + "' is not a readable group");
  return group;
}

std::vector<std::string> ListChildren(const File& file, hid_t group) {
  SilenceAutomaticErrorPrinting();
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0) Fail(file.path(), "cannot list a group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t size =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (size < 0) Fail(file.path(), "cannot read a link name");
    std::string name(static_cast<size_t>(size), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size() + 1,
                       H5P_DEFAULT);
    names.push_back(name);
  }
  return names;
}

void WriteArray(const File& file, hid_t location, const std::string& name, ElementType type,
                const std::vector<hsize_t>& dims, const void* data) {
  SilenceAutomaticErrorPrinting();
  const Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  // Every non-empty array is stored in chunks with a Fletcher-32 checksum each, which HDF5
  // verifies on every read: a flipped bit in an image is then a read error, not a training
  // sample. An empty array has no data to damage (and cannot be chunked).
  const Handle properties(H5Pcreate(H5P_DATASET_CREATE));
  if (count > 0 && !dims.empty()) {
    std::vector<hsize_t> chunk = dims;
    const hsize_t row_bytes = count / dims[0] * H5Tget_size(FileType(type));
    chunk[0] = std::clamp<hsize_t>(kChunkBytes / std::max<hsize_t>(row_bytes, 1), 1, dims[0]);
    if (H5Pset_chunk(properties.id(), static_cast<int>(chunk.size()), chunk.data()) < 0 ||
        H5Pset_fletcher32(properties.id()) < 0) {
      Fail(file.path(), "cannot set up the checksum of dataset '" + name + "'");
    }
  }
  const Handle dataset(H5Dcreate2(location, name.c_str(), FileType(type), space.id(), H5P_DEFAULT,
                                  properties.id(), H5P_DEFAULT));
  if (!dataset.valid()) Fail(file.path(), "cannot create dataset '" + name + "'");
  if (count > 0 &&
      H5Dwrite(dataset.id(), MemoryType(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    Fail(file.path(), "cannot write dataset '" + name + "'");
  }
}

namespace {

herr_t CollectDatasetNames(hid_t group, const char* name, const H5L_info_t* /*info*/, void* out) {
  if (H5Oexists_by_name(group, name, H5P_DEFAULT) <= 0) return 0;  // a dangling link
  H5O_info_t info;
  if (H5Oget_info_by_name(group, name, &info, H5P_DEFAULT) >= 0 && info.type == H5O_TYPE_DATASET) {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
  }
  return 0;
}

}  // namespace

void VerifyChecksums(const File& file, hid_t location, const std::set<std::string>& already_read) {
  SilenceAutomaticErrorPrinting();
  std::vector<std::string> names;
  if (H5Lvisit(location, H5_INDEX_NAME, H5_ITER_INC, CollectDatasetNames, &names) < 0) {
    Fail(file.path(), "cannot list the datasets");
  }
  std::vector<char> buffer;
  for (const std::string& name : names) {
    if (already_read.count(name) > 0) continue;
    const Handle dataset = OpenDataset(file, location, name);
    const Handle type(H5Dget_type(dataset.id()));
    if (!HasChecksum(dataset.id()) || H5Tget_class(type.id()) == H5T_STRING) continue;
    const Handle space(H5Dget_space(dataset.id()));
    const hssize_t count = H5Sget_simple_extent_npoints(space.id());
    if (count <= 0) continue;
    buffer.resize(static_cast<size_t>(count) * H5Tget_size(type.id()));
    if (H5Dread(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0) {
      Fail(file.path(), DamagedDataset(name));
    }
  }
}

std::vector<hsize_t> Dimensions(const File& file, hid_t location, const std::string& name) {
  const Handle dataset = OpenDataset(file, location, name);
  const Handle space(H5Dget_space(dataset.id()));
  const int rank = H5Sget_simple_extent_ndims(space.id());
  if (rank < 0) Fail(file.path(), "cannot read the shape of dataset '" + name + "'");
  std::vector<hsize_t> dims(static_cast<size_t>(rank));
  H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
  return dims;
}

bool IsUInt8(const File& file, hid_t location, const std::string& name) {
  const Handle dataset = OpenDataset(file, location, name);
  const Handle type(H5Dget_type(dataset.id()));
  return H5Tget_class(type.id()) == H5T_INTEGER && H5Tget_size(type.id()) == 1 &&
         H5Tget_sign(type.id()) == H5T_SGN_NONE;
}

std::vector<float> ReadFloats(const File& file, hid_t location, const std::string& name) {
  return ReadWhole<float>(file, location, name, H5T_NATIVE_FLOAT);
}

std::vector<uint8_t> ReadBytes(const File& file, hid_t location, const std::string& name) {
  return ReadWhole<uint8_t>(file, location, name, H5T_NATIVE_UINT8);
}

void WriteAttribute(const File& file, hid_t location, const std::string& name, int64_t value) {
  WriteScalarAttribute(file, location, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void WriteAttribute(const File& file, hid_t location, const std::string& name, double value) {
  WriteScalarAttribute(file, location, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void WriteAttribute(const File& file, hid_t location, const std::string& name,
                    const std::string& value) {
  const Handle type = VariableLengthString();
  const char* text = value.c_str();
  WriteScalarAttribute(file, location, name, type.id(), type.id(), &text);
}

bool HasAttribute(hid_t location, const std::string& name) {
  SilenceAutomaticErrorPrinting();
  return H5Aexists(location, name.c_str()) > 0;
}

int64_t ReadIntAttribute(const File& file, hid_t location, const std::string& name) {
  const Handle attribute = OpenAttribute(file, location, name);
  const Handle type(H5Aget_type(attribute.id()));
  if (H5Tget_class(type.id()) != H5T_INTEGER) {
    Fail(file.path(), "attribute '" + name + "' is not an integer");
  }
  int64_t value = 0;
  if (H5Aread(attribute.id(), H5T_NATIVE_INT64, &value) < 0) {
    Fail(file.path(), "cannot read attribute '" + name + "'");
  }
  return value;
}

double ReadDoubleAttribute(const File& file, hid_t location, const std::string& name) {
  const Handle attribute = OpenAttribute(file, location, name);
  const Handle type(H5Aget_type(attribute.id()));
  const H5T_class_t type_class = H5Tget_class(type.id());
  if (type_class != H5T_FLOAT && type_class != H5T_INTEGER) {
    Fail(file.path(), "attribute '" + name + "' is not a number");
  }
  double value = 0;
  if (H5Aread(attribute.id(), H5T_NATIVE_DOUBLE, &value) < 0) {
    Fail(file.path(), "cannot read attribute '" + name + "'");
  }
  return value;
}

std::string ReadStringAttribute(const File& file, hid_t location, const std::string& name) {
  const Handle attribute = OpenAttribute(file, location, name);
  const Handle type(H5Aget_type(attribute.id()));
  if (H5Tget_class(type.id()) != H5T_STRING) {
    Fail(file.path(), "attribute '" + name + "' is not a string");
  }
  if (H5Tis_variable_str(type.id()) > 0) {
    char* text = nullptr;
    const Handle memory_type = VariableLengthString();
    if (H5Aread(attribute.id(), memory_type.id(), &text) < 0) {
      Fail(file.path(), "cannot read attribute '" + name + "'");
    }
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  const size_t size = H5Tget_size(type.id());
  std::string value(size, '\0');
  if (H5Aread(attribute.id(), type.id(), value.data()) < 0) {
    Fail(file.path(), "cannot read attribute '" + name + "'");
  }
  value.erase(std::find(value.begin(), value.end(), '\0'), value.end());
  return value;
}

void WriteStrings(const File& file, hid_t location, const std::string& name,
                  const std::vector<std::string>& values) {
  SilenceAutomaticErrorPrinting();
  const Handle type = VariableLengthString();
  const hsize_t count = values.size();
  const Handle space(H5Screate_simple(1, &count, nullptr));
  const Handle dataset(H5Dcreate2(location, name.c_str(), type.id(), space.id(), H5P_DEFAULT,
                                  H5P_DEFAULT, H5P_DEFAULT));
  if (!dataset.valid()) Fail(file.path(), "cannot create dataset '" + name + "'");
  std::vector<const char*> pointers;
  for (const std::string& value : values) pointers.push_back(value.c_str());
  if (count > 0 &&
      H5Dwrite(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) < 0) {
    Fail(file.path(), "cannot write dataset '" + name + "'");
  }
}

std::vector<std::string> ReadStrings(const File& file, hid_t location, const std::string& name) {
  const Handle dataset = OpenDataset(file, location, name);
  const Handle type(H5Dget_type(dataset.id()));
  if (H5Tget_class(type.id()) != H5T_STRING) {
    Fail(file.path(), "dataset '" + name + "' does not hold strings");
  }
  const Handle space(H5Dget_space(dataset.id()));
  const hssize_t count = H5Sget_simple_extent_npoints(space.id());
  std::vector<std::string> values;
  if (count <= 0) return values;
  if (H5Tis_variable_str(type.id()) > 0) {
    std::vector<char*> pointers(static_cast<size_t>(count), nullptr);
    const Handle memory_type = VariableLengthString();
    if (H5Dread(dataset.id(), memory_type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) <
        0) {
      Fail(file.path(), "cannot read dataset '" + name + "'");
    }
    for (char* p : pointers) values.emplace_back(p != nullptr ? p : "");
    H5Dvlen_reclaim(memory_type.id(), space.id(), H5P_DEFAULT, pointers.data());
    return values;
  }
  // Fixed-length strings (numpy "S" arrays, as robomimic's own scripts write masks).
  const size_t size = H5Tget_size(type.id());
  std::vector<char> buffer(size * static_cast<size_t>(count));
  if (H5Dread(dataset.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0) {
    Fail(file.path(), "cannot read dataset '" + name + "'");
  }
  for (hssize_t i = 0; i < count; ++i) {
    std::string value(buffer.data() + static_cast<size_t>(i) * size, size);
    value.erase(std::find(value.begin(), value.end(), '\0'), value.end());
    values.push_back(value);
  }
  return values;
}

void CreateExternalLink(const File& file, hid_t location, const std::string& name,
                        const std::string& target_file, const std::string& target_object) {
  SilenceAutomaticErrorPrinting();
  if (H5Lcreate_external(target_file.c_str(), target_object.c_str(), location, name.c_str(),
                         H5P_DEFAULT, H5P_DEFAULT) < 0) {
    Fail(file.path(), "cannot create link '" + name + "' to " + target_file);
  }
}

}  // namespace recon::store::h5
