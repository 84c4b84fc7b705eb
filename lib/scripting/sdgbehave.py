"""sdgbehave: the Python API of behavior scripts.

A behavior script is a Python file that a scene lists under `scripts:`.
Loading the scene runs the file's top-level code, as importing a module
does, and registers every class it defines that derives from `Behavior` and
sets its own `BEHAVIOR_NS`. Attached under a prim's `behaviors:` by that
namespace, the class is instantiated once per prim, like a built-in.

This file is compiled into sdgbehave; docs/scripting.md documents every call.
"""
import ast as _ast
import importlib.util as _importlib_util
import os as _os
import random as _random
import signal as _signal
import sys as _sys
import traceback as _traceback

import _sdgbehave as _native
from _sdgbehave import Prim, Rng, Stage, look_at_rotation  # noqa: F401  (documented API)

__all__ = ["Behavior", "IntervalBehavior", "Prim", "Stage", "Rng", "look_at_rotation", "INTERVAL_VARIABLE",
           "ScriptExit"]


class ScriptExit(BaseException):
    """Raised by os._exit() in a script: a behavior cannot end the process
    (sdgbehave would exit without saying why, leaving a dataset half
    written). sys.exit() raises SystemExit as usual; both stop the run with
    an error naming the script's line. Raise an exception to stop a run."""


class _HookTimeout(BaseException):
    """Raised into a hook that ran longer than the hook timeout
    (--hook-timeout, run.hook_timeout). A BaseException, so that
    `except Exception` in a script does not swallow it."""

# The `interval` variable of IntervalBehavior; added to VARIABLES_TO_EXPOSE
# when a subclass does not declare one itself.
INTERVAL_VARIABLE = {"attr_name": "interval", "attr_type": "uint", "default_value": 0,
                     "doc": "Apply every N updates; 0 means every update."}


class _Log:
    """Messages through sdgbehave's logger, prefixed with the prim and namespace."""

    def __init__(self, behavior):
        self._behavior = behavior

    def _write(self, level, message):
        b = self._behavior
        _native.log(level, f"{b.prim_path}: {b.BEHAVIOR_NS}: {message}")

    def debug(self, message):
        self._write("debug", message)

    def info(self, message):
        self._write("info", message)

    def warn(self, message):
        self._write("warning", message)

    warning = warn

    def error(self, message):
        self._write("error", message)


class Behavior:
    """Base class of every scripted behavior: the lifecycle hooks and what a
    behavior may use (its prim, the stage, its random stream, events, the log).

    Subclasses set BEHAVIOR_NS (a camelCase name) and VARIABLES_TO_EXPOSE (a
    list of {"attr_name", "attr_type", "default_value", "doc"} records) and
    override the hooks they need. RNG_STREAM, when set, keys the random
    stream by that name instead of BEHAVIOR_NS (a port of a built-in sets the
    built-in's name to draw exactly what the built-in draws).
    """

    BEHAVIOR_NS = None
    VARIABLES_TO_EXPOSE = []
    RNG_STREAM = None
    _ctx = None  # the host's handle, set before on_init

    # --- what the host gives every instance ------------------------------
    @property
    def prim(self):
        """The prim this behavior is attached to (a Prim)."""
        return self._ctx.prim

    @property
    def prim_path(self):
        """The attached prim's path, a str."""
        return self._ctx.prim_path

    @property
    def stage(self):
        """The stage (a Stage)."""
        return self._ctx.stage

    @property
    def rng(self):
        """This (behavior, prim)'s random stream (an Rng), derived from the run
        seed, the prim path, the namespace and the iteration; or, when the
        behavior exposes an int `seed` variable >= 0, from that seed. It starts
        afresh on every play after a stop."""
        return self._ctx.rng

    @property
    def log(self):
        """log.debug/info/warn/error(message), prefixed with the prim path."""
        return _Log(self)

    def get_exposed_variable(self, name):
        """The value of exposed variable `name` (attribute
        exposedVar:<BEHAVIOR_NS>:<name> on the prim), or None if it is missing."""
        return self._ctx.get_exposed_variable(name)

    def publish(self, event, payload=None):
        """Queues an event; subscribers get it on the next update. The payload
        is a dict of str keys and str, number or bool values."""
        self._ctx.publish(event, payload or {})

    def subscribe(self, event, callback):
        """Calls callback(payload_dict) for every `event`; returns an id for
        unsubscribe. Subscriptions end when the behavior is destroyed."""
        return self._ctx.subscribe(event, callback)

    def unsubscribe(self, subscription):
        self._ctx.unsubscribe(subscription)

    # --- lifecycle hooks (override what you need) -------------------------
    def on_init(self):
        """Once, when the run creates the behavior (before the pre-roll)."""

    def on_play(self):
        """When the timeline starts playing (and on resume from pause)."""

    def on_pause(self):
        """When the timeline pauses."""

    def on_stop(self):
        """When the timeline stops. sdgbehave then undoes every change this
        behavior made to the stage while playing."""

    def on_update(self, current_time, delta_time):
        """Once per update while the timeline plays (one update per frame)."""

    def on_destroy(self):
        """Once, at the end of the run (after a stop)."""


