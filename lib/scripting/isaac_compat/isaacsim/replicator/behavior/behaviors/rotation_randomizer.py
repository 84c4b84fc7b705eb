"""RotationRandomizer: sdgbehave's built-in rotationRandomizer (see _stand_in)."""
from ._stand_in import stand_in

RotationRandomizer = stand_in("RotationRandomizer", "rotationRandomizer", __name__)
