#pragma once

// FNV-1a (64 bits): the one digest the project uses to tell bytes apart (dataset fingerprints,
// checkpoint entries, the session index, model ids). Not cryptographic: it finds accidents (a
// flipped bit, a file from another training), not an attacker.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace recon {

inline constexpr uint64_t kFnv1aOffset = 0xcbf29ce484222325ULL;

/// Folds `size` bytes at `data` into `hash` (start from kFnv1aOffset).
inline uint64_t Fnv1a(const void* data, size_t size, uint64_t hash = kFnv1aOffset) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

inline uint64_t Fnv1a(std::string_view bytes, uint64_t hash = kFnv1aOffset) {
  return Fnv1a(bytes.data(), bytes.size(), hash);
}

/// `hash` as 16 lower-case hex digits.
std::string DigestHex(uint64_t hash);

}  // namespace recon
