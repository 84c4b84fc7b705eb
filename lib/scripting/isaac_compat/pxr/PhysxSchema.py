"""pxr.PhysxSchema: PhysxRigidBodyAPI (gravity switch and damping of a rigid
body), as Isaac's scene_utils applies it; other PhysX schemas raise a
located error (see docs/isaac-scripts.md)."""
from _isaac_compat import module_getattr as _module_getattr

from . import Sdf
from ._physics_schemas import api_schema as _api_schema

__getattr__ = _module_getattr(__name__)

_T = Sdf.ValueTypeNames

PhysxRigidBodyAPI = _api_schema("PhysxRigidBodyAPI", [
    ("DisableGravity", "physxRigidBody:disableGravity", _T.Bool),
    ("AngularDamping", "physxRigidBody:angularDamping", _T.Float),
    ("LinearDamping", "physxRigidBody:linearDamping", _T.Float),
], "PhysX's extra rigid body settings: gravity off, linear and angular damping.")
