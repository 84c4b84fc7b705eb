#include "assets/file_check.h"

#include "assets/mesh_loader.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "assets/image.h"
#include "assets/mesh_loader.h"
#include "assets/packaged_image.h"
#include "core/git_lfs.h"
#include "core/log.h"
#include "core/text.h"
#include "stage/prim_types.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

bool namesFiles(const AttributeSpec& spec) {
  if (spec.type == ValueType::Asset || spec.type == ValueType::AssetArray) return true;
  return spec.type == ValueType::String && spec.files != FileKind::None;
}

std::string lowerExtension(const std::string& file) {
  std::string ext = fs::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// ---- Mesh formats: what the loader (assimp) reads, told apart by the file's
// extension and then its first bytes, so a wrong kind of file (a PNG or a
// password file named as a mesh) is a scene error and not a failed run. One
// entry per format: a format becomes readable with one more entry.

constexpr size_t kHeadBytes = 4096;  // how much of a mesh file the check reads

std::string_view skipBomAndSpace(std::string_view head) {
  if (head.starts_with("\xEF\xBB\xBF")) head.remove_prefix(3);
  while (!head.empty() && std::isspace(static_cast<unsigned char>(head.front()))) head.remove_prefix(1);
  return head;
}

// Up to `n` first bytes of the stream.
std::string readHead(std::istream& in, size_t n) {
  std::string head(n, '\0');
  in.read(head.data(), std::streamsize(n));
  head.resize(size_t(in.gcount()));
  return head;
}

bool looksLikeText(std::string_view head) { return head.find('\0') == std::string_view::npos; }

// The first `n` characters of a line, printable, for messages.
std::string excerpt(std::string_view line) {
  std::string out;
  for (char c : line.substr(0, 40)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return text::quote(out);
}

// Each sniff says why `head` (the first bytes of a file of `size` bytes)
// is not the format, or "" when it is.
using Sniff = std::string (*)(std::string_view head, uint64_t size);

std::string sniffGlb(std::string_view head, uint64_t) {
  return head.starts_with("glTF") ? "" : "not a binary glTF: it does not start with 'glTF'";
}

// A USD layer or package (read by scene_io/usd_mesh_asset.cpp): usda text,
// a crate file, or a zip.
std::string sniffUsd(std::string_view head, uint64_t) {
  if (head.starts_with("#usda") || head.starts_with("PXR-USDC") || head.starts_with(std::string_view("PK\x03\x04", 4)))
    return "";
  return "not a USD file: it starts with neither '#usda' (text), 'PXR-USDC' (crate) nor a zip header (usdz)";
}

std::string sniffGltf(std::string_view head, uint64_t) {
  return looksLikeText(head) && skipBomAndSpace(head).starts_with("{") ? "" : "not a glTF (JSON) file: it does not start with '{'";
}

std::string sniffObj(std::string_view head, uint64_t size) {
  static const std::array<std::string_view, 20> kKeywords = {"v", "vt", "vn", "vp", "f", "l", "p", "o", "g", "s",
                                                             "mtllib", "usemtl", "cstype", "deg", "curv", "curv2",
                                                             "surf", "parm", "end", "lod"};
  if (!looksLikeText(head)) return "not a Wavefront OBJ: it is not text";
  size_t lineNumber = 0;
  while (!head.empty()) {
    const size_t end = head.find('\n');
    // The last line the head cuts off is not judged.
    if (end == std::string_view::npos && size > kHeadBytes) break;
    std::string_view line = head.substr(0, end);
    head.remove_prefix(end == std::string_view::npos ? head.size() : end + 1);
    ++lineNumber;
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front()))) line.remove_prefix(1);
    if (line.empty() || line.front() == '#') continue;
    const std::string_view keyword = line.substr(0, line.find_first_of(" \t\r"));
    if (std::find(kKeywords.begin(), kKeywords.end(), keyword) == kKeywords.end())
      return "not a Wavefront OBJ: line " + std::to_string(lineNumber) + " starts with " + excerpt(line);
  }
  return "";
}

