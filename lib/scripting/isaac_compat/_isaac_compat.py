"""The shared machinery of sdgbehave's Isaac Sim layer (not an Isaac module).

Holds the behavior whose hook is running (so `np.random.default_rng(None)`
and the event bus know whose they are), the asyncio loop the timeline
drives, and the located error every missing API raises.
"""
import sys as _sys

DOCS = "docs/isaac-scripts.md"
LAYER_PREFIX = "isaac_compat/"

# The BehaviorScript instance whose hook runs now (None between hooks).
current = None
# The run executing a driver program (sdgbehave exec: _sdgbehave.Driver),
# else None. The driver's awaits of the next update are its own updates.
driver = None


_driver_stage = None


def driver_stage():
    """The driver program's Usd.Stage (one object while a stage is open)."""
    global _driver_stage
    if _driver_stage is None:
        from pxr import Usd
        _driver_stage = Usd.Stage(driver.context.stage)
    return _driver_stage


def stage_changed():
    """A new stage is open: handles on the old one's prims go."""
    global _driver_stage
    _driver_stage = None


class DriverEvents:
    """The driver program's side of the event bus (carb.eventdispatcher from
    the program's own code): publish, subscribe and unsubscribe as a
    behavior has them."""

    def publish(self, name, payload):
        driver.context.publish(name, payload)

    def subscribe(self, name, callback):
        return driver.context.subscribe(name, callback)

    def unsubscribe(self, sid):
        driver.context.unsubscribe(sid)


class IsaacApiMissing(AttributeError):
    """An Isaac Sim API the layer does not provide."""


def _script_frame():
    """(file, line) of the innermost frame outside the layer and the host."""
    frame = _sys._getframe(2)
    while frame is not None:
        name = frame.f_code.co_filename
        if not name.startswith(LAYER_PREFIX) and name != "sdgbehave.py" and not name.startswith("<frozen"):
            return name, frame.f_lineno
        frame = frame.f_back
    return "?", 0


def missing(module, name):
    """The error for `module.name`, located at the script line that used it."""
    file, line = _script_frame()
    return IsaacApiMissing(
        f"{module}.{name} is not provided by sdgbehave's Isaac Sim layer (used at {file}:{line}); "
        f"{DOCS} lists what the layer provides")


def driver_for(what, why):
    """The run of the driver program (sdgbehave exec), or the located error
    saying that `what` works only in one, and `why`."""
    if driver is None or current is not None:
        raise unsupported(what, why)
    return driver


def module_getattr(module):
    """A module-level __getattr__ raising the located error for `module`."""
    def __getattr__(name):
        if name.startswith("__"):
            raise AttributeError(name)
        raise missing(module, name)
    return __getattr__


class Located:
    """Base of the layer's classes: an unknown method is a located error."""
    __slots__ = ()

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        raise missing(f"{type(self).__module__}.{type(self).__name__}", name)


def unsupported(what, why=""):
    """The error for a call the layer knows but cannot carry out."""
    file, line = _script_frame()
    return NotImplementedError(f"{what} is not supported by sdgbehave's Isaac Sim layer (used at {file}:{line})"
                               f"{': ' + why if why else ''}; {DOCS} says what the layer provides")


# --- the asyncio loop the timeline drives ------------------------------------
# Coroutines a script starts (asyncio.ensure_future) run on this loop;
# `await omni.kit.app.get_app().next_update_async()` resumes on the next
# timeline update. Nothing runs between updates: a run stays deterministic.
import asyncio as _asyncio

_loop = None
_waiting = []          # futures of next_update_async, resolved by the next update
_last_update = None    # the (iteration token, time) of the update already advanced
_errors = []


def loop():
    global _loop
    if _loop is None:
        _loop = _asyncio.new_event_loop()
        _loop.set_exception_handler(lambda _l, context: _errors.append(context))
        _asyncio.set_event_loop(_loop)
    return _loop


def next_update():
    """A future resolved by the next update. Awaited from a behavior (a hook, an event callback or a
    coroutine they started), it is resolved by a tick event the behavior publishes on sdgbehave's bus,
    which the next update delivers, pre-roll updates included (an event-driven behavior gets no
    on_update there); the bus's order makes the resumption deterministic. Awaited outside any behavior,
    the next on_update resolves it."""
    future = loop().create_future()
    b = current
    if b is None:
        _waiting.append(future)
        return future
    ticks = b.__dict__.get("_isaac_ticks")
    if ticks is None:
        event = f"sdgbehave.isaacLayer.nextUpdate:{b._ctx.prim_path}:{type(b).__name__}"
        ticks = b.__dict__["_isaac_ticks"] = {"futures": [], "pending": False, "event": event}

        def deliver(payload, _b=b, _ticks=ticks):
            global current
            _ticks["pending"] = False
            ready, _ticks["futures"] = _ticks["futures"], []
            previous = current
            current = _b
            try:
                for f in ready:
                    if not f.done():
                        f.set_result(None)
                run_ready()
            finally:
                current = previous
        b.subscribe(ticks["event"], deliver)
    ticks["futures"].append(future)
    if not ticks["pending"]:
        ticks["pending"] = True
        b.publish(ticks["event"], {})
    return future


def advance(token):
    """A timeline update: resolves what awaited it (once per update, whichever
    behavior's on_update comes first)."""
    global _last_update
    if token == _last_update:
        return
    _last_update = token
    if driver is not None:
        run_ready()  # the driver program resumes after the whole update (_isaac_exec)
        return
    ready, _waiting[:] = list(_waiting), []
    for future in ready:
        if not future.done():
            future.set_result(None)
    run_ready()


def run_ready():
    """Runs the loop's ready callbacks (and what they make ready) to completion."""
    if _loop is None or _loop.is_running():
        return  # called from code the loop runs (a driver program's task): the loop goes on by itself
    for _ in range(1000):
        if not _loop._ready:
            break
        _loop.call_soon(_loop.stop)
        _loop.run_forever()
    if _errors:
        context = _errors.pop(0)
        _errors.clear()
        exc = context.get("exception")
        if exc is not None:
            raise exc
        raise RuntimeError(context.get("message", "an asyncio task failed"))
