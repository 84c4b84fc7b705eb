#include "writers/coco_writer.h"

#include <fstream>
#include <map>
#include <sstream>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "writers/py_json.h"

namespace sdg {

std::vector<uint32_t> encodeRle(const std::vector<uint32_t>& ids, int width, int height, uint32_t id) {
  std::vector<uint32_t> counts;
  bool inside = false;
  uint32_t run = 0;
  for (int x = 0; x < width; ++x)
    for (int y = 0; y < height; ++y) {
      const bool on = ids[size_t(y) * size_t(width) + size_t(x)] == id;
      if (on != inside) {
        counts.push_back(run);
        run = 0;
        inside = on;
      }
      ++run;
    }
  counts.push_back(run);
  return counts;
}

std::string cocoFragment(const std::string& imageFile, int width, int height, const FrameAnnotations& a,
                         const FrameSemantics& semantics, const std::string& taxonomy) {
  using Json = nlohmann::ordered_json;
  Json fragment;
  fragment["file_name"] = imageFile;
  fragment["width"] = width;
  fragment["height"] = height;
  Json annotations = Json::array();
  for (const Box2D& box : a.tight) {
    const SemanticEntity& entity = semantics.entities[box.entity];
    auto label = entity.labels.find(taxonomy);
    if (label == entity.labels.end()) continue;
    Json ann;
    ann["category"] = label->second;
    ann["bbox"] = Json::array({box.xMin, box.yMin, box.xMax - box.xMin + 1, box.yMax - box.yMin + 1});
    Json rle;
    rle["counts"] = encodeRle(a.instanceIds, width, height, entity.instanceId);
    rle["size"] = Json::array({height, width});
    ann["segmentation"] = rle;
    ann["area"] = a.visiblePixels[box.entity];
    ann["prim_path"] = entity.primPath;
    annotations.push_back(std::move(ann));
  }
  fragment["annotations"] = std::move(annotations);
  return fragment.dump();
}

void CocoWriter::encode(const ProductFrame& frame, FrameFiles& out) const {
  const std::string text = cocoFragment(images_.rgbPath(frame.frame, frame.product), frame.passes.width,
                                        frame.passes.height, frame.annotations, frame.scene->semantics, taxonomy_);
  out.parts.push_back({cocoFragmentPath(frame.frame, frame.product), std::vector<uint8_t>(text.begin(), text.end())});
}

void assembleCoco(const std::string& path, const std::string& taxonomy, const std::vector<std::string>& fragmentFiles) {
  using Json = nlohmann::ordered_json;
  std::string images, annotations;
  std::map<std::string, uint32_t> categoryIds;
  std::vector<std::string> categoryOrder;
  uint64_t imageId = 0, annotationId = 0;
  for (const std::string& file : fragmentFiles) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    Json fragment = Json::parse(text.str(), nullptr, false);
    if (!in || fragment.is_discarded() || !fragment.is_object())
      throw RunError("COCO: the fragment " + file + " is missing or corrupt; rerun with --resume to redo its frame");
    Json image;
    image["id"] = ++imageId;
    image["file_name"] = fragment["file_name"];
    image["width"] = fragment["width"];
    image["height"] = fragment["height"];
    images += (images.empty() ? "" : ", ") + pythonJsonDumps(image);
    for (const Json& a : fragment["annotations"]) {
      const std::string name = a["category"].get<std::string>();
      auto [category, fresh] = categoryIds.emplace(name, uint32_t(categoryIds.size() + 1));
      if (fresh) categoryOrder.push_back(name);
      Json ann;
      ann["id"] = ++annotationId;
      ann["image_id"] = imageId;
      ann["category_id"] = category->second;
      ann["bbox"] = a["bbox"];
      ann["segmentation"] = a["segmentation"];
      ann["area"] = a["area"];
      ann["iscrowd"] = 0;
      ann["prim_path"] = a["prim_path"];
      annotations += (annotations.empty() ? "" : ", ") + pythonJsonDumps(ann);
    }
  }
  Json categories = Json::array();
  for (const std::string& name : categoryOrder) {
    Json c;
    c["id"] = categoryIds.at(name);
    c["name"] = name;
    c["supercategory"] = taxonomy;
    categories.push_back(c);
  }
  writeFileAtomic(path, "{\"info\": {\"description\": \"sdgbehave\"}, \"images\": [" + images + "], \"annotations\": [" +
                            annotations + "], \"categories\": " + pythonJsonDumps(categories) + "}");
}

}  // namespace sdg
