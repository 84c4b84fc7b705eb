// The native module's Stage (prims by path; a behavior defines and removes
// only its own prims under /Behaviors/<ns>/, a driver program anywhere) and
// Context (a behavior's handle: its prim, random stream, exposed variables
// and events).
#include <pybind11/embed.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "assets/asset_resolver.h"
#include "behavior/behavior_prims.h"
#include "behavior/run_activity.h"
#include "core/text.h"
#include "scripting/script_bindings.h"
#include "scripting/script_call.h"
#include "scripting/value_convert.h"
#include "stage/path.h"
#include "stage/prim_types.h"

namespace py = pybind11;

namespace sdg::scripting {
namespace {

PrimHandle definePrim(StageHandle& s, const std::string& path, const std::string& typeName) {
  ScriptContext& ctx = *s.ctx;
  Stage& stage = ctx.liveStage();
  const std::string scope = std::string(kBehaviorsScope) + "/" + ctx.ns();
  if (!ctx.driver && !path.starts_with(scope + "/"))
    throw py::value_error("define_prim: " + ctx.ns() + " creates prims under " + scope + "/, not at " + path);
  if (std::string why = path::whyInvalid(path); !why.empty()) throw py::value_error("define_prim: " + path + ": " + why);
  if (stage.find(path)) throw py::value_error("define_prim: " + path + " already exists (see next_free_path)");
  std::optional<PrimType> type = primTypeFromName(typeName);
  if (!type) {
    std::vector<std::string> names;
    for (const PrimTypeInfo& info : allPrimTypes()) names.emplace_back(info.name);
    throw py::value_error("define_prim: unknown prim type '" + typeName + "'" + text::didYouMean(typeName, names));
  }
  // Missing ancestors become scopes; each is a prim this behavior created.
  std::vector<std::string> missing;
  for (std::string parent(path::parent(path)); parent.size() > 1 && !stage.find(parent);
       parent = std::string(path::parent(parent)))
    missing.push_back(parent);
  // (A driver's are its own: nothing undoes them.) USD's typeless ancestors are scopes here.
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    Prim& scope = stage.definePrim(*it, PrimType::Scope);
    if (!ctx.driver) ctx.journal().created(scope);
  }
  Prim& prim = stage.definePrim(path, *type);
  if (!ctx.driver) ctx.journal().created(prim);
  return PrimHandle{s.ctx, path};
}

void removePrim(StageHandle& s, const std::string& path) {
  ScriptContext& ctx = *s.ctx;
  Stage& stage = ctx.liveStage();
  Prim* prim = stage.find(path);
  if (!prim) throw py::value_error("remove_prim: " + path + " does not exist");
  if (!ctx.created(*prim)) throw py::value_error("remove_prim: " + path + " was not created by " + ctx.ns());
  // The journals key prims by address: forget the removed ones, so that a
  // prim created later at the same address is not taken for this one.
  for (Prim* p : stage.subtree(*prim)) {
    ctx.playJournal.forget(*p);
    ctx.idleJournal.forget(*p);
  }
  stage.removePrim(path);
}

std::vector<PrimHandle> traverse(StageHandle& s, py::object root) {
  Stage& stage = s.ctx->liveStage();
  Prim* start = &stage.pseudoRoot();
  if (!root.is_none()) start = &(root.cast<PrimHandle&>().prim());
  std::vector<PrimHandle> out;
  for (Prim* p : stage.subtree(*start))
    if (!p->isPseudoRoot()) out.push_back(PrimHandle{s.ctx, p->path()});
  return out;
}

py::dict payloadToPython(const Payload& payload) {
  py::dict d;
  for (const auto& [key, value] : payload.entries())
    std::visit([&](const auto& v) { d[py::str(key)] = py::cast(v); }, value);
  return d;
}

Payload payloadFromPython(const py::dict& d, const std::string& what) {
  Payload payload;
  for (auto [key, value] : d) {
    if (!py::isinstance<py::str>(key)) throw py::type_error(what + ": payload keys are strings");
    std::string k = key.cast<std::string>();
    if (py::isinstance<py::bool_>(value)) payload.set(k, value.cast<bool>());
    else if (py::isinstance<py::str>(value)) payload.set(k, value.cast<std::string>());
    else if (PyNumber_Check(value.ptr())) payload.set(k, value.cast<double>());
    else throw py::type_error(what + ": payload value '" + k + "' must be a str, number or bool, found " +
                              std::string(py::str(py::type::handle_of(value).attr("__name__"))));
  }
  return payload;
}

}  // namespace

