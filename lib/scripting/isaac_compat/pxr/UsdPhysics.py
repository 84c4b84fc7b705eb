"""pxr.UsdPhysics: the physics schemas Isaac's volume stack randomizer applies
(RigidBodyAPI, CollisionAPI, MeshCollisionAPI, MaterialAPI, Scene), with
USD's attribute names and types. Which prim has which API applied is kept by
the layer (pxr/_physics_schemas.py); the attributes are the prim's own."""
from _isaac_compat import module_getattr as _module_getattr

from . import Sdf, Usd
from ._physics_schemas import api_schema as _api_schema

__getattr__ = _module_getattr(__name__)

_T = Sdf.ValueTypeNames

RigidBodyAPI = _api_schema("PhysicsRigidBodyAPI", [
    ("RigidBodyEnabled", "physics:rigidBodyEnabled", _T.Bool),
    ("KinematicEnabled", "physics:kinematicEnabled", _T.Bool),
    ("StartsAsleep", "physics:startsAsleep", _T.Bool),
    ("Velocity", "physics:velocity", _T.Float3),
    ("AngularVelocity", "physics:angularVelocity", _T.Float3),
], "A prim the simulation moves as one rigid body.")

CollisionAPI = _api_schema("PhysicsCollisionAPI", [
    ("CollisionEnabled", "physics:collisionEnabled", _T.Bool),
], "A gprim that collides.")

MeshCollisionAPI = _api_schema("PhysicsMeshCollisionAPI", [
    ("Approximation", "physics:approximation", _T.Token),
], "How a colliding mesh is approximated (convexHull, ...).")

MaterialAPI = _api_schema("PhysicsMaterialAPI", [
    ("DynamicFriction", "physics:dynamicFriction", _T.Float),
    ("StaticFriction", "physics:staticFriction", _T.Float),
    ("Restitution", "physics:restitution", _T.Float),
    ("Density", "physics:density", _T.Float),
], "Friction and restitution of a Material prim bound with the 'physics' purpose.")


class Scene(Usd.Typed):
    """A PhysicsScene prim (gravity); sdgbehave simulates every body in one scene."""
    __slots__ = ()

    @staticmethod
    def _sdg_is_a(handle):
        return handle.type_name == "PhysicsScene"

    @staticmethod
    def Define(stage, path):
        return Scene(stage.DefinePrim(path, "PhysicsScene"))

    def GetGravityDirectionAttr(self):
        return Usd.Attribute(self._prim, "physics:gravityDirection")

    def GetGravityMagnitudeAttr(self):
        return Usd.Attribute(self._prim, "physics:gravityMagnitude")
