import omni.isaac.core.world  # noqa: F401
