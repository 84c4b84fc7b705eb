#include "scene_io/yaml_events.h"

#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <istream>
#include <sstream>
#include <streambuf>
#include <vector>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include "core/diagnostics.h"

namespace sdg {
namespace {

// Lets yaml-cpp read the caller's text in place instead of a copy.
class TextBuffer : public std::streambuf {
 public:
  explicit TextBuffer(std::string_view text) {
    char* begin = const_cast<char*>(text.data());  // read only: no put area is set
    setg(begin, begin, begin + text.size());
  }
};

// What an anchor stands for, and what repeating it costs.
struct Anchored {
  RawNode node;
  size_t nodes = 0;      // nodes in the subtree
  size_t textBytes = 0;  // scalar text in the subtree
  int height = 0;        // levels, the node itself included
  bool complete = false;
};

class RawNodeBuilder final : public YAML::EventHandler {
 public:
  explicit RawNodeBuilder(TextOrigin origin) : origin_(std::move(origin)) {}

  SourceLoc at(const YAML::Mark& mark) const {
    // yaml-cpp marks are 0-based; editors count from 1.
    int line = mark.line + 1 + origin_.lineOffset;
    int column = mark.column + 1 + (mark.line == 0 ? origin_.columnOffset : 0);
    return SourceLoc{origin_.file, line, column};
  }