class IntervalBehavior(Behavior):
    """A timeline randomizer with Isaac Sim's `interval` counting: setup() on
    the first play after a stop, apply() once on play when interval > 0, then
    apply() every `interval` updates (0: every update; updates with
    delta_time <= 0 are not counted); reset() on stop. The counter keeps its
    value across pause and resume."""

    interval = 0
    update_counter = 0
    _set_up = False

    def setup(self):
        """Read exposed variables and cache what apply() needs."""

    def apply(self):
        """Change the stage: called as the interval says."""
        raise NotImplementedError(f"{type(self).__name__} must define apply()")

    def reset(self):
        """Forget caches (the stage itself is restored by sdgbehave)."""

    def on_play(self):
        self.interval = self.get_exposed_variable("interval")
        if not self._set_up:
            self.setup()
            self._set_up = True
        if self.interval > 0:
            self.apply()  # the first captured frame is already randomized

    def on_update(self, current_time, delta_time):
        if delta_time <= 0:
            return
        if self.interval == 0:
            self.apply()
            return
        self.update_counter += 1
        if self.update_counter >= self.interval:
            self.apply()
            self.update_counter = 0

    def on_stop(self):
        if self._set_up:
            self.reset()
        self._set_up = False
        self.update_counter = 0
        self.interval = 0


# --- the host's side (not part of the API) --------------------------------

def _entry_lines(tree):
    """{class name: (class line, VARIABLES_TO_EXPOSE line, [entry lines])} from
    the script's syntax tree, so problems point at the entry that has them."""
    lines = {}
    for node in _ast.walk(tree):
        if not isinstance(node, _ast.ClassDef):
            continue
        var_line, entries = node.lineno, []
        for stmt in node.body:
            targets = stmt.targets if isinstance(stmt, _ast.Assign) else \
                [stmt.target] if isinstance(stmt, _ast.AnnAssign) else []
            if any(isinstance(t, _ast.Name) and t.id == "VARIABLES_TO_EXPOSE" for t in targets):
                var_line = stmt.lineno
                if isinstance(stmt.value, (_ast.List, _ast.Tuple)):
                    entries = [(e.lineno, e.col_offset + 1) for e in stmt.value.elts]
        lines[node.name] = (node.lineno, var_line, entries)
    return lines


