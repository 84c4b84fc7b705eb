"""VolumeStackRandomizer: sdgbehave's built-in volumeStackRandomizer (see _stand_in)."""
from ._stand_in import stand_in

VolumeStackRandomizer = stand_in("VolumeStackRandomizer", "volumeStackRandomizer", __name__, events=True)
