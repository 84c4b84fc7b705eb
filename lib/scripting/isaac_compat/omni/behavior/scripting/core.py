"""omni.behavior.scripting.core.BehaviorScript over sdgbehave.Behavior.

An Isaac Sim behavior class is an sdgbehave behavior: registered under its
BEHAVIOR_NS with its VARIABLES_TO_EXPOSE as variables, instantiated once per
prim, its hooks called by sdgbehave's timeline. `self.prim` is a Usd.Prim,
`self.prim_path` an Sdf.Path, `self.stage` a Usd.Stage.

While a hook runs, the layer knows whose it is: `np.random.default_rng(None)`
(and `default_rng()`) then draws its seed from this behavior's sdgbehave
random stream -- a function of the run seed, the prim, the namespace, the
iteration and the stream's position -- instead of OS entropy, so datasets
are byte-identical across runs, --threads and shards. An explicit seed keeps
its Isaac meaning.
"""
import re as _re

import _isaac_compat
import sdgbehave as _sdgbehave
from pxr import Sdf, Usd

# The loop exists before any script code runs, so that asyncio.ensure_future
# in a hook or an event callback schedules on it (not on a loop asyncio would
# make up, which nothing runs).
_isaac_compat.loop()

_HOOKS = ("on_init", "on_play", "on_pause", "on_stop", "on_update", "on_destroy")


def _wrap_hook(name, method):
    def hook(self, *args):
        previous = _isaac_compat.current
        _isaac_compat.current = self
        try:
            if name == "on_update":
                _isaac_compat.advance(args[0])
            elif name == "on_play":
                _isaac_compat._last_update = None  # the next update is new even at an earlier time
            result = method(self, *args)
            _isaac_compat.run_ready()
            return result
        finally:
            _isaac_compat.current = previous
    hook.__name__, hook.__qualname__, hook.__doc__ = method.__name__, method.__qualname__, method.__doc__
    hook.__wrapped__ = method
    return hook


def _namespace(cls):
    """BEHAVIOR_NS, else the class name in camelCase (ExampleBehavior -> exampleBehavior)."""
    ns = cls.__dict__.get("BEHAVIOR_NS")
    return ns if ns else cls.__name__[:1].lower() + cls.__name__[1:]


class BehaviorScript(_sdgbehave.Behavior):
    """Isaac Sim's behavior base class."""

    _isaac_script = True

    # What sdgbehave's loader asks of a script class it did not write (it
    # never imports this layer itself: the dependency runs one way).
    @classmethod
    def _sdg_namespace(cls):
        return _namespace(cls)

    @classmethod
    def _sdg_exposed_variables(cls):
        return _sdg_variables(cls)

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        for name in _HOOKS:
            method = cls.__dict__.get(name)
            if method is not None and not hasattr(method, "__wrapped__"):
                setattr(cls, name, _wrap_hook(name, method))

    @property
    def prim(self):
        p = self.__dict__.get("_isaac_prim")
        if p is None:
            p = Usd.Prim(self._ctx.prim, self.stage)
            self.__dict__["_isaac_prim"] = p
        return p

    @property
    def prim_path(self):
        return Sdf.Path(self._ctx.prim_path)

    @property
    def stage(self):
        s = self.__dict__.get("_isaac_stage")
        if s is None:
            s = Usd.Stage(self._ctx.stage)
            self.__dict__["_isaac_stage"] = s
        return s

    def _isaac_entropy(self):
        """A 64-bit seed from this behavior's random stream."""
        rng = self._ctx.rng
        return (rng.integers(0, 2 ** 32) << 32) | rng.integers(0, 2 ** 32)


def _sdg_variables(cls):
    """VARIABLES_TO_EXPOSE in sdgbehave's form: type names as strings, Gf values as tuples."""
    out = []
    for record in cls.VARIABLES_TO_EXPOSE or []:
        if not isinstance(record, dict):
            out.append(record)
            continue
        r = dict(record)
        if isinstance(r.get("attr_type"), Sdf.ValueTypeName):
            r["attr_type"] = r["attr_type"].native
        if "default_value" in r:
            r["default_value"] = Usd._to_native(r["default_value"])
        out.append(r)
    return out


def _install_seeding():
    """Routes numpy's default_rng(None) through the running behavior's stream."""
    import random as _random

    import numpy
    real = numpy.random.default_rng
    if getattr(real, "_sdg_seeded", False):
        return

    class Generator(numpy.random.Generator):
        """numpy's Generator, with scalar uniform(low, high) drawn as
        low + (high - low) * random(): numpy's own formula on the same
        next double, so the stream is bit-identical, at a quarter of the
        cost of numpy's argument handling (scripts draw per prim per frame)."""

        def uniform(self, low=0.0, high=1.0, size=None):
            if size is None and type(low) is float and type(high) is float:
                span = high - low
                if span - span == 0.0:  # finite; numpy raises for an infinite span
                    return low + span * self.random()
            return super().uniform(low, high, size)

        def choice(self, a, size=None, replace=True, p=None, axis=0, shuffle=True):
            """One element of a list of str, bool or float, drawn as numpy draws it (its index from
            integers(0, n) as int64, or, with p for at most two elements, the first normalized cumulative
            probability above random()), returned as numpy's scalar of the list's type; anything else is
            numpy's own choice. Isaac's texture randomizer draws twice per
            prim per frame, and numpy's argument handling was most of that."""
            if size is None and replace and axis == 0 and type(a) is list and a:
                kind = _SCALAR_TYPES.get(type(a[0]))
                if kind is not None and all(type(x) is type(a[0]) for x in a):
                    if p is None:
                        return kind(a[int(self.integers(0, len(a), dtype=numpy.int64))])
                    if type(p) is list and len(p) == len(a) <= 2 and all(type(x) is float for x in p):
                        total, cdf = 0.0, []
                        for x in p:
                            if not (x >= 0.0) or x == float("inf"):
                                break
                            total += x
                            cdf.append(total)
                        else:
                            # numpy: sum(p) within sqrt(eps) of 1, cdf normalized by its last value
                            if abs(total - 1.0) <= _P_TOLERANCE and total > 0.0:
                                u = self.random()
                                last = cdf[-1]
                                for i, c in enumerate(cdf):
                                    if u < c / last:
                                        return kind(a[i])
                                return kind(a[-1])
            return super().choice(a, size, replace, p, axis, shuffle)

    _SCALAR_TYPES = {str: numpy.str_, bool: numpy.bool_, float: numpy.float64}
    _P_TOLERANCE = numpy.sqrt(numpy.finfo(numpy.float64).eps)

    def default_rng(seed=None):
        if seed is None:
            b = _isaac_compat.current
            seed = b._isaac_entropy() if b is not None else _random.getrandbits(64)
        rng = real(seed)
        return rng if isinstance(seed, numpy.random.Generator) else Generator(rng.bit_generator)

    default_rng._sdg_seeded = True
    default_rng.__doc__ = real.__doc__
    numpy.random.default_rng = default_rng


try:
    _install_seeding()
except ImportError:  # numpy is optional: scripts that do not use it run without it
    pass
