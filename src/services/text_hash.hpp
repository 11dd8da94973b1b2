// A stable 64-bit fingerprint of a text (FNV-1a), as 16 hex digits: names step-check cache
// entries and identifies a sweep's scene in sweep.plan.json. Not cryptographic.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace stiction::services {

inline std::string text_hash(const std::string& text) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

}  // namespace stiction::services
