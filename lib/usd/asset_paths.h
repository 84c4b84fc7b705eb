#pragma once
// Package-relative asset paths as USD writes them (Ar's package utilities):
// "pkg.usdz[dir/a.usdc]" names the entry dir/a.usdc of pkg.usdz, and
// packages nest: "a.usdz[b.usdz[c.png]]" is c.png inside b.usdz inside
// a.usdz. splitPackagePath (layer_io.h) splits at the outermost brackets;
// these split and join at the innermost, which is what anchoring needs: a
// relative path written in a layer resolves from the layer's own folder in
// its innermost package (resolveAssetPath, compose.h).
#include <string>
#include <utility>

namespace sdg::usd {

// "a.usdz[b.usdz[c/d.png]]" -> {"a.usdz[b.usdz]", "c/d.png"}; a plain path
// gives {path, ""}.
std::pair<std::string, std::string> splitPackagePathInner(const std::string& path);

// The entry `packaged` inside `package`, nesting as needed:
// ("a.usdz[b.usdz]", "c.png") -> "a.usdz[b.usdz[c.png]]".
std::string joinPackagePath(const std::string& package, const std::string& packaged);

// True when the innermost file of `path` is a .usdz package ("x.usdz",
// "a.usdz[b.usdz]"), whose relative paths anchor at the package's root.
bool namesPackage(const std::string& path);

}  // namespace sdg::usd
