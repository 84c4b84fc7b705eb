#include "studio/yaml_text_edit.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "scene_io/scene_loader.h"

namespace sdg::studio {
namespace {

std::vector<size_t> lineStarts(const std::string& text) {
  std::vector<size_t> starts = {0};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') starts.push_back(i + 1);
  return starts;
}

size_t offsetOf(const std::vector<size_t>& starts, const SourceLoc& loc) {
  if (loc.line < 1 || size_t(loc.line) > starts.size()) throw std::invalid_argument("a location outside the text");
  return starts[size_t(loc.line) - 1] + size_t(std::max(loc.column, 1) - 1);
}

// End (exclusive) of the flow value or scalar that starts at `at`.
size_t valueEnd(const std::string& t, size_t at, bool inFlow) {
  const char c = t[at];
  if (c == '[' || c == '{') {
    int depth = 0;
    for (size_t i = at; i < t.size(); ++i) {
      char d = t[i];
      if (d == '"') {
        for (++i; i < t.size() && t[i] != '"'; ++i)
          if (t[i] == '\\') ++i;
      } else if (d == '\'') {
        for (++i; i < t.size(); ++i)
          if (t[i] == '\'' && !(i + 1 < t.size() && t[i + 1] == '\'')) break;
          else if (t[i] == '\'') ++i;
      } else if (d == '[' || d == '{') {
        ++depth;
      } else if (d == ']' || d == '}') {
        if (--depth == 0) return i + 1;
      }
    }
    throw std::invalid_argument("an unclosed flow collection");
  }
  if (c == '"') {
    for (size_t i = at + 1; i < t.size(); ++i) {
      if (t[i] == '\\') ++i;
      else if (t[i] == '"') return i + 1;
    }
    throw std::invalid_argument("an unclosed string");
  }
  if (c == '\'') {
    for (size_t i = at + 1; i < t.size(); ++i)
      if (t[i] == '\'') {
        if (i + 1 < t.size() && t[i + 1] == '\'') ++i;
        else return i + 1;
      }
    throw std::invalid_argument("an unclosed string");
  }
  size_t i = at;
  while (i < t.size() && t[i] != '\n' && !(inFlow && (t[i] == ',' || t[i] == ']' || t[i] == '}')) &&
         !(t[i] == '#' && i > at && (t[i - 1] == ' ' || t[i - 1] == '\t')))
    ++i;
  while (i > at && (t[i - 1] == ' ' || t[i - 1] == '\t')) --i;
  return i;
}

bool isFlowAt(const std::string& t, size_t at) { return at < t.size() && (t[at] == '{' || t[at] == '['); }

// "key: value", or "key: {next: ...{last: value}}" for the keys still missing.
std::string nestedEntry(const std::vector<std::string>& keys, size_t from, const std::string& yaml) {
  std::string value = yaml;
  for (size_t k = keys.size(); k-- > from + 1;) value = "{" + keys[k] + ": " + value + "}";
  return keys[from] + ": " + value;
}

size_t indentOf(const std::string& t, size_t lineStart) {
  size_t i = lineStart;
  while (i < t.size() && t[i] == ' ') ++i;
  return i - lineStart;
}

// Inserts `entry` into the mapping `map` (flow or block).
std::string insertIntoMap(const std::string& t, const std::vector<size_t>& starts, const RawNode& map,
                          const std::string& entry, bool inFlow) {
  size_t at = offsetOf(starts, map.loc);
  if (isFlowAt(t, at)) {
    size_t close = valueEnd(t, at, true) - 1;  // the '}'
    size_t last = close;
    while (last > at + 1 && (t[last - 1] == ' ' || t[last - 1] == '\n')) --last;
    std::string piece = map.entries.empty() ? entry : ", " + entry;
    return t.substr(0, last) + piece + t.substr(last);
  }
  if (inFlow || map.entries.empty()) throw std::invalid_argument("cannot add a key to this mapping in place");
  // Block style: a new line at the siblings' indentation, after the map's
  // last line (before the next line indented less, comments included).
  const size_t indent = size_t(map.entries.front().key.loc.column - 1);
  size_t line = size_t(map.entries.back().key.loc.line);  // 1-based index of the last key's line
  size_t insertLine = starts.size() + 1;
  for (size_t l = line + 1; l <= starts.size(); ++l) {
    size_t s = starts[l - 1];
    size_t e = t.find('\n', s);
    std::string content = t.substr(s, (e == std::string::npos ? t.size() : e) - s);
    if (content.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (indentOf(t, s) < indent) {
      insertLine = l;
      break;
    }
  }
  // Back over blank lines and the comments that lead into the next section.
  size_t end = insertLine <= starts.size() ? starts[insertLine - 1] : t.size();
  while (insertLine > line + 1) {
    size_t s = starts[insertLine - 2];
    std::string content = t.substr(s, end - s);
    size_t first = content.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && content[first] != '#') break;
    if (first != std::string::npos && indentOf(t, s) >= indent) break;
    --insertLine;
    end = s;
  }
  std::string newline = std::string(indent, ' ') + entry + "\n";
  if (end > 0 && t[end - 1] != '\n') newline = "\n" + newline;
  return t.substr(0, end) + newline + t.substr(end);
}

// Replaces a null value (`key:` with nothing, `~` or `null`) by `flow`.
std::string fillNull(const std::string& t, const std::vector<size_t>& starts, const RawNode& key,
                     const std::string& flow) {
  size_t at = offsetOf(starts, key.loc) + key.scalar.size();
  size_t colon = t.find(':', at);
  if (colon == std::string::npos) throw std::invalid_argument("no ':' after a key");
  size_t v = colon + 1;
  while (v < t.size() && t[v] == ' ') ++v;
  size_t end = v;
  if (t.compare(v, 4, "null") == 0) end = v + 4;
  else if (t.compare(v, 1, "~") == 0) end = v + 1;
  return t.substr(0, colon + 1) + " " + flow + t.substr(end);
}

}  // namespace

std::string applyTextEdit(const std::string& text, const TextEdit& edit) {
  if (edit.keys.empty()) throw std::invalid_argument("nothing to edit");
  SceneDocument doc = sceneDocumentFromText(text, "studio-edit");
  const std::vector<size_t> starts = lineStarts(text);
  const RawNode* prims = doc.root.isMap() ? doc.root.find("prims") : nullptr;
  if (!prims || !prims->isMap()) throw std::invalid_argument("the scene has no prims: mapping");
  const RawEntry* primEntry = nullptr;
  for (const RawEntry& e : prims->entries)
    if (e.key.scalar == edit.prim) primEntry = &e;
  if (!primEntry) {
    // A prim from a referenced asset: its override gets an entry of its own.
    std::string entry = edit.prim + ": {" + nestedEntry(edit.keys, 0, edit.yaml) + "}";
    return insertIntoMap(text, starts, *prims, entry, false);
  }
  const RawEntry* current = primEntry;
  bool inFlow = false;
  for (size_t k = 0; k < edit.keys.size(); ++k) {
    const RawNode& value = current->value;
    if (value.isNull()) return fillNull(text, starts, current->key, "{" + nestedEntry(edit.keys, k, edit.yaml) + "}");
    if (!value.isMap()) throw std::invalid_argument(edit.keys[k] + ": the place to edit is not a mapping");
    inFlow = inFlow || isFlowAt(text, offsetOf(starts, value.loc));
    const RawEntry* next = nullptr;
    for (const RawEntry& e : value.entries)
      if (e.key.scalar == edit.keys[k]) next = &e;
    if (!next) return insertIntoMap(text, starts, value, nestedEntry(edit.keys, k, edit.yaml), inFlow);
    current = next;
  }
  // The key exists: replace its value where it is written.
  const RawNode& value = current->value;
  if (value.isNull()) return fillNull(text, starts, current->key, edit.yaml);
  size_t at = offsetOf(starts, value.loc);
  if ((value.isMap() || value.isSequence()) && !isFlowAt(text, at))
    throw std::invalid_argument(edit.keys.back() + " is written as a block collection; edit it in the file");
  size_t end = valueEnd(text, at, inFlow);
  return text.substr(0, at) + edit.yaml + text.substr(end);
}

std::string removeTextKey(const std::string& text, const std::string& prim, const std::vector<std::string>& keys) {
  SceneDocument doc = sceneDocumentFromText(text, "studio-edit");
  const std::vector<size_t> starts = lineStarts(text);
  const RawNode* prims = doc.root.isMap() ? doc.root.find("prims") : nullptr;
  if (!prims || !prims->isMap() || keys.empty()) return text;
  const RawNode* map = nullptr;
  for (const RawEntry& e : prims->entries)
    if (e.key.scalar == prim) map = &e.value;
  bool inFlow = false;
  for (size_t k = 0; map && k + 1 < keys.size(); ++k) {
    if (!map->isMap()) return text;
    inFlow = inFlow || isFlowAt(text, offsetOf(starts, map->loc));
    const RawNode* next = nullptr;
    for (const RawEntry& e : map->entries)
      if (e.key.scalar == keys[k]) next = &e.value;
    map = next;
  }
  if (!map || !map->isMap()) return text;
  const size_t mapAt = offsetOf(starts, map->loc);
  const bool flow = inFlow || isFlowAt(text, mapAt);
  for (size_t i = 0; i < map->entries.size(); ++i) {
    const RawEntry& e = map->entries[i];
    if (e.key.scalar != keys.back()) continue;
    size_t from = offsetOf(starts, e.key.loc);
    if (flow) {
      size_t valueAt = e.value.isNull() ? from + e.key.scalar.size() + 1 : offsetOf(starts, e.value.loc);
      size_t to = e.value.isNull() ? valueAt : valueEnd(text, valueAt, true);
      // Take the comma after it, else the one before it.
      size_t after = text.find_first_not_of(" ", to);
      if (after != std::string::npos && text[after] == ',') {
        to = text.find_first_not_of(" ", after + 1);
      } else {
        size_t before = text.find_last_not_of(" ", from - 1);
        if (before != std::string::npos && text[before] == ',') from = before;
      }
      return text.substr(0, from) + text.substr(to);
    }
    // Block: the key's line through the last line indented more than it.
    const size_t line = size_t(e.key.loc.line);
    const size_t indent = size_t(e.key.loc.column - 1);
    size_t endLine = line + 1;
    while (endLine <= starts.size()) {
      size_t s = starts[endLine - 1];
      size_t eol = text.find('\n', s);
      std::string content = text.substr(s, (eol == std::string::npos ? text.size() : eol) - s);
      if (content.find_first_not_of(" \t\r") != std::string::npos && indentOf(text, s) <= indent) break;
      ++endLine;
    }
    size_t begin = starts[line - 1];
    size_t end = endLine <= starts.size() ? starts[endLine - 1] : text.size();
    return text.substr(0, begin) + text.substr(end);
  }
  return text;
}

std::string yamlFlow(const std::string& json) {
  nlohmann::json j = nlohmann::json::parse(json);
  std::function<std::string(const nlohmann::json&)> emit = [&](const nlohmann::json& v) -> std::string {
    if (v.is_array()) {
      std::string out = "[";
      for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + emit(v[i]);
      return out + "]";
    }
    if (v.is_object()) {
      std::string out = "{";
      bool first = true;
      for (const auto& [k, x] : v.items()) {
        // A key goes into the text as it is: only plain names.
        if (k.empty() || k.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_:") !=
                             std::string::npos)
          throw std::invalid_argument("a mapping key in a value must be a plain name, found \"" + k + "\"");
        out += (first ? "" : ", ") + k + ": " + emit(x);
        first = false;
      }
      return out + "}";
    }
    if (v.is_number_float()) {
      std::string s = v.dump();
      if (s.find_first_of(".eE") == std::string::npos) s += ".0";
      return s;
    }
    return v.dump();  // ints, bools, null, strings (JSON strings are YAML double-quoted strings)
  };
  return emit(j);
}

std::string lineDiff(const std::string& before, const std::string& after, const std::string& name,
                     const std::string& beforeLabel, const std::string& afterLabel) {
  if (before == after) return {};
  auto split = [](const std::string& s) {
    std::vector<std::string> lines;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  };
  const std::vector<std::string> a = split(before), b = split(after);
  // Longest common subsequence of lines (scene files are small).
  std::vector<std::vector<uint32_t>> lcs(a.size() + 1, std::vector<uint32_t>(b.size() + 1, 0));
  for (size_t i = a.size(); i-- > 0;)
    for (size_t j = b.size(); j-- > 0;)
      lcs[i][j] = a[i] == b[j] ? lcs[i + 1][j + 1] + 1 : std::max(lcs[i + 1][j], lcs[i][j + 1]);
  struct Line {
    char tag;
    std::string text;
  };
  std::vector<Line> ops;
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (i < a.size() && j < b.size() && a[i] == b[j]) ops.push_back({' ', a[i++]}), ++j;
    else if (i < a.size() && (j == b.size() || lcs[i + 1][j] >= lcs[i][j + 1])) ops.push_back({'-', a[i++]});
    else ops.push_back({'+', b[j++]});
  }
  std::string out = "--- " + name + " (" + beforeLabel + ")\n+++ " + name + " (" + afterLabel + ")\n";
  constexpr size_t kContext = 2;
  for (size_t k = 0; k < ops.size(); ++k) {
    bool near = false;
    for (size_t d = (k >= kContext ? k - kContext : 0); d < std::min(ops.size(), k + kContext + 1); ++d)
      near = near || ops[d].tag != ' ';
    if (near) out += std::string(1, ops[k].tag) + ops[k].text + "\n";
    else if (k > 0 && out.back() == '\n' && out.compare(out.size() - 4, 4, "...\n") != 0) out += "...\n";
  }
  return out;
}

}  // namespace sdg::studio