std::string sniffFbx(std::string_view head, uint64_t) {
  if (head.starts_with("Kaydara FBX Binary")) return "";
  // An ASCII FBX starts with '; FBX ...' comments or its header section.
  std::string_view text = skipBomAndSpace(head);
  if (looksLikeText(head) && (text.starts_with(";") || text.starts_with("FBXHeaderExtension"))) return "";
  return "not an FBX: neither 'Kaydara FBX Binary' nor an ASCII FBX's '; FBX' at its start";
}

std::string sniffPly(std::string_view head, uint64_t) {
  return head.starts_with("ply\n") || head.starts_with("ply\r\n") ? "" : "not a PLY: it does not start with 'ply'";
}

std::string sniffStl(std::string_view head, uint64_t size) {
  // Binary: an 80-byte header, a triangle count, 50 bytes per triangle.
  if (size >= 84 && head.size() >= 84) {
    uint32_t triangles = 0;
    std::memcpy(&triangles, head.data() + 80, 4);
    if (size == 84 + 50 * uint64_t(triangles)) return "";
  }
  std::string_view text = skipBomAndSpace(head);
  if (looksLikeText(head) && text.size() >= 5 && std::equal(text.begin(), text.begin() + 5, "solid", [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) == b;
      }))
    return "";
  return "not an STL: neither text starting with 'solid' nor a binary STL (84 + 50 bytes per triangle)";
}

std::string sniffCollada(std::string_view head, uint64_t) {
  return looksLikeText(head) && skipBomAndSpace(head).starts_with("<") && head.find("<COLLADA") != std::string_view::npos
             ? ""
             : "not a COLLADA (.dae) file: no <COLLADA element at its start";
}

struct MeshFormat {
  std::vector<std::string> extensions;  // lower case, with the dot
  Sniff sniff;                          // nullptr: a format the loader cannot read
  const char* refusal;                  // why not, when it cannot
};

const std::vector<MeshFormat>& meshFormats() {
  static const std::vector<MeshFormat> kFormats = {
      {{".obj"}, sniffObj, nullptr},
      {{".glb"}, sniffGlb, nullptr},
      {{".gltf"}, sniffGltf, nullptr},
      {{".fbx"}, sniffFbx, nullptr},
      {{".ply"}, sniffPly, nullptr},
      {{".stl"}, sniffStl, nullptr},
      {{".dae"}, sniffCollada, nullptr},
      {{".usd", ".usda", ".usdc", ".usdz"}, sniffUsd, nullptr},
  };
  return kFormats;
}

const MeshFormat* meshFormatFor(const std::string& ext) {
  for (const MeshFormat& f : meshFormats())
    if (std::find(f.extensions.begin(), f.extensions.end(), ext) != f.extensions.end()) return &f;
  return nullptr;
}

// Whether the first bytes of `path` are those of the mesh format its
// extension names.
std::optional<std::string> meshHeaderProblem(const std::string& file, const std::string& path, const MeshFormat& format) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kHeadBytes, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  std::error_code ec;
  const uint64_t size = fs::file_size(path, ec);
  const std::string why = format.sniff(head, ec ? head.size() : size);
  if (why.empty()) return std::nullopt;
  return "mesh " + text::quote(file) + " (" + path + "): " + why;
}

// "texture 'a.png' (/abs/a.png): why" from a reader's RunError, which
// starts with the path: it is said once.
std::string readProblem(const char* noun, const std::string& file, const std::string& path, const RunError& e) {
  std::string why = e.what();
  if (why.starts_with(path + ": ")) why.erase(0, path.size() + 2);
  return std::string(noun) + " " + text::quote(file) + " (" + path + "): " + why;
}

