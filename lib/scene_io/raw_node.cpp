#include "scene_io/raw_node.h"

#include <fstream>
#include <sstream>
#include <sys/stat.h>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include "core/diagnostics.h"
#include "core/text.h"

namespace sdg {

RawNode::RawNode() = default;
RawNode::~RawNode() = default;
RawNode::RawNode(const RawNode&) = default;
RawNode::RawNode(RawNode&&) noexcept = default;
RawNode& RawNode::operator=(const RawNode&) = default;
RawNode& RawNode::operator=(RawNode&&) noexcept = default;

const RawNode* RawNode::find(std::string_view key) const {
  for (const auto& [k, v] : entries)
    if (k.isScalar() && k.scalar == key) return &v;
  return nullptr;
}

std::string RawNode::describe() const {
  switch (kind) {
    case Kind::Null: return "nothing (null)";
    case Kind::Map: return "a mapping";
    case Kind::Sequence:
      return "a list of " + std::to_string(items.size()) + (items.size() == 1 ? " item" : " items");
    case Kind::Scalar: return (quoted ? "the string " : "") + text::quote(scalar);
  }
  return {};
}

namespace {
class Converter {
 public:
  Converter(FileName file, int lineOffset, int columnOffset)
      : file_(std::move(file)), lineOffset_(lineOffset), columnOffset_(columnOffset) {}

  RawNode convert(const YAML::Node& node, const SourceLoc& fallback) {
    // Aliases share nodes, so a small document can expand exponentially;
    // counting every visit bounds both memory and time.
    if (++visited_ > kMaxDocumentNodes)
      throw SceneError(locOf(node, fallback),
                       "the document expands to more than " + std::to_string(kMaxDocumentNodes) +
                           " nodes; YAML aliases (*name) that nest this deeply are refused");
    // The parser bounds nesting in the text, but an alias used inside its own
    // anchor (`&a [*a]`) makes a cycle that would recurse here without end.
    if (depth_ >= kMaxDocumentDepth)
      throw SceneError(locOf(node, fallback),
                       "the document nests more than " + std::to_string(kMaxDocumentDepth) +
                           " levels deep, counting through aliases; an alias used inside its own anchor "
                           "(such as `&a [*a]`) nests without end");
    DepthScope scope(depth_);
    RawNode out;
    out.loc = locOf(node, fallback);
    switch (node.Type()) {
      case YAML::NodeType::Undefined:
      case YAML::NodeType::Null: out.kind = RawNode::Kind::Null; break;
      case YAML::NodeType::Scalar:
        // Each alias of a long string copies it: counting nodes alone would
        // let a few KiB of YAML ask for gigabytes.
        textBytes_ += node.Scalar().size();
        if (textBytes_ > kMaxDocumentTextBytes)
          throw SceneError(out.loc, "the document expands to more than " +
                                        std::to_string(kMaxDocumentTextBytes >> 20) +
                                        " MiB of text; YAML aliases (*name) that repeat long values are refused");
        out.kind = RawNode::Kind::Scalar;
        out.scalar = node.Scalar();
        out.quoted = node.Tag() == "!";
        break;
      case YAML::NodeType::Sequence:
        out.kind = RawNode::Kind::Sequence;
        out.items.reserve(node.size());
        for (const YAML::Node& item : node) out.items.push_back(convert(item, out.loc));
        break;
      case YAML::NodeType::Map:
        out.kind = RawNode::Kind::Map;
        for (const auto& kv : node) {
          RawNode key = convert(kv.first, out.loc);
          RawNode value = convert(kv.second, key.loc);
          out.entries.push_back(RawEntry{std::move(key), std::move(value)});
        }
        break;
    }
    return out;
  }

  SourceLoc locOf(const YAML::Node& node, const SourceLoc& fallback) const {
    YAML::Mark mark = node.Mark();
    if (mark.line < 0) return fallback;  // yaml-cpp gives null nodes no position
    return at(mark);
  }

  SourceLoc at(const YAML::Mark& mark) const {
    // yaml-cpp marks are 0-based; editors count from 1.
    int line = mark.line + 1 + lineOffset_;
    int column = mark.column + 1 + (mark.line == 0 ? columnOffset_ : 0);
    return SourceLoc{file_, line, column};
  }

 private:
  struct DepthScope {
    explicit DepthScope(int& depth) : depth_(depth) { ++depth_; }
    ~DepthScope() { --depth_; }
    DepthScope(const DepthScope&) = delete;
    DepthScope& operator=(const DepthScope&) = delete;
    int& depth_;
  };

  FileName file_;
  int lineOffset_;
  int columnOffset_;
  size_t visited_ = 0;
  size_t textBytes_ = 0;
  int depth_ = 0;
};
}  // namespace

RawNode parseYaml(std::string_view text, const std::string& file, int lineOffset, int columnOffset) {
  Converter converter(file, lineOffset, columnOffset);
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    std::string what = e.msg;
    if (dynamic_cast<const YAML::DeepRecursion*>(&e)) what = "the YAML nests too deeply (" + e.msg + ")";
    throw SceneError(converter.at(e.mark), "not valid YAML: " + what);
  } catch (const YAML::Exception& e) {
    throw SceneError(converter.at(e.mark), std::string("cannot read YAML: ") + e.msg);
  }
  return converter.convert(root, SourceLoc{file, 1 + lineOffset, 1 + columnOffset});
}

RawNode parseYamlFile(const std::string& path) {
  SourceLoc fileLoc{path, 0, 0};
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw SceneError(fileLoc, "cannot open the scene file: it does not exist");
  if (S_ISDIR(info.st_mode)) throw SceneError(fileLoc, "cannot open the scene file: it is a directory");
  if (static_cast<size_t>(info.st_size) > kMaxSceneFileBytes)
    throw SceneError(fileLoc, "the scene file is " + std::to_string(info.st_size) +
                                  " bytes; scene files are limited to " + std::to_string(kMaxSceneFileBytes) +
                                  " bytes (keep bulk data in asset files)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(fileLoc, "cannot open the scene file: permission denied or unreadable");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parseYaml(buffer.str(), path);
}

}  // namespace sdg
