"""LookAtBehavior: sdgbehave's built-in lookAtBehavior (see _stand_in)."""
from ._stand_in import stand_in

LookAtBehavior = stand_in("LookAtBehavior", "lookAtBehavior", __name__)
