"""TextureRandomizer: sdgbehave's built-in textureRandomizer (see _stand_in)."""
from ._stand_in import stand_in

TextureRandomizer = stand_in("TextureRandomizer", "textureRandomizer", __name__)
