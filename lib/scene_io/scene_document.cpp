#include "scene_io/scene_document.h"

#include "scene_io/yaml_events.h"

namespace sdg {

SceneDocument readSceneDocument(const std::string& path) { return SceneDocument{path, parseYamlFile(path)}; }

SceneDocument sceneDocumentFromText(std::string_view yaml, const std::string& name) {
  return SceneDocument{name, parseYaml(yaml, name)};
}

std::vector<DeclaredFile> declaredFiles(const SceneDocument& doc, std::string_view key) {
  std::vector<DeclaredFile> files;
  if (!doc.root.isMap()) return files;
  if (const RawNode* node = doc.root.find(key); node && node->isSequence())
    for (const RawNode& item : node->items)
      if (item.isScalar()) files.push_back({item.scalar, item.loc});
  return files;
}

}  // namespace sdg
