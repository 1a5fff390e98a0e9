#pragma once

// The store's JSON files (the session manifest, training records, rollout summaries) are read
// through one reader, so that every malformed file is refused the same way: a UserError naming
// the file and the field, e.g. "session.json: field 'beacons[0].dim' must be an integer".

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace recon::store {

/// Reads fields of one JSON object and names the field in every error.
class FieldReader {
 public:
  /// `source` names the file; `prefix` the object's place in it ("" for the top level).
  FieldReader(const nlohmann::json& object, std::string source, std::string prefix);

  bool Has(const std::string& key) const { return object_.contains(key); }
  const nlohmann::json& Required(const std::string& key) const;
  std::string String(const std::string& key) const;
  std::string OptionalString(const std::string& key, const std::string& fallback) const;
  /// A string, or nothing when the key is absent or null.
  std::optional<std::string> OptionalNullableString(const std::string& key) const;
  int64_t Integer(const std::string& key) const;
  int64_t OptionalInteger(const std::string& key, int64_t fallback) const;
  int64_t NonNegativeInteger(const std::string& key) const;
  uint64_t Unsigned(const std::string& key) const;
  uint64_t OptionalUnsigned(const std::string& key, uint64_t fallback) const;
  double Number(const std::string& key) const;
  double OptionalNumber(const std::string& key, double fallback) const;
  /// As OptionalNumber, but null reads as NaN: nlohmann::json writes a NaN (a loss that
  /// diverged, a mean of nothing) as null, and a record must read back what it held.
  double OptionalNumberOrNan(const std::string& key, double fallback) const;
  bool Boolean(const std::string& key, bool fallback) const;
  const nlohmann::json& Array(const std::string& key) const;
  /// Lists of numbers (null reads as NaN), integers and strings; empty when the key is absent.
  std::vector<double> OptionalNumbers(const std::string& key) const;
  std::vector<int64_t> OptionalIntegers(const std::string& key) const;
  std::vector<std::string> OptionalStrings(const std::string& key) const;
  /// An object of numbers by name (null reads as NaN); empty when the key is absent.
  std::map<std::string, double> OptionalNumberMap(const std::string& key) const;
  FieldReader Object(const std::string& key) const;
  FieldReader Element(const nlohmann::json& element, const std::string& key, size_t index) const;
  std::string Name(const std::string& key) const;
  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const;
  const nlohmann::json& object() const { return object_; }

 private:
  const nlohmann::json& object_;
  std::string source_;
  std::string prefix_;
};

/// Parses the JSON file at `path`; nullopt when there is no such file. UserError naming the file
/// when it cannot be read or is not valid JSON.
std::optional<nlohmann::json> ReadJsonFile(const std::string& path);

/// Every `*.json` file directly in `folder`, parsed, by file name without the extension; empty
/// when there is no such folder. UserError as ReadJsonFile.
std::map<std::string, nlohmann::json> ReadJsonFilesIn(const std::string& folder);

/// Reads a record of a method's results from its file's JSON; `method` is what it is of when
/// the record does not say.
template <typename Record>
using RecordFromJson = Record (*)(const nlohmann::json& value, const std::string& source,
                                  const std::string& method);

/// The record in the file at `path` (the file of `method`), nullopt when there is no such file.
template <typename Record>
std::optional<Record> ReadRecordFile(const std::string& path, const std::string& method,
                                     RecordFromJson<Record> from_json) {
  const std::optional<nlohmann::json> value = ReadJsonFile(path);
  if (!value) return std::nullopt;
  return from_json(*value, path, method);
}

/// The records in every `<method>.json` file of `folder`, by method.
template <typename Record>
std::map<std::string, Record> ReadRecordsIn(const std::string& folder,
                                            RecordFromJson<Record> from_json) {
  std::map<std::string, Record> records;
  for (const auto& [method, value] : ReadJsonFilesIn(folder)) {
    const std::string path = (std::filesystem::path(folder) / (method + ".json")).string();
    records.emplace(method, from_json(value, path, method));
  }
  return records;
}

/// Writes `value` to `path` atomically, indented by one space and ending in a newline (the
/// layout of the session's result files).
void WriteJsonFile(const std::string& path, const nlohmann::json& value);

}  // namespace recon::store
