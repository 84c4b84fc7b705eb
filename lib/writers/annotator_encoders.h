#pragma once
// The encode functions of annotatorTable()'s rows (one per annotator), and
// the byte helpers they share. Internal to lib/writers.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "writers/annotator_table.h"

namespace sdg::encoders {

std::vector<uint8_t> textBytes(const std::string& s);
template <typename T>
std::span<const uint8_t> bytesOf(const std::vector<T>& v) {
  return {reinterpret_cast<const uint8_t*>(v.data()), v.size() * sizeof(T)};
}
template <typename T>
void put(std::vector<uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}
nlohmann::ordered_json labelsJson(const LabelSet& labels);

// annotator_table.cpp: images and camera.
void rgb(const AnnotatorOutput& out);
void hdrColor(const AnnotatorOutput& out);
void distanceToCamera(const AnnotatorOutput& out);
void distanceToImagePlane(const AnnotatorOutput& out);
void normals(const AnnotatorOutput& out);
void cameraParams(const AnnotatorOutput& out);
void motionVectors(const AnnotatorOutput& out);
void forwardFlow(const AnnotatorOutput& out);
void backwardFlow(const AnnotatorOutput& out);
// label_encoders.cpp: segmentations, boxes, occlusion, point cloud.
void semanticSegmentation(const AnnotatorOutput& out);
void instanceIdSegmentation(const AnnotatorOutput& out);
void instanceSegmentation(const AnnotatorOutput& out);
void boundingBox2dTight(const AnnotatorOutput& out);
void boundingBox2dLoose(const AnnotatorOutput& out);
void boundingBox3d(const AnnotatorOutput& out);
void occlusion(const AnnotatorOutput& out);
void pointcloud(const AnnotatorOutput& out);
// lidar_encoder.cpp: the frame's LiDAR sweeps (with the first render product only).
void lidar(const AnnotatorOutput& out);

}  // namespace sdg::encoders
