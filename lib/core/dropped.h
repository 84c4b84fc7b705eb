#pragma once
// A warning that says what an input had that sdgbehave does not carry over
// (a USD prim type, schema, material network...), counted: the log's JSON
// form gives the count as its own object, run_summary.json lists them and
// `validate --strict` fails on them.
#include <cstddef>
#include <string>

#include "core/diagnostics.h"

namespace sdg {

struct DroppedInfo {
  std::string kind;  // "prim_type", "applied_schema", "material_network", ...
  std::string what;  // the type, schema, network or input name
  size_t count = 0;  // how many places have it
};

struct DroppedWarning {
  Diagnostic diagnostic;  // a warning located at the first place
  DroppedInfo info;
};

}  // namespace sdg