  RawNode takeRoot() {
    if (!haveRoot_) {  // an empty document
      root_.loc = SourceLoc{origin_.file, 1 + origin_.lineOffset, 1 + origin_.columnOffset};
    }
    return std::move(root_);
  }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    RawNode node;
    node.loc = locOf(mark);
    countNodes(1, node.loc);
    finish(std::move(node), anchor, 0, 0, 1);
  }

  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    RawNode node;
    node.loc = locOf(mark);
    countNodes(1, node.loc);
    countText(value.size(), node.loc);
    node.kind = RawNode::Kind::Scalar;
    node.scalar = value;
    node.quoted = tag == "!";  // yaml-cpp's tag for a quoted scalar
    finish(std::move(node), anchor, 1, value.size(), 1);
  }

  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const SourceLoc loc = locOf(mark);
    // yaml-cpp has refused aliases to unknown names, so an anchor that is
    // not complete is one the alias sits inside of.
    if (anchor >= anchors_.size() || !anchors_[anchor].complete)
      throw SceneError(loc, "an alias used inside its own anchor (such as `&a [*a]`) would repeat without end");
    const Anchored& source = anchors_[anchor];
    if (int(open_.size()) + source.height > kMaxDocumentDepth) throw tooDeep(loc);
    countNodes(source.nodes, loc);
    countText(source.textBytes, loc);
    finish(RawNode(source.node), 0, source.nodes, source.textBytes, source.height);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor, RawNode::Kind::Sequence);
  }
  void OnSequenceEnd() override { close(); }

  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, anchor, RawNode::Kind::Map);
  }
  void OnMapEnd() override { close(); }

 private:
  struct OpenNode {
    RawNode node;
    YAML::anchor_t anchor = 0;
    bool haveKey = false;
    RawNode key;  // a map's key, waiting for its value
    size_t nodesAtStart = 0;
    size_t textAtStart = 0;
    int childHeight = 0;
  };

  // yaml-cpp gives some implied nulls no position; they take their key's,
  // or their container's.
  SourceLoc locOf(const YAML::Mark& mark) const {
    if (mark.line >= 0) return at(mark);
    if (open_.empty()) return SourceLoc{origin_.file, 1 + origin_.lineOffset, 1 + origin_.columnOffset};
    const OpenNode& parent = open_.back();
    return parent.haveKey ? parent.key.loc : parent.node.loc;
  }

  SceneError tooDeep(const SourceLoc& loc) const {
    return SceneError(loc, "the document nests more than " + std::to_string(kMaxDocumentDepth) +
                               " levels deep, counting through aliases");
  }

  void countNodes(size_t n, const SourceLoc& loc) {
    nodes_ += n;
    if (nodes_ > kMaxDocumentNodes)
      throw SceneError(loc, "the document has more than " + std::to_string(kMaxDocumentNodes) +
                                " nodes, counting the copies YAML anchors (&name) and aliases (*name) make; keep bulk data in "
                                "asset files");
  }

  void countText(size_t bytes, const SourceLoc& loc) {
    // Each alias of a long string copies it: counting nodes alone would
    // let a few KiB of YAML ask for gigabytes.
    textBytes_ += bytes;
    if (textBytes_ > kMaxDocumentTextBytes)
      throw SceneError(loc, "the document expands to more than " + std::to_string(kMaxDocumentTextBytes >> 20) +
                                " MiB of text; YAML aliases (*name) that repeat long values are refused");
  }

  void open(const YAML::Mark& mark, YAML::anchor_t anchor, RawNode::Kind kind) {
    OpenNode o;
    o.node.kind = kind;
    o.node.loc = locOf(mark);
    countNodes(1, o.node.loc);
    if (int(open_.size()) + 1 > kMaxDocumentDepth) throw tooDeep(o.node.loc);
    o.anchor = anchor;
    o.nodesAtStart = nodes_ - 1;
    o.textAtStart = textBytes_;
    open_.push_back(std::move(o));
  }

  void close() {
    OpenNode o = std::move(open_.back());
    open_.pop_back();
    finish(std::move(o.node), o.anchor, nodes_ - o.nodesAtStart, textBytes_ - o.textAtStart, 1 + o.childHeight);
  }

  // A complete node goes into its anchor's slot (when it has one) and into
  // its container, or becomes the root.
  void finish(RawNode node, YAML::anchor_t anchor, size_t nodes, size_t textBytes, int height) {
    if (anchor != 0) {
      // The copy kept for later aliases counts too: anchors nested inside
      // anchors would otherwise copy a subtree once per level, uncounted.
      countNodes(nodes, node.loc);
      countText(textBytes, node.loc);
      if (anchor >= anchors_.size()) anchors_.resize(anchor + 1);
      anchors_[anchor] = Anchored{node, nodes, textBytes, height, true};
    }
    if (open_.empty()) {
      root_ = std::move(node);
      haveRoot_ = true;
      return;
    }
    OpenNode& parent = open_.back();
    parent.childHeight = std::max(parent.childHeight, height);
    if (parent.node.kind == RawNode::Kind::Sequence) {
      parent.node.items.push_back(std::move(node));
    } else if (!parent.haveKey) {
      parent.key = std::move(node);
      parent.haveKey = true;
    } else {
      parent.node.entries.push_back(RawEntry{std::move(parent.key), std::move(node)});
      parent.key = RawNode();
      parent.haveKey = false;
    }
  }

  TextOrigin origin_;
  std::vector<OpenNode> open_;
  std::vector<Anchored> anchors_;  // by yaml-cpp's anchor id, from 1
  RawNode root_;
  bool haveRoot_ = false;
  size_t nodes_ = 0;
  size_t textBytes_ = 0;
};

}  // namespace

RawNode buildRawNodes(std::string_view text, const TextOrigin& origin) {
  TextBuffer buffer(text);
  std::istream in(&buffer);
  RawNodeBuilder builder(origin);
  try {
    YAML::Parser parser(in);
    parser.HandleNextDocument(builder);
  } catch (const YAML::ParserException& e) {
    std::string what = e.msg;
    if (dynamic_cast<const YAML::DeepRecursion*>(&e)) what = "the YAML nests too deeply (" + e.msg + ")";
    throw SceneError(builder.at(e.mark), "not valid YAML: " + what);
  } catch (const YAML::Exception& e) {
    throw SceneError(builder.at(e.mark), std::string("cannot read YAML: ") + e.msg);
  }
  return builder.takeRoot();
}

RawNode parseYaml(std::string_view text, const std::string& file, int lineOffset, int columnOffset) {
  return buildRawNodes(text, TextOrigin{file, lineOffset, columnOffset});
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
