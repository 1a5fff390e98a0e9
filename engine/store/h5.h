#pragma once

// A thin layer over the HDF5 C library: owning handles, typed reads and writes of whole arrays,
// attributes, and errors that name the file and the object. The HDF5 C++ API is not used
// because it throws its own exception types without the path, and because the C API is what
// every other HDF5 tool documents.

#include <hdf5.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace recon::store::h5 {

/// An owned HDF5 identifier (file, group, dataset, attribute, type or space), closed on
/// destruction with the matching H5*close.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  ~Handle() { Reset(); }
  Handle(Handle&& other) noexcept : id_(other.id_) { other.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t id() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void Reset();
  /// Gives up ownership without closing: the caller has closed the id (or HDF5 refused to, and
  /// a second close of a file whose first close failed crashes the library).
  hid_t Release() {
    const hid_t id = id_;
    id_ = H5I_INVALID_HID;
    return id;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
};

/// An open HDF5 file with its path, which every error message names.
class File {
 public:
  /// Creates a file for writing; nothing reaches `path` before Close.
  static File Create(const std::string& path);
  /// Opens an existing file read-only. UserError naming the path when it is missing, truncated
  /// or not HDF5.
  static File OpenReadOnly(const std::string& path);

  hid_t id() const { return handle_.id(); }
  const std::string& path() const { return path_; }
  /// Closes; a file made by Create is written to its path here, in one piece (it was built in
  /// memory), so a full disk surfaces as a UserError naming the path and the system's reason
  /// rather than being lost in a destructor. A created file destroyed without Close is never
  /// written.
  void Close();

 private:
  File(Handle handle, std::string path, bool writable)
      : handle_(std::move(handle)), path_(std::move(path)), writable_(writable) {}
  Handle handle_;
  std::string path_;
  bool writable_ = false;
};

/// The element types the store writes.
enum class ElementType { kFloat32, kFloat64, kUInt8, kInt64 };

/// The HDF5 library's explanation of its most recent failure on this thread (innermost first),
/// for error messages; empty if none.
std::string LastErrorDetail();

/// Throws UserError "<file>: <what> (<HDF5 detail>)".
[[noreturn]] void Fail(const std::string& file, const std::string& what);

bool Exists(hid_t location, const std::string& path);
Handle CreateGroup(const File& file, hid_t location, const std::string& name);
/// Opens a group; UserError naming `file` and `name` when it is missing or not a group.
Handle OpenGroup(const File& file, hid_t location, const std::string& name);
/// Names of the links in a group, in name order.
std::vector<std::string> ListChildren(const File& file, hid_t group);

/// Writes a whole array (row-major) as a new dataset: chunked (whole rows, up to 1 MiB a chunk),
/// each chunk with a Fletcher-32 checksum that every read verifies.
void WriteArray(const File& file, hid_t location, const std::string& name, ElementType type,
                const std::vector<hsize_t>& dims, const void* data);
/// Reads every checksummed dataset under `location` (strings aside) but those in `already_read`
/// (paths relative to `location`, which the caller read itself, and so verified): UserError
/// naming the file and the first dataset whose data does not match its checksum. For datasets a
/// reader does not otherwise load (robomimic's `states`, `dones`), so that no damage passes
/// unseen, without reading the others twice.
void VerifyChecksums(const File& file, hid_t location, const std::set<std::string>& already_read);
/// The dimensions of a dataset. UserError naming `file` and `name` if it is missing.
std::vector<hsize_t> Dimensions(const File& file, hid_t location, const std::string& name);
/// A dataset's shape as an error message gives it: "(12, 3)".
inline std::string ShapeText(const std::vector<hsize_t>& dims) {
  std::string shape;
  for (hsize_t d : dims) shape += (shape.empty() ? "" : ", ") + std::to_string(d);
  return "(" + shape + ")";
}
/// True when the dataset stores 8-bit unsigned integers (images as robomimic keeps them).
bool IsUInt8(const File& file, hid_t location, const std::string& name);
/// Reads a whole numeric dataset, converting to the requested type (HDF5 converts float64
/// actions from other tools to float32 on read).
std::vector<float> ReadFloats(const File& file, hid_t location, const std::string& name);
std::vector<uint8_t> ReadBytes(const File& file, hid_t location, const std::string& name);

void WriteAttribute(const File& file, hid_t location, const std::string& name, int64_t value);
void WriteAttribute(const File& file, hid_t location, const std::string& name, double value);
/// A variable-length UTF-8 string, as h5py writes Python strings (robomimic's env_args).
void WriteAttribute(const File& file, hid_t location, const std::string& name,
                    const std::string& value);
bool HasAttribute(hid_t location, const std::string& name);
int64_t ReadIntAttribute(const File& file, hid_t location, const std::string& name);
double ReadDoubleAttribute(const File& file, hid_t location, const std::string& name);
/// Reads fixed- or variable-length string attributes.
std::string ReadStringAttribute(const File& file, hid_t location, const std::string& name);

/// A dataset of variable-length strings (robomimic's mask/train lists demo names this way).
void WriteStrings(const File& file, hid_t location, const std::string& name,
                  const std::vector<std::string>& values);
std::vector<std::string> ReadStrings(const File& file, hid_t location, const std::string& name);

/// An external link `name` in `location` to object `target_object` of file `target_file`
/// (a path relative to the linking file's folder).
void CreateExternalLink(const File& file, hid_t location, const std::string& name,
                        const std::string& target_file, const std::string& target_object);

}  // namespace recon::store::h5
