#pragma once
// The interface every dataset writer implements (BasicWriter, COCO, BOP).
// The run makes its writers from the scene through the registry
// (writer_registry.h), asks them what to render, and hands each render
// product's frame to every writer on a pool thread; nothing else knows
// which writers exist.
//
// Adding a writer: its option table and doc in scene_io/settings_specs.cpp
// (writerTypes()), a class deriving from Writer in its own files, a row in
// writer_registry.cpp's table, what finishing the dataset needs (a field of
// DatasetParts), its section in docs/writers.md and a test that reads its
// output the way its users' tools do.
#include <string>
#include <vector>

#include "writers/annotator_table.h"
#include "writers/output_files.h"
#include "writers/product_frame.h"

namespace sdg {

// A frame's output: the dataset's own files, and hidden parts (fragments
// assembled when the dataset is finished) that the manifest tracks too.
struct FrameFiles {
  std::vector<OutputFile> dataset;
  std::vector<OutputFile> parts;
};

class Writer {
 public:
  virtual ~Writer() = default;
  // What its files are made from (beyond colour, which is always read).
  virtual AnnotatorNeeds needs() const = 0;
  // Files written once per run, before the first frame (every shard writes
  // the same bytes).
  virtual std::vector<OutputFile> runFiles() const { return {}; }
  // One render product's frame; called on pool threads, concurrently.
  virtual void encode(const ProductFrame& frame, FrameFiles& out) const = 0;
};

}  // namespace sdg
