"""The applied physics schemas of sdgbehave's Isaac Sim layer (shared by
pxr.UsdPhysics and pxr.PhysxSchema; not a pxr module).

sdgbehave's stage records no `apiSchemas` list, so the layer keeps which
prim has which physics API applied (by prim path, per schema); the schemas'
attributes themselves (`physics:rigidBodyEnabled`, ...) are ordinary prim
attributes written through the behavior's journal, so they are restored on
stop like any other write. Removing a prim through Usd.Stage.RemovePrim
forgets its applied schemas and those of its descendants."""
from _isaac_compat import Located as _Located

from . import Sdf, Usd

_applied = {}  # schema name -> set of prim paths
_physics_bindings = {}  # prim path -> material path bound with the 'physics' purpose


def forget(path):
    """Drops the applied schemas of `path` and its descendants (the prim was removed)."""
    prefix = path.rstrip("/") + "/"
    for p in [p for p in _physics_bindings if p == path or p.startswith(prefix)]:
        del _physics_bindings[p]
    for paths in _applied.values():
        for p in [p for p in paths if p == path or p.startswith(prefix)]:
            paths.discard(p)


def applied_paths(schema_name):
    return _applied.get(schema_name, set())


def _attr_methods(attrs):
    """Get<Name>Attr / Create<Name>Attr for each (Name, attribute, value type)."""
    methods = {}
    for name, attr_name, type_name in attrs:
        def get(self, _n=attr_name, _t=type_name):
            # A schema attribute is defined by the schema: Set authors it with the schema's type.
            return Usd.Attribute(self._prim, _n, pending=None if self._prim._h.has_attribute(_n) else _t)

        def create(self, default=None, write_sparsely=False, _n=attr_name, _t=type_name):
            attr = self._prim.CreateAttribute(_n, _t)
            if default is not None:
                attr.Set(default)
            return attr
        methods[f"Get{name}Attr"] = get
        methods[f"Create{name}Attr"] = create
    return methods


class _Relationship(_Located):
    """simulationOwner: sdgbehave simulates one scene, so targets are accepted and kept by the layer only."""
    __slots__ = ("_targets",)

    def __init__(self):
        self._targets = []

    def AddTarget(self, path, *args):
        self._targets.append(Sdf.Path(str(path)))
        return True

    def GetTargets(self):
        return list(self._targets)


def api_schema(schema_name, attrs, doc):
    """A single-apply API schema class: Apply records it, HasAPI answers it."""
    def _sdg_has_api(handle):
        return handle.path in _applied.get(schema_name, ())

    def apply(prim):
        _applied.setdefault(schema_name, set()).add(prim._h.path)
        return cls(prim)

    def init(self, prim=None):
        Usd.APISchemaBase.__init__(self, prim.GetPrim() if isinstance(prim, Usd.SchemaBase) else prim)

    def get_simulation_owner_rel(self):
        return _Relationship()

    body = {"__slots__": (), "__doc__": doc, "__init__": init, "Apply": staticmethod(apply),
            "_sdg_has_api": staticmethod(_sdg_has_api), "_sdg_is_a": staticmethod(_sdg_has_api),
            "GetSimulationOwnerRel": get_simulation_owner_rel}
    body.update(_attr_methods(attrs))
    cls = type(schema_name, (Usd.APISchemaBase,), body)
    return cls


def bind_physics_material(prim, material_path):
    _physics_bindings[prim._h.path] = str(material_path)


def physics_material_of(path):
    """The material path bound with the 'physics' purpose to `path` or its closest ancestor."""
    while path:
        found = _physics_bindings.get(path)
        if found is not None:
            return found
        path = path.rsplit("/", 1)[0]
    return None
