#pragma once
// Checks that the files a scene names exist and can be read, before a run
// needs them: meshes and textures of prims, and the file variables of
// behaviors (asset, asset[] and comma-separated lists, marked by their
// spec's FileKind). Existence, readability and a format sdgbehave reads are
// checked: a mesh by its extension and first bytes (one table entry per
// format, see file_check.cpp), an image by its header; nothing is decoded,
// so `validate` stays fast. With a confined resolver (the studio's), a file
// outside the asset roots is a problem of its own and is never opened.
//
// Isaac Sim's own defaults (textureRandomizer's textures:csv and
// volumeStackRandomizer's assets:csv name "/Isaac/..." files) are used only
// when an Isaac asset root is configured; otherwise an entry that the user
// did not write is left out, with one warning per process saying how to
// supply the root.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "core/diagnostics.h"
#include "stage/behavior_spec.h"
#include "stage/stage.h"

namespace sdg {

// The file entries `attr` names (its spec says it names files), in order:
// each item of an asset[], the comma-separated entries of a string. Unusable
// Isaac defaults (see above) are left out; `owner` names the attribute in
// the warning.
std::vector<std::string> fileEntriesOf(const Attribute& attr, const AttributeSpec& spec, const AssetResolver& resolver,
                                       const std::string& owner);

// Why `entry` cannot be used as a file of `kind` (a URL, a format sdgbehave
// cannot read, not found with every place searched, unreadable), or nullopt
// when it resolves to a readable file. A mesh entry's '#label' or
// '#submesh' suffix is not part of the file name.
std::optional<std::string> fileProblem(const std::string& entry, FileKind kind, const AssetResolver& resolver);

// "mesh", "texture" or "file", for messages.
const char* fileKindNoun(FileKind kind);

// Calls `visit` for every file entry the stage's prims and attached behaviors
// name (the entries checkStageFiles checks), in traversal order. `owner` is
// "<prim path>.<attribute>"; `kind` is FileKind::Any where the spec says
// nothing narrower.
using StageFileVisitor = std::function<void(const Prim& prim, const Attribute& attr, const std::string& owner,
                                            const std::string& entry, FileKind kind)>;
void forEachStageFile(const Stage& stage, const BehaviorCatalog& catalog, const AssetResolver& resolver,
                      const StageFileVisitor& visit);

// The lower-case extensions (".glb") of the files of `kind` sdgbehave reads,
// for listings such as the studio's file suggestions; the check itself
// goes by the bytes for images. Empty for other kinds.
const std::vector<std::string>& readableExtensions(FileKind kind);

// Every file the stage's prims and attached behaviors name; each problem is
// reported at the attribute that names the file (or its prim).
void checkStageFiles(const Stage& stage, const BehaviorCatalog& catalog, const AssetResolver& resolver,
                     Diagnostics& diag);

}  // namespace sdg
