#include "writers/coco_writer.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "writers/py_json.h"

namespace sdg {

namespace {
std::string streamPath(const std::string& dir, const std::string& name, const char* part) {
  return (std::filesystem::path(dir) / (name + "." + part + ".partial")).string();
}

std::FILE* openStream(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw RunError("cannot write " + path + ": " + std::strerror(errno));
  return f;
}

std::string readAll(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw RunError("cannot read " + path + ": " + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
  std::fclose(f);
  return text;
}
}  // namespace

CocoWriter::CocoWriter(std::string outDir, std::string fileName, std::string taxonomy)
    : outDir_(std::move(outDir)), fileName_(std::move(fileName)), taxonomy_(std::move(taxonomy)) {
  images_ = openStream(streamPath(outDir_, fileName_, "images"));
  annotations_ = openStream(streamPath(outDir_, fileName_, "annotations"));
}

CocoWriter::~CocoWriter() {
  if (images_) std::fclose(images_);
  if (annotations_) std::fclose(annotations_);
}

std::vector<uint32_t> CocoWriter::encodeRle(const std::vector<uint32_t>& ids, int width, int height, uint32_t id) {
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

void CocoWriter::append(std::FILE* file, const std::string& text, bool& first) {
  std::string chunk = (first ? "" : ", ") + text;
  first = false;
  if (std::fwrite(chunk.data(), 1, chunk.size(), file) != chunk.size())
    throw RunError("cannot write the COCO stream in " + outDir_ + ": " + std::strerror(errno));
}

void CocoWriter::addFrame(const std::string& imageFile, int width, int height, const FrameAnnotations& a,
                          const FrameSemantics& semantics) {
  using Json = nlohmann::ordered_json;
  const uint64_t imageId = nextImage_++;
  Json image;
  image["id"] = imageId;
  image["file_name"] = imageFile;
  image["width"] = width;
  image["height"] = height;
  append(images_, pythonJsonDumps(image), firstImage_);
  for (const Box2D& box : a.tight) {
    const SemanticEntity& entity = semantics.entities[box.entity];
    auto label = entity.labels.find(taxonomy_);
    if (label == entity.labels.end()) continue;
    auto [category, fresh] = categories_.emplace(label->second, uint32_t(categories_.size() + 1));
    if (fresh) categoryOrder_.push_back(label->second);
    Json ann;
    ann["id"] = nextAnnotation_++;
    ann["image_id"] = imageId;
    ann["category_id"] = category->second;
    ann["bbox"] = Json::array({box.xMin, box.yMin, box.xMax - box.xMin + 1, box.yMax - box.yMin + 1});
    Json rle;
    rle["counts"] = encodeRle(a.instanceIds, width, height, entity.instanceId);
    rle["size"] = Json::array({height, width});
    ann["segmentation"] = rle;
    ann["area"] = a.visiblePixels[box.entity];
    ann["iscrowd"] = 0;
    ann["prim_path"] = entity.primPath;
    append(annotations_, pythonJsonDumps(ann), firstAnnotation_);
  }
}

void CocoWriter::finish() {
  using Json = nlohmann::ordered_json;
  if (std::fclose(images_) != 0 || std::fclose(annotations_) != 0) {
    images_ = annotations_ = nullptr;
    throw RunError("cannot write the COCO streams in " + outDir_ + ": " + std::strerror(errno));
  }
  images_ = annotations_ = nullptr;
  Json categories = Json::array();
  for (const std::string& name : categoryOrder_) {
    Json c;
    c["id"] = categories_.at(name);
    c["name"] = name;
    c["supercategory"] = taxonomy_;
    categories.push_back(c);
  }
  const std::string imagesPath = streamPath(outDir_, fileName_, "images");
  const std::string annotationsPath = streamPath(outDir_, fileName_, "annotations");
  std::string text = "{\"info\": {\"description\": \"sdgbehave\"}, \"images\": [" + readAll(imagesPath) +
                     "], \"annotations\": [" + readAll(annotationsPath) + "], \"categories\": " +
                     pythonJsonDumps(categories) + "}";
  writeFileAtomic((std::filesystem::path(outDir_) / fileName_).string(), text);
  std::filesystem::remove(imagesPath);
  std::filesystem::remove(annotationsPath);
}

}  // namespace sdg