class _EmbeddedFinder:
    """Imports the Python packages compiled into sdgbehave (the Isaac Sim
    layer: pxr, carb, omni, usdrt, isaacsim) from their embedded sources;
    tracebacks name them isaac_compat/<path>."""

    PREFIX = "isaac_compat/"

    def __init__(self, files):
        self._modules = {}
        for path, source in files.items():
            parts = path[:-3].split("/")
            package = parts[-1] == "__init__"
            if package:
                parts = parts[:-1]
            self._modules[".".join(parts)] = (path, source, package)
        # Isaac's behavior package: its modules' names, sdgbehave's own sources.
        for name, (path, package) in _ISAAC_BEHAVIOR_MODULES.items():
            self._modules[name] = (path, files[path], package)
        for file in _ISAAC_BEHAVIOR_STAND_INS:
            # Named like Isaac's file, which is nowhere here: attached, it is the built-in of that name.
            virtual = f"isaacsim/replicator/behavior/behaviors/{file}.py"
            self._modules[f"{_ISAAC_EXTENSION}.behavior.behaviors.{file}"] = (
                virtual, files["_isaac_behavior/stand_in_module.py"], False)

    def find_spec(self, fullname, path=None, target=None):
        entry = self._modules.get(fullname)
        if entry is None:
            return None
        if fullname.startswith(_ISAAC_EXTENSION) and _user_isaac_module(fullname):
            return None  # the user's own copy of Isaac's extension wins (see _join_isaac_trees)
        return _importlib_util.spec_from_loader(fullname, self, origin=self.PREFIX + entry[0], is_package=entry[2])

    def create_module(self, spec):
        return None

    def exec_module(self, module):
        path, source, _package = self._modules[module.__spec__.name]
        module.__file__ = self.PREFIX + path
        exec(compile(source, self.PREFIX + path, "exec"), module.__dict__)

    def get_source(self, fullname):
        entry = self._modules.get(fullname)
        return entry[1] if entry else None


_EMBEDDED = None
# Isaac's behavior package as sdgbehave provides it (isaac_compat/_isaac_behavior/, written for sdgbehave,
# not Isaac's files): module name -> (source, is a package).
_ISAAC_BEHAVIOR_MODULES = {
    "isaacsim.replicator": ("_isaac_behavior/replicator_package.py", True),
    "isaacsim.replicator.behavior": ("_isaac_behavior/package.py", True),
    "isaacsim.replicator.behavior.global_variables": ("_isaac_behavior/names.py", False),
    "isaacsim.replicator.behavior.base_behavior": ("_isaac_behavior/interval_base.py", False),
    "isaacsim.replicator.behavior.utils": ("_isaac_behavior/utils_package.py", True),
    "isaacsim.replicator.behavior.utils.behavior_utils": ("_isaac_behavior/exposed_variables.py", False),
    "isaacsim.replicator.behavior.utils.scene_utils": ("_isaac_behavior/prim_edits.py", False),
    "isaacsim.replicator.behavior.behaviors": ("_isaac_behavior/stand_ins.py", True),
}
# Isaac's six behavior modules (isaacsim.replicator.behavior.behaviors.<file>).
_ISAAC_BEHAVIOR_STAND_INS = ("light_randomizer", "location_randomizer", "look_at_behavior", "rotation_randomizer",
                             "texture_randomizer", "volume_stack_randomizer")
# Isaac's behavior extension: sdgbehave ships its own (global_variables,
# utils, behaviors standing for the built-ins), and a user's copy found
# above a script replaces it.
_ISAAC_EXTENSION = "isaacsim.replicator"
_user_isaac_trees = []


def _user_isaac_module(fullname):
    """True when a user's Isaac extension tree holds `fullname`."""
    rel = fullname.split(".")[1:]  # below isaacsim/
    for tree in _user_isaac_trees:
        base = _os.path.join(tree, *rel)
        if _os.path.isfile(base + ".py") or _os.path.isdir(base):  # a module, a package or a namespace
            return True
    return False


def _install_embedded(files):
    global _EMBEDDED
    _EMBEDDED = _EmbeddedFinder(dict(files))
    _sys.meta_path.insert(0, _EMBEDDED)


