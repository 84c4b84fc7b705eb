#pragma once
// USD-style absolute prim paths: "/Root/Pallet_01". Components are
// identifiers ([A-Za-z_][A-Za-z0-9_]*), as in USD's Sdf.
#include <string>
#include <string_view>

namespace sdg::path {

// Documented limits that keep hostile input bounded.
inline constexpr size_t kMaxPathLength = 4096;
inline constexpr size_t kMaxDepth = 256;

// Why `path` is not a valid absolute prim path, or "" when it is.
std::string whyInvalid(std::string_view path);
inline bool isValid(std::string_view path) { return whyInvalid(path).empty(); }
bool isIdentifier(std::string_view name);

// "/A/B" -> "/A"; "/A" -> "/"; "/" -> "".
std::string_view parent(std::string_view path);
// "/A/B" -> "B".
std::string_view name(std::string_view path);
// True when `path` is `ancestor` or below it.
bool isAtOrBelow(std::string_view path, std::string_view ancestor);
size_t depth(std::string_view path);

}  // namespace sdg::path
