import sdgbehave

SETTINGS = {"scale": 2}
FACTOR = SETTINGS["scael"]
