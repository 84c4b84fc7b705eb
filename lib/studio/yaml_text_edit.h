#pragma once
// Edits a scene's YAML text in place, at the locations the loader records,
// so that saving keeps the user's comments, key order and formatting
// everywhere else: a value is replaced where it is written; a new key goes
// into its mapping in that mapping's style (flow `{a: 1}` or block lines at
// the siblings' indentation); a prim that has no entry of its own (one from
// a referenced asset) gets one, as a local override, at the end of prims:.
#include <string>
#include <vector>

namespace sdg::studio {

// One change: `prim` and, under it, the key path (["size"], or
// ["behaviors", "locationRandomizer", "interval"]); `yaml` is the new value
// as YAML flow text.
struct TextEdit {
  std::string prim;
  std::vector<std::string> keys;
  std::string yaml;
};

// The text with the edit applied; std::invalid_argument when the text has
// no `prims:` mapping or the place cannot be edited (e.g. an alias).
std::string applyTextEdit(const std::string& text, const TextEdit& edit);

// Removes prim.keys (e.g. ["behaviors", "rotationRandomizer"]) where the text
// writes it: a flow entry with its comma, a block entry with its lines.
// The text unchanged when it is not written there.
std::string removeTextKey(const std::string& text, const std::string& prim, const std::vector<std::string>& keys);

// A JSON value (from the page) as YAML flow text: numbers, true/false,
// double-quoted strings, [a, b] lists.
std::string yamlFlow(const std::string& json);

// A unified diff of two texts, line by line, with 2 lines of context,
// headed `--- NAME (BEFORE)` and `+++ NAME (AFTER)`.
std::string lineDiff(const std::string& before, const std::string& after, const std::string& name,
                     const std::string& beforeLabel = "on disk", const std::string& afterLabel = "edited");

}  // namespace sdg::studio
