"""LocationRandomizer: sdgbehave's built-in locationRandomizer (see _stand_in)."""
from ._stand_in import stand_in

LocationRandomizer = stand_in("LocationRandomizer", "locationRandomizer", __name__)
