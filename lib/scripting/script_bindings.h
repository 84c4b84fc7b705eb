#pragma once
// What the native module's binding files share (script_api.cpp and the
// script_*_binding.cpp files): the handles a script holds on prims and the
// stage, and the binding function of each type. Not a public header.
#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "scripting/script_context.h"

namespace sdg::scripting {

using ContextPtr = std::shared_ptr<ScriptContext>;

// A prim by path: looked up on every call, so a handle never dangles.
struct PrimHandle {
  ContextPtr ctx;
  std::string path;

  Prim& prim() const {
    Prim* p = ctx->liveStage().find(path);
    if (!p) throw pybind11::value_error("prim " + path + " no longer exists");
    return *p;
  }
  std::string what(const std::string& attribute) const { return path + "." + attribute; }
};

struct StageHandle {
  ContextPtr ctx;
};

// A prim handle, or None for no prim (or the pseudo-root).
inline pybind11::object handleOrNone(const ContextPtr& ctx, const Prim* p) {
  if (!p || p->isPseudoRoot()) return pybind11::none();
  return pybind11::cast(PrimHandle{ctx, p->path()});
}

// One binding function per type of the `_sdgbehave` module.
void bindPrim(pybind11::module_& m);     // script_prim_binding.cpp
void bindStage(pybind11::module_& m);    // script_stage_binding.cpp
void bindContext(pybind11::module_& m);  // script_stage_binding.cpp
void bindGfFast(pybind11::module_& m);   // script_gf_fast.cpp

}  // namespace sdg::scripting
