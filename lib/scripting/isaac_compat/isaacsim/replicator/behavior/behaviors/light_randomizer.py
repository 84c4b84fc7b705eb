"""LightRandomizer: sdgbehave's built-in lightRandomizer (see _stand_in)."""
from ._stand_in import stand_in

LightRandomizer = stand_in("LightRandomizer", "lightRandomizer", __name__)