void bindStage(py::module_& m) {
  py::class_<StageHandle>(m, "Stage", "The stage the run plays.")
      .def("get_prim",
           [](StageHandle& s, const std::string& path) { return handleOrNone(s.ctx, s.ctx->liveStage().find(path)); },
           py::arg("path"), "The prim at path, or None.")
      .def("traverse", &traverse, py::arg("root") = py::none(),
           "Every prim below root (root included; the whole stage without one), pre-order.")
      .def("define_prim", &definePrim, py::arg("path"), py::arg("type_name") = "Xform",
           "Creates a prim under /Behaviors/<BEHAVIOR_NS>/; it is removed again on stop.")
      .def("remove_prim", &removePrim, py::arg("path"), "Removes a prim this behavior created.")
      .def("next_free_path",
           [](StageHandle& s, const std::string& path) { return nextFreePath(s.ctx->liveStage(), path); },
           py::arg("path"))
      .def(
          "resolve_asset",
          [](StageHandle& s, const std::string& path) -> py::object {
            s.ctx->liveStage();
            if (!s.ctx->assets) return py::none();
            std::optional<std::string> resolved = s.ctx->assets->resolve(path);
            if (!resolved) resolved = s.ctx->assets->resolveFolder(path);
            return resolved ? py::object(py::str(*resolved)) : py::object(py::none());
          },
          py::arg("path"),
          "The absolute path of a file or folder named as the scene names assets (absolute, or below the scene's "
          "folder, its asset_roots or an --asset-root), or None when none exists.")
      .def_property_readonly("meters_per_unit",
                             [](StageHandle& s) { return s.ctx->liveStage().metadata().metersPerUnit; })
      .def_property_readonly("up_axis", [](StageHandle& s) { return s.ctx->liveStage().metadata().upAxis; })
      .def_property_readonly("time_codes_per_second",
                             [](StageHandle& s) { return s.ctx->liveStage().metadata().timeCodesPerSecond; })
      .def(
          "set_metadata",
          [](StageHandle& s, std::optional<std::string> upAxis, std::optional<double> metersPerUnit) {
            if (!s.ctx->driver)
              throw py::value_error("set_metadata: a behavior cannot change the stage's up axis or units");
            StageMetadata& m = s.ctx->liveStage().metadata();
            if (upAxis) {
              if (*upAxis != "Y" && *upAxis != "Z")
                throw py::value_error("set_metadata: the up axis is Y or Z, found '" + *upAxis + "'");
              m.upAxis = *upAxis;
            }
            if (metersPerUnit) {
              if (!(*metersPerUnit > 0) || !std::isfinite(*metersPerUnit))
                throw py::value_error("set_metadata: metres per unit must be positive, found " +
                                      text::formatDouble(*metersPerUnit));
              m.metersPerUnit = *metersPerUnit;
            }
          },
          py::arg("up_axis") = py::none(), py::arg("meters_per_unit") = py::none(),
          "A driver program's (sdgbehave exec) change of the stage's up axis or metres per unit.");
}

void bindContext(py::module_& m) {
  py::class_<ScriptContext, std::shared_ptr<ScriptContext>>(m, "Context", "A behavior's handle (self._ctx).")
      .def_property_readonly("prim", [](const ContextPtr& c) { c->liveStage(); return PrimHandle{c, c->primPath}; })
      .def_property_readonly("prim_path", [](const ContextPtr& c) { return c->primPath; })
      .def_property_readonly("stage", [](const ContextPtr& c) { c->liveStage(); return StageHandle{c}; })
      .def_property_readonly("rng", [](const ContextPtr& c) -> Rng& { return c->randomStream(); },
                             py::return_value_policy::reference_internal)
      .def("get_exposed_variable",
           [](const ContextPtr& c, const std::string& name) -> py::object {
             const Prim* p = c->liveStage().find(c->primPath);
             const Value* v = p ? p->value(exposedAttributeName(c->ns(), name)) : nullptr;
             return v ? toPython(*v) : py::object(py::none());
           })
      .def("publish",
           [](const ContextPtr& c, const std::string& event, const py::dict& payload) {
             c->liveStage();
             c->events->publish(event, payloadFromPython(payload, "publish " + event));
           })
      .def("subscribe",
           [](const ContextPtr& c, const std::string& event, py::function callback) {
             c->liveStage();
             // Watched like a hook: a Python error, a timeout or an exit in the
             // callback stops the run, naming the callback.
             EventBus::Subscription id = c->events->subscribe(
                 event, [callback, prim = c->primPath, ns = c->ns(), script = c->script,
                         hook = "the callback for event '" + event + "'"](const Payload& payload) {
                   activity::HookScope scope(prim, ns, hook, activity::HookScope::Kind::Callback);
                   callScript(
                       script, [&] { return prim + ": " + ns + ": " + hook; },
                       [&] { callback(payloadToPython(payload)); });
                 });
             c->subscriptions.push_back(id);
             return id;
           })
      .def("unsubscribe", [](const ContextPtr& c, EventBus::Subscription id) {
        c->liveStage();
        c->events->unsubscribe(id);
        std::erase(c->subscriptions, id);
      });
}

}  // namespace sdg::scripting
