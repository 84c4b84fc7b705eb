"""pxr.Sdf: paths, asset paths and value type names (the type names sdgbehave's stage holds)."""
from _isaac_compat import Located as _Located, module_getattr as _module_getattr

__getattr__ = _module_getattr(__name__)


class Path(_Located):
    __slots__ = ("pathString",)

    def __init__(self, path=""):
        self.pathString = path.pathString if isinstance(path, Path) else str(path)

    def __str__(self):
        return self.pathString

    def __repr__(self):
        return f"Sdf.Path({self.pathString!r})"

    def __eq__(self, other):
        return str(other) == self.pathString if isinstance(other, (Path, str)) else False

    def __hash__(self):
        return hash(self.pathString)

    def __lt__(self, other):
        return self.pathString < str(other)

    def __bool__(self):
        return bool(self.pathString)

    @property
    def name(self):
        return self.pathString.rsplit("/", 1)[-1].rsplit(".", 1)[-1]

    def IsEmpty(self):
        return not self.pathString

    @property
    def isEmpty(self):
        return not self.pathString

    def GetParentPath(self):
        head = self.pathString.rsplit("/", 1)[0]
        return Path(head or "/")

    def AppendChild(self, name):
        return Path(self.pathString.rstrip("/") + "/" + name)

    def AppendPath(self, path):
        return Path(self.pathString.rstrip("/") + "/" + str(path).lstrip("/"))

    def AppendProperty(self, name):
        return Path(self.pathString + "." + name)

    def GetPrimPath(self):
        return Path(self.pathString.split(".", 1)[0])

    def HasPrefix(self, prefix):
        p = str(prefix)
        return self.pathString == p or self.pathString.startswith(p.rstrip("/") + "/")


Path.emptyPath = Path("")
Path.absoluteRootPath = Path("/")


class AssetPath(_Located):
    __slots__ = ("path", "resolvedPath")

    def __init__(self, path="", resolved=""):
        self.path, self.resolvedPath = str(path), resolved

    def __eq__(self, other):
        return isinstance(other, AssetPath) and other.path == self.path

    __hash__ = None

    def __repr__(self):
        return f"Sdf.AssetPath({self.path!r})"


class AssetPathArray(list):
    def __init__(self, items=()):
        super().__init__(i if isinstance(i, AssetPath) else AssetPath(i) for i in items)


class ValueTypeName(_Located):
    """A USD value type; `native` is the type name of sdgbehave's stage that stores it."""
    __slots__ = ("type_name", "native")

    def __init__(self, type_name, native):
        self.type_name, self.native = type_name, native

    def __eq__(self, other):
        if type(other) is ValueTypeName or isinstance(other, ValueTypeName):
            return other.native == self.native
        return other == self.type_name

    def __hash__(self):
        return hash(self.native)

    def __str__(self):
        return self.type_name

    def __repr__(self):
        return f"Sdf.ValueTypeName({self.type_name!r})"

    @property
    def cppTypeName(self):
        return self.type_name


class _Names:
    """Sdf.ValueTypeNames: the types sdgbehave's stage holds; others raise a located error."""

    def __init__(self, table):
        for attr, (usd, native) in table.items():
            setattr(self, attr, ValueTypeName(usd, native))

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        from _isaac_compat import missing
        raise missing("pxr.Sdf.ValueTypeNames", name)

    def Find(self, usd):
        # Asked per op per frame (XformOp.GetTypeName): the table's answers are remembered.
        found = _found.get(usd)
        if found is not None:
            return found
        for v in vars(self).values():
            if v.type_name == usd or v.native == usd:
                if isinstance(usd, str):
                    _found[usd] = v
                return v
        return ValueTypeName(usd, usd)


_found = {}


ValueTypeNames = _Names({
    "Bool": ("bool", "bool"), "Int": ("int", "int"), "UInt": ("uint", "uint"), "Float": ("float", "float"),
    "Double": ("double", "double"), "Int2": ("int2", "int2"), "Float2": ("float2", "float2"),
    "Float3": ("float3", "float3"), "Color3f": ("color3f", "color3f"), "Double3": ("double3", "double3"),
    "Vector3d": ("vector3d", "vector3d"), "Point3d": ("point3d", "double3"),
    "Quatf": ("quatf", "quatf"), "Quatd": ("quatd", "quatd"), "Matrix4d": ("matrix4d", "matrix4d"),
    "String": ("string", "string"), "Token": ("token", "token"), "Asset": ("asset", "asset"),
    "AssetArray": ("asset[]", "asset[]"), "StringArray": ("string[]", "string[]"),
    "TokenArray": ("token[]", "string[]"),
})
