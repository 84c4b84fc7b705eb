"""An Isaac-style behavior (the project's own test input) that authors the physics schemas Isaac's
volume_stack_randomizer.py applies, through the same calls scene_utils.py makes, and checks what the
layer answers. Any wrong answer raises, which fails the run; on success it prints one line."""
from omni.behavior.scripting.core import BehaviorScript
from pxr import PhysicsSchemaTools, PhysxSchema, Sdf, UsdPhysics, UsdShade


def expect(ok, what):
    if not ok:
        raise AssertionError(f"physics schemas: {what}")


class PhysicsSchemasProbe(BehaviorScript):
    BEHAVIOR_NS = "physicsSchemasProbe"
    VARIABLES_TO_EXPOSE = []

    def on_play(self):
        stage, prim = self.stage, self.prim
        expect(not prim.HasAPI(UsdPhysics.RigidBodyAPI), "RigidBodyAPI before Apply")
        body = UsdPhysics.RigidBodyAPI.Apply(prim)
        body.CreateRigidBodyEnabledAttr(True)
        expect(prim.HasAPI(UsdPhysics.RigidBodyAPI), "RigidBodyAPI after Apply")
        expect(not prim.HasAPI(UsdPhysics.CollisionAPI), "CollisionAPI is a schema of its own")
        expect(UsdPhysics.RigidBodyAPI(prim).GetRigidBodyEnabledAttr().Get() is True, "rigidBodyEnabled")
        expect(prim.GetAttribute("physics:rigidBodyEnabled").GetTypeName() == Sdf.ValueTypeNames.Bool,
               "physics:rigidBodyEnabled is a bool")
        physx = PhysxSchema.PhysxRigidBodyAPI.Apply(prim)
        physx.GetDisableGravityAttr().Set(False)
        physx.CreateAngularDampingAttr().Set(10.0)
        expect(prim.GetAttribute("physxRigidBody:angularDamping").Get() == 10.0, "angular damping")
        expect(prim.GetAttribute("physxRigidBody:disableGravity").Get() is False, "disableGravity")

        material = UsdShade.Material.Define(stage, f"/Behaviors/{self.BEHAVIOR_NS}/PhysicsMaterial")
        mat_api = UsdPhysics.MaterialAPI.Apply(material.GetPrim())
        mat_api.CreateStaticFrictionAttr().Set(0.001)
        UsdPhysics.MaterialAPI(material.GetPrim()).GetStaticFrictionAttr().Set(0.95)
        expect(abs(material.GetPrim().GetAttribute("physics:staticFriction").Get() - 0.95) < 1e-6, "friction")
        render_before = UsdShade.MaterialBindingAPI(prim).GetDirectBinding().GetMaterialPath()
        UsdShade.MaterialBindingAPI.Apply(prim).Bind(material, UsdShade.Tokens.weakerThanDescendants, "physics")
        expect(UsdShade.MaterialBindingAPI(prim).GetDirectBinding().GetMaterialPath() == render_before,
               "a physics binding left the render material alone")

        body_id = PhysicsSchemaTools.sdfPathToInt(prim.GetPath())
        expect(PhysicsSchemaTools.sdfPathToInt(prim.GetPath()) == body_id, "sdfPathToInt is stable")
        expect(PhysicsSchemaTools.intToSdfPath(body_id) == prim.GetPath(), "intToSdfPath inverts it")

        wall = stage.DefinePrim(f"/Behaviors/{self.BEHAVIOR_NS}/Walls/floor", "Cube")
        UsdPhysics.CollisionAPI.Apply(wall).CreateCollisionEnabledAttr(True)
        expect(wall.HasAPI(UsdPhysics.CollisionAPI), "CollisionAPI after Apply")
        stage.RemovePrim(f"/Behaviors/{self.BEHAVIOR_NS}/Walls")
        again = stage.DefinePrim(f"/Behaviors/{self.BEHAVIOR_NS}/Walls/floor", "Cube")
        expect(not again.HasAPI(UsdPhysics.CollisionAPI), "a removed prim's schemas are forgotten")
        print(f"[PhysicsSchemasProbe][{self.prim_path}] physics schemas ok")
