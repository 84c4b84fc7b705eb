"""One of Isaac's six behavior modules (isaacsim.replicator.behavior.behaviors.<file>): its class stands for
the sdgbehave built-in of that name (_isaac_behavior/stand_in_class.py). The same source serves the six;
the module's own name says which."""
from _isaac_behavior.stand_in_class import STAND_INS, stand_in

_class_name, _namespace = STAND_INS[__name__.rsplit(".", 1)[1]]
globals()[_class_name] = stand_in(_class_name, _namespace, __name__)
