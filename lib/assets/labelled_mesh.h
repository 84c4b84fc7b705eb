#pragma once
// A mesh file that a behavior puts on the stage during a run, labelled as it
// will be there: what the BOP writer takes a model from when no prim of the
// stage as loaded carries the label yet (the volume stack's cartons).
#include <string>

namespace sdg {

struct LabelledMesh {
  std::string taxonomy;  // the semantic type the label is in ("class")
  std::string label;
  std::string url;       // as the behavior writes it into the prim's `asset`
  std::string spawner;   // "<prim path>: <behavior>", for messages
};

}  // namespace sdg
