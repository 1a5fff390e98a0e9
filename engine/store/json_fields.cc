#include "engine/store/json_fields.h"

#include <cmath>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::store {

namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
}  // namespace

FieldReader::FieldReader(const json& object, std::string source, std::string prefix)
    : object_(object), source_(std::move(source)), prefix_(std::move(prefix)) {
  if (!object_.is_object()) Fail(prefix_.empty() ? "(top level)" : prefix_, "must be an object");
}

const json& FieldReader::Required(const std::string& key) const {
  if (!object_.contains(key)) Fail(Name(key), "is missing");
  return object_.at(key);
}

std::string FieldReader::String(const std::string& key) const {
  const json& value = Required(key);
  if (!value.is_string()) Fail(Name(key), "must be a string");
  return value.get<std::string>();
}

std::string FieldReader::OptionalString(const std::string& key, const std::string& fallback) const {
  return object_.contains(key) ? String(key) : fallback;
}

std::optional<std::string> FieldReader::OptionalNullableString(const std::string& key) const {
  if (!object_.contains(key) || object_.at(key).is_null()) return std::nullopt;
  return String(key);
}

int64_t FieldReader::Integer(const std::string& key) const {
  const json& value = Required(key);
  if (!value.is_number_integer()) Fail(Name(key), "must be an integer");
  return value.get<int64_t>();
}

int64_t FieldReader::OptionalInteger(const std::string& key, int64_t fallback) const {
  return object_.contains(key) ? Integer(key) : fallback;
}

int64_t FieldReader::NonNegativeInteger(const std::string& key) const {
  const int64_t value = Integer(key);
  if (value < 0) Fail(Name(key), "must not be negative");
  return value;
}

uint64_t FieldReader::Unsigned(const std::string& key) const {
  const json& value = Required(key);
  if (!value.is_number_unsigned()) Fail(Name(key), "must be a non-negative integer");
  return value.get<uint64_t>();
}

uint64_t FieldReader::OptionalUnsigned(const std::string& key, uint64_t fallback) const {
  return object_.contains(key) ? Unsigned(key) : fallback;
}

double FieldReader::Number(const std::string& key) const {
  const json& value = Required(key);
  if (!value.is_number()) Fail(Name(key), "must be a number");
  return value.get<double>();
}

double FieldReader::OptionalNumber(const std::string& key, double fallback) const {
  return object_.contains(key) ? Number(key) : fallback;
}

double FieldReader::OptionalNumberOrNan(const std::string& key, double fallback) const {
  if (!object_.contains(key)) return fallback;
  if (object_.at(key).is_null()) return std::nan("");
  return Number(key);
}

bool FieldReader::Boolean(const std::string& key, bool fallback) const {
  if (!object_.contains(key)) return fallback;
  if (!object_.at(key).is_boolean()) Fail(Name(key), "must be true or false");
  return object_.at(key).get<bool>();
}

const json& FieldReader::Array(const std::string& key) const {
  const json& value = Required(key);
  if (!value.is_array()) Fail(Name(key), "must be a list");
  return value;
}

std::vector<double> FieldReader::OptionalNumbers(const std::string& key) const {
  std::vector<double> values;
  if (!object_.contains(key)) return values;
  const json& list = Array(key);
  for (size_t i = 0; i < list.size(); ++i) {
    if (list[i].is_null()) {
      values.push_back(std::nan(""));
    } else if (list[i].is_number()) {
      values.push_back(list[i].get<double>());
    } else {
      Fail(Name(key) + "[" + std::to_string(i) + "]", "must be a number");
    }
  }
  return values;
}

std::vector<int64_t> FieldReader::OptionalIntegers(const std::string& key) const {
  std::vector<int64_t> values;
  if (!object_.contains(key)) return values;
  const json& list = Array(key);
  for (size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_number_integer()) {
      Fail(Name(key) + "[" + std::to_string(i) + "]", "must be an integer");
    }
    values.push_back(list[i].get<int64_t>());
  }
  return values;
}

std::vector<std::string> FieldReader::OptionalStrings(const std::string& key) const {
  std::vector<std::string> values;
  if (!object_.contains(key)) return values;
  const json& list = Array(key);
  for (size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_string()) Fail(Name(key) + "[" + std::to_string(i) + "]", "must be a string");
    values.push_back(list[i].get<std::string>());
  }
  return values;
}

std::map<std::string, double> FieldReader::OptionalNumberMap(const std::string& key) const {
  std::map<std::string, double> values;
  if (!object_.contains(key)) return values;
  const FieldReader map = Object(key);
  for (const auto& [name, value] : map.object().items()) {
    values[name] = map.OptionalNumberOrNan(name, 0.0);
  }
  return values;
}

FieldReader FieldReader::Object(const std::string& key) const {
  return {Required(key), source_, Name(key)};
}

FieldReader FieldReader::Element(const json& element, const std::string& key, size_t index) const {
  return {element, source_, Name(key) + "[" + std::to_string(index) + "]"};
}

std::string FieldReader::Name(const std::string& key) const {
  return prefix_.empty() ? key : prefix_ + "." + key;
}

void FieldReader::Fail(const std::string& field, const std::string& problem) const {
  throw UserError(source_ + ": field '" + field + "' " + problem);
}

std::optional<json> ReadJsonFile(const std::string& path) {
  const std::optional<std::string> text = ReadWholeFile(path);
  if (!text) return std::nullopt;
  try {
    return json::parse(*text);
  } catch (const json::parse_error& e) {
    throw UserError(path + ": not valid JSON (" + e.what() + ")");
  }
}

std::map<std::string, json> ReadJsonFilesIn(const std::string& folder) {
  std::map<std::string, json> files;
  if (!fs::is_directory(folder)) return files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".json") continue;
    if (std::optional<json> value = ReadJsonFile(entry.path().string())) {
      files[entry.path().stem().string()] = std::move(*value);
    }
  }
  return files;
}

void WriteJsonFile(const std::string& path, const json& value) {
  WriteFileAtomically(path, value.dump(1) + "\n");
}

}  // namespace recon::store
