// Content hashes for provenance (scene file hash in outputs) and, later, kernel cache keys.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace clpt {

// 64-bit FNV-1a: fast, stable across platforms; not cryptographic.
uint64_t fnv1a64(std::string_view bytes, uint64_t seed = 0xcbf29ce484222325ull);

// 16 lowercase hex digits.
std::string hex64(uint64_t value);

}  // namespace clpt
