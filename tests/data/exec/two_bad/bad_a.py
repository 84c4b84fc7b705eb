from omni.isaac.nonexistent import Thing  # noqa: F401