// A USD mesh asset is composed and its meshes read (they are small, and a
// broken layer should fail `validate`, at its file:line:col, not the run).
std::optional<std::string> usdMeshProblem(const std::string& file, const std::string& path, const MeshFormat& format) {
  if (std::optional<std::string> header = meshHeaderProblem(file, path, format)) return header;
  try {
    loadMeshFile(path);
    return std::nullopt;
  } catch (const RunError& e) {
    return readProblem("mesh", file, path, e);
  }
}

// Whether the image's header reads: any format OpenImageIO reads, within
// the size limits. Only the header is read, so `validate` stays fast.
std::optional<std::string> imageProblem(const std::string& file, const std::string& path) {
  try {
    readImageHeader(path);
    return std::nullopt;
  } catch (const RunError& e) {
    return readProblem("texture", file, path, e);
  }
}

void warnIsaacDefaultsSkipped(const std::string& owner) {
  static std::atomic<bool> warned{false};
  if (warned.exchange(true)) return;
  log::warn(owner + ": Isaac Sim's default assets (/Isaac/...) are skipped: no Isaac asset root is set. To use "
                    "them, point --isaac-assets DIR, SDGBEHAVE_ISAAC_ASSETS or the scene's isaac_assets: at a local "
                    "copy of Isaac Sim's asset pack (the folder that holds Isaac/)");
}

}  // namespace

const char* fileKindNoun(FileKind kind) {
  switch (kind) {
    case FileKind::Mesh: return "mesh";
    case FileKind::Image: return "texture";
    default: return "file";
  }
}

const std::vector<std::string>& readableExtensions(FileKind kind) {
  static const std::vector<std::string> kMesh = [] {
    std::vector<std::string> out;
    for (const MeshFormat& f : meshFormats())
      if (f.sniff) out.insert(out.end(), f.extensions.begin(), f.extensions.end());
    return out;
  }();
  // What the image module reads (image.h); the header decides, not the name.
  static const std::vector<std::string> kImage = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".exr",
                                                  ".hdr", ".tga", ".bmp",  ".webp"};
  static const std::vector<std::string> kNone;
  return kind == FileKind::Mesh ? kMesh : kind == FileKind::Image ? kImage : kNone;
}

std::vector<std::string> fileEntriesOf(const Attribute& attr, const AttributeSpec& spec, const AssetResolver& resolver,
                                       const std::string& owner) {
  std::vector<std::string> entries;
  switch (attr.value.type()) {
    case ValueType::Asset:
      if (!attr.value.get<std::string>().empty()) entries.push_back(attr.value.get<std::string>());
      break;
    case ValueType::AssetArray:
      for (const std::string& s : attr.value.get<std::vector<std::string>>())
        if (!s.empty()) entries.push_back(s);
      break;
    case ValueType::String:
      if (spec.files != FileKind::None) entries = text::splitCsv(attr.value.get<std::string>());
      break;
    default: break;
  }
  // A default nobody wrote that points into Isaac's asset pack, while no
  // local copy of that pack is configured, would fail every run of every
  // scene that does not override it: leave it out and say how to get it.
  if (!attr.loc.known() && resolver.isaacRoot().empty()) {
    size_t before = entries.size();
    std::erase_if(entries, [](const std::string& e) { return isIsaacAssetPath(e); });
    if (entries.size() != before) warnIsaacDefaultsSkipped(owner);
  }
  return entries;
}

