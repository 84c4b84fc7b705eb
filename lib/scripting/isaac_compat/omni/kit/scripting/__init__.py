"""omni.kit.scripting: Isaac Sim's other import path of BehaviorScript."""
from omni.behavior.scripting.core import BehaviorScript  # noqa: F401
