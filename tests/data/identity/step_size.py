"""The step mover.py takes: a module the script imports, hashed into the run's identity."""


def step(rng):
    return rng.uniform(-0.2, 0.2)