std::optional<std::string> fileProblem(const std::string& entry, FileKind kind, const AssetResolver& resolver) {
  std::string file = entry;
  if (kind == FileKind::Mesh) file = file.substr(0, file.rfind('#'));
  const std::string noun = fileKindNoun(kind);
  if (file.find("://") != std::string::npos)
    return noun + " " + text::quote(file) + " is a URL; sdgbehave reads local files only";
  const MeshFormat* mesh = nullptr;
  if (kind == FileKind::Mesh) {
    mesh = meshFormatFor(lowerExtension(file));
    if (!mesh)
      return noun + " " + text::quote(file) + " is not a mesh format sdgbehave reads; mesh files end in " +
             text::join(readableExtensions(FileKind::Mesh), ", ");
    if (!mesh->sniff) return noun + " " + text::quote(file) + " " + mesh->refusal;
  }
  if (kind == FileKind::Image && isPackagedAssetPath(file)) {  // a texture of a .usdz stage: decode it
    try {
      std::vector<uint8_t> bytes = readPackagedAsset(file, resolver);
      decodeImageRgba8(bytes.data(), bytes.size(), file, TextureData::Linear);
      return std::nullopt;
    } catch (const RunError& e) {
      return noun + " " + text::quote(file) + ": " + e.what();
    }
  }
  std::optional<std::string> path = resolver.resolve(file);
  if (!path && resolver.leavesRoots(file))
    return noun + " " + text::quote(file) + " is outside the scene's folder and asset roots (" +
           text::join(resolver.roots(), ", ") + "), where the studio opens no file; copy it below one of them or " +
           "start the studio with --asset-root naming its folder";
  if (!path) {
    std::string why = noun + " " + text::quote(file) + " not found; " + resolver.describeSearch(file);
    if (isIsaacAssetPath(file) && resolver.isaacRoot().empty())
      why += " (Isaac Sim asset paths resolve against --isaac-assets DIR, SDGBEHAVE_ISAAC_ASSETS or the scene's "
             "isaac_assets:, and none is set)";
    return why;
  }
  std::ifstream probe(*path, std::ios::binary);
  if (!probe || probe.peek() == std::ifstream::traits_type::eof())
    return noun + " " + text::quote(file) + " (" + *path + ") cannot be read" + (probe ? ": it is empty" : "");
  if (std::string head = readHead(probe, 64); isGitLfsPointer(head))
    return noun + " " + text::quote(file) + ": " +
           gitLfsPointerMessage(*path, kind == FileKind::Image  ? "an image"
                                       : kind == FileKind::Mesh ? "a mesh"
                                                                : "the file it stands for");
  if (kind == FileKind::Image) return imageProblem(file, *path);
  if (mesh && mesh->sniff == sniffUsd) return usdMeshProblem(file, *path, *mesh);
  if (mesh) return meshHeaderProblem(file, *path, *mesh);
  return std::nullopt;
}

void forEachStageFile(const Stage& stage, const BehaviorCatalog& catalog, const AssetResolver& resolver,
                      const StageFileVisitor& visit) {
  auto visitAttribute = [&](const Prim& prim, const std::string& name, const AttributeSpec& spec) {
    const Attribute* attr = prim.findAttribute(name);
    if (!attr) return;
    const std::string owner = prim.path() + "." + name;
    const FileKind kind = spec.files == FileKind::None ? FileKind::Any : spec.files;
    for (const std::string& entry : fileEntriesOf(*attr, spec, resolver, owner)) visit(prim, *attr, owner, entry, kind);
  };
  stage.traverse([&](const Prim& prim) {
    for (const AttributeSpec& spec : primTypeInfo(prim.type()).attributes)
      if (namesFiles(spec)) visitAttribute(prim, spec.name, spec);
    for (const std::string& behavior : prim.behaviors())
      if (const BehaviorSpec* b = catalog.find(behavior))
        for (const AttributeSpec& spec : b->variables)
          if (namesFiles(spec)) visitAttribute(prim, exposedAttributeName(behavior, spec.name), spec);
  });
}

void checkStageFiles(const Stage& stage, const BehaviorCatalog& catalog, const AssetResolver& resolver,
                     Diagnostics& diag) {
  forEachStageFile(stage, catalog, resolver,
                   [&](const Prim& prim, const Attribute& attr, const std::string& owner, const std::string& entry,
                       FileKind kind) {
                     if (std::optional<std::string> problem = fileProblem(entry, kind, resolver))
                       diag.error(attr.loc.known() ? attr.loc : prim.loc(), owner + ": " + *problem);
                   });
}

}  // namespace sdg
