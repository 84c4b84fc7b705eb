"""Isaac's six behaviors, each standing for sdgbehave's built-in of that name."""
from .light_randomizer import LightRandomizer
from .location_randomizer import LocationRandomizer
from .look_at_behavior import LookAtBehavior
from .rotation_randomizer import RotationRandomizer
from .texture_randomizer import TextureRandomizer
from .volume_stack_randomizer import VolumeStackRandomizer

__all__ = ["LightRandomizer", "LocationRandomizer", "LookAtBehavior", "RotationRandomizer", "TextureRandomizer",
           "VolumeStackRandomizer"]