def _import_hint(exc):
    """What to say after a ModuleNotFoundError: for the Isaac Sim roots, what
    the layer offers there instead; else how to get a Python module."""
    name = getattr(exc, "name", None)
    if not name:
        return ""
    root = name.split(".")[0]
    if _EMBEDDED is not None and root in ("omni", "isaacsim", "carb", "pxr", "usdrt"):
        offered = sorted(m for m in _EMBEDDED._modules if (m == root or m.startswith(root + "."))
                         and not m.rsplit(".", 1)[-1].startswith("_"))
        return (f"sdgbehave's Isaac Sim layer has no module '{name}'; under '{root}' it provides: "
                f"{', '.join(offered)} (docs/isaac-scripts.md says what each does)")
    return (f"module '{name}' is not installed for the Python sdgbehave embeds (Debian's python3): install "
            f"its Debian package (python3-...) or put it on PYTHONPATH")


def _join_isaac_trees(path):
    """An Isaac Sim extension tree above the script (a folder holding
    isaacsim/, as NVIDIA ships isaacsim.replicator.behavior) joins the
    layer's isaacsim package, so the script's own imports of
    isaacsim.replicator.behavior.* find the real files."""
    folder = _os.path.dirname(_os.path.abspath(path))
    while True:
        tree = _os.path.join(folder, "isaacsim")
        if _os.path.isdir(tree):
            import isaacsim
            if tree not in isaacsim.__path__:
                isaacsim.__path__.append(tree)
            if _os.path.isdir(_os.path.join(tree, "replicator")) and tree not in _user_isaac_trees:
                _user_isaac_trees.append(tree)
                # Modules of sdgbehave's own extension imported before are
                # dropped, so the user's are imported from now on.
                for name in [m for m in _sys.modules if m == _ISAAC_EXTENSION or
                             m.startswith(_ISAAC_EXTENSION + ".")]:
                    if getattr(_sys.modules[name], "__file__", "").startswith(_EmbeddedFinder.PREFIX) or \
                            getattr(_sys.modules[name], "__spec__", None) and \
                            _sys.modules[name].__spec__.loader is _EMBEDDED:
                        del _sys.modules[name]
        parent = _os.path.dirname(folder)
        if parent == folder:
            return
        folder = parent


def _is_isaac_class(obj):
    return isinstance(obj, type) and issubclass(obj, Behavior) and getattr(obj, "_isaac_script", False)


