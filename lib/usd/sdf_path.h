#pragma once
// USD path strings as the layer model (layer.h) keeps them: building child,
// property and variant paths, taking them apart, prefix tests and
// replacement, anchoring relative paths. Paths are plain strings; these
// helpers know USD's syntax ("/A/B", "/A.attr", "/A{set=sel}B",
// "/A.rel[/T]") so the rest of the module never splits paths by hand.
#include <string>
#include <string_view>
#include <vector>

namespace sdg::usd::path {

inline constexpr const char* kRoot = "/";

// "/A" + "B" -> "/A/B"; "/" + "B" -> "/B"; "/A{v=x}" + "B" -> "/A{v=x}B".
std::string child(std::string_view parent, std::string_view name);
// "/A" + "points" -> "/A.points".
std::string property(std::string_view prim, std::string_view name);
// "/A{set=}" (a variant set spec) and "/A{set=sel}" (a variant spec).
std::string variantSet(std::string_view prim, std::string_view set);
std::string variant(std::string_view prim, std::string_view set, std::string_view selection);

// The prim part of a property or target path ("/A/B.x[/C]" -> "/A/B").
std::string_view primPart(std::string_view path);
// The property name of a property path ("/A.x:y" -> "x:y"), "" for a prim path.
std::string_view propertyName(std::string_view path);
// The parent prim ("/A/B" -> "/A", "/A" -> "/", "/A{v=x}B" -> "/A{v=x}", "/A{v=x}" -> "/A").
std::string parent(std::string_view primPath);
// The last name ("/A/B" -> "B", "/A{v=x}B" -> "B").
std::string_view name(std::string_view primPath);
// Number of prim names in the path ("/" 0, "/A/B" 2); variant selections do not count.
int depth(std::string_view primPath);
// Removes variant selections: "/A{v=x}B.c" -> "/A/B.c".
std::string stripVariants(std::string_view path);
bool hasVariants(std::string_view path);

// Whether `path` is `prefix` or lies under it ("/A/B" and "/A/B.x" are under "/A"; "/AB" is not).
bool hasPrefix(std::string_view path, std::string_view prefix);
// `path` with `oldPrefix` replaced by `newPrefix`; requires hasPrefix(path, oldPrefix).
std::string replacePrefix(std::string_view path, std::string_view oldPrefix, std::string_view newPrefix);

// USD path syntax: absolute ("/A/B", "/A{v=x}B", "/A.x", "/A.rel[/T]") or
// relative ("B/C", "../B", ".x"); names are identifiers.
bool isValidPath(std::string_view path);

// Anchors a relative path ("../B", ".x", "C/D") at the prim `anchor`;
// absolute paths come back unchanged. Returns "" when ".." climbs above "/".
// `path` must be valid (isValidPath); linear in the lengths.
std::string makeAbsolute(std::string_view anchor, std::string_view path);

// USD identifiers: a letter or '_' (or a UTF-8 lead byte) followed by letters, digits, '_'.
bool isIdentifier(std::string_view name);
// ':'-separated identifiers ("inputs:diffuseColor").
bool isNamespacedIdentifier(std::string_view name);
// A syntactically valid absolute prim path of identifiers ("/A/B"), for reference targets.
bool isAbsolutePrimPath(std::string_view path);

}  // namespace sdg::usd::path