def _load_script(path, module_name):
    """Runs the script as module `module_name` (its folder first on sys.path)
    and returns [(class, class line, VARIABLES_TO_EXPOSE line, entry lines)]
    for every Behavior subclass it defines with its own BEHAVIOR_NS."""
    folder = _os.path.dirname(_os.path.abspath(path))
    if folder not in _sys.path:
        _sys.path.insert(0, folder)
    with open(path, "rb") as f:
        source = f.read()
    tree = _ast.parse(source, filename=path)
    _join_isaac_trees(path)
    spec = _importlib_util.spec_from_file_location(module_name, path)
    module = _importlib_util.module_from_spec(spec)
    _sys.modules[module_name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del _sys.modules[module_name]
        raise
    lines = _entry_lines(tree)
    found = []
    for obj in list(vars(module).values()):
        if _is_isaac_class(obj) and obj.__module__ == module_name:
            # Isaac Sim's script manager runs every BehaviorScript class the
            # file defines; the namespace is BEHAVIOR_NS, else the class name
            # (the class answers both itself: see the compatibility layer).
            if "BEHAVIOR_NS" not in obj.__dict__:
                obj.BEHAVIOR_NS = obj._sdg_namespace()
            class_line, var_line, entries = lines.get(obj.__name__, (1, 1, []))
            found.append((obj, obj.__name__, class_line, var_line, entries, obj._sdg_exposed_variables()))
            continue
        if isinstance(obj, type) and issubclass(obj, Behavior) and obj.__module__ == module_name \
                and "BEHAVIOR_NS" in obj.__dict__:
            class_line, var_line, entries = lines.get(obj.__name__, (1, 1, []))
            variables = list(obj.VARIABLES_TO_EXPOSE) if isinstance(obj.VARIABLES_TO_EXPOSE, (list, tuple)) \
                else obj.VARIABLES_TO_EXPOSE
            if issubclass(obj, IntervalBehavior) and isinstance(variables, list) and not any(
                    isinstance(v, dict) and v.get("attr_name") == "interval" for v in variables):
                variables.append(dict(INTERVAL_VARIABLE))
            found.append((obj, obj.__name__, class_line, var_line, entries, variables))
    return found


def _error_location(exc, tb, files):
    """(file, line, column, text) of an exception: a SyntaxError's own place,
    else the innermost traceback frame in one of the scripts, else the
    innermost frame; text is the formatted traceback, without the frames of
    sdgbehave's own loading machinery. `files` maps each script's absolute
    path to the path it was given as, which every message shows."""
    def script(filename):
        return files.get(filename) or files.get(_os.path.abspath(filename))

    def shown(filename):
        return script(filename) or filename

    if isinstance(exc, SyntaxError) and exc.filename:
        return shown(exc.filename), exc.lineno or 0, exc.offset or 0, f"{type(exc).__name__}: {exc.msg}"
    frames = [f for f in _traceback.extract_tb(tb)
              if f.filename != "sdgbehave.py" or f.name not in ("_load_script", "_on_hook_timeout", "_exit")]
    frames = [f for f in frames if not f.filename.startswith("<frozen importlib")]
    chosen = None
    for frame in frames:
        if script(frame.filename):
            chosen = frame
        frame.filename = shown(frame.filename)  # the source lines are already read
    text = "Traceback (most recent call last):\n" + "".join(_traceback.format_list(frames)) + \
        "".join(_traceback.format_exception_only(type(exc), exc))
    text = text.rstrip()
    if isinstance(exc, ModuleNotFoundError):
        text += "\n" + _import_hint(exc)
    if chosen is None and frames:
        chosen = frames[-1]
    if chosen is None:
        return "", 0, 0, text
    column = (chosen.colno + 1) if getattr(chosen, "colno", None) is not None else 0
    return chosen.filename, chosen.lineno or 0, column, text


def _on_hook_timeout(signum, frame):
    """The watchdog's signal: raises _HookTimeout in the stuck call, where it
    is, if the call it was sent for is still running."""
    if _native._hook_interrupted():
        raise _HookTimeout(f"the call ran longer than the hook timeout ({_native._hook_timeout():g} s)")


def _install_watchdog_signal(signum):
    """The watchdog interrupts a stuck call with this signal, sent to the
    thread that runs scripts: Python then calls _on_hook_timeout at the next
    bytecode, and a sleep or a blocking read returns early."""
    _signal.signal(signum, _on_hook_timeout)


def _guard_exits():
    """Replaces os._exit, which would end sdgbehave on the spot, with a
    function raising ScriptExit (in the process that loaded the scripts: a
    child a script forked keeps the real one)."""
    real_exit = _os._exit
    owner = _os.getpid()

    def _exit(status=0):
        if _os.getpid() != owner:
            real_exit(status)
        raise ScriptExit(f"os._exit({status!r})")

    _exit.__doc__ = real_exit.__doc__
    _os._exit = _exit
    posix = _sys.modules.get("posix")
    if posix is not None:
        posix._exit = _exit


def _run_program(path, argv):
    """sdgbehave exec: runs the Script Editor program `path` (isaac_compat/_isaac_exec.py)."""
    folder = _os.path.dirname(path)
    if folder not in _sys.path:
        _sys.path.insert(0, folder)
    _join_isaac_trees(path)
    import _isaac_exec
    _isaac_exec.run(path, argv, _native.driver())


def _seed_global_random(seed):
    """Seeds Python's `random` (and numpy's global generator, if a script
    imported numpy) so that scripts that use them still run reproducibly;
    self.rng is the supported source of randomness."""
    _random.seed(seed)
    numpy = _sys.modules.get("numpy")
    if numpy is not None:
        numpy.random.seed(seed % (2 ** 32))


_guard_exits()
