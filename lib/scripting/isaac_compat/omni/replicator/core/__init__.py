"""omni.replicator.core: render products, writers and the orchestrator for
a driver program (sdgbehave exec). A writer attached to render products
writes sdgbehave's dataset (BasicWriter, COCO, BOP: docs/writers.md) into
its output_dir; frames are taken by orchestrator.step/step_async/run, or on
every update while the timeline plays when capture on play is on (the
default, as in Replicator)."""
import os as _os

import _isaac_compat
from _isaac_compat import Located as _Located, module_getattr as _module_getattr, unsupported as _unsupported

__getattr__ = _module_getattr(__name__)


def _driver(what):
    return _isaac_compat.driver_for(f"omni.replicator.core {what}", "Replicator's capture API works in a driver "
                                    "program (sdgbehave exec), not inside a behavior")


def _path(camera):
    if hasattr(camera, "GetPath"):
        camera = camera.GetPath()
    return str(camera)


def _plain(value):
    """A writer option as JSON: Gf vectors and tuples as lists."""
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (str, bool, int, float)) or value is None:
        return value
    try:
        return [_plain(v) for v in value]
    except TypeError:
        return str(value)


class RenderProduct(_Located):
    """A camera and a resolution to render at."""
    __slots__ = ("camera", "resolution", "path", "_destroyed")
    _count = 0

    def __init__(self, camera, resolution):
        RenderProduct._count += 1
        self.camera, self.resolution = camera, resolution
        self.path = f"/Render/RenderProduct_Replicator_{RenderProduct._count:02d}"
        self._destroyed = False

    def destroy(self):
        self._destroyed = True


class _Create(_Located):
    __slots__ = ()

    def render_product(self, camera, resolution, force_new=True, name=None, render_vars=None):
        _driver("create.render_product")
        if isinstance(camera, (list, tuple)):
            if len(camera) != 1:
                raise _unsupported("create.render_product with several cameras", "make one render product per camera")
            camera = camera[0]
        path = _path(camera)
        width, height = (int(v) for v in resolution)
        if width <= 0 or height <= 0:
            raise ValueError(f"create.render_product: the resolution must be positive, found {tuple(resolution)}")
        stage = _isaac_compat.driver_stage()
        prim = stage.GetPrimAtPath(path)
        if not prim or prim.GetTypeName() != "Camera":
            raise ValueError(f"create.render_product: the stage has no Camera prim at {path}")
        return RenderProduct(path, (width, height))


create = _Create()


class Writer(_Located):
    """A writer by Replicator's name; initialize() takes the options by Isaac's names (output_dir and what the
    writer writes: rgb, semantic_segmentation, bounding_box_2d_tight, ...)."""
    __slots__ = ("name", "_options", "_output_dir", "_id")

    def __init__(self, name, init_params=None):
        self.name, self._options, self._output_dir, self._id = name, {}, None, None
        if init_params:
            self.initialize(**init_params)

    def initialize(self, output_dir=None, **options):
        if output_dir is None:
            raise ValueError(f"{self.name}.initialize: give output_dir (sdgbehave has no default output folder)")
        self._output_dir = _os.path.abspath(str(output_dir))
        self._options = {k: _plain(v) for k, v in options.items()}

    def attach(self, render_products, trigger=None, **kwargs):
        d = _driver("Writer.attach")
        if self._output_dir is None:
            raise ValueError(f"{self.name}.attach: call initialize(output_dir=...) first")
        if self._id is not None:
            raise ValueError(f"{self.name}.attach: the writer is attached already (detach it first)")
        products = render_products if isinstance(render_products, (list, tuple)) else [render_products]
        if not products:
            raise ValueError(f"{self.name}.attach: no render product")
        sizes = {p.resolution for p in products}
        if len(sizes) != 1:
            raise _unsupported(f"{self.name}.attach to render products of different resolutions",
                               "sdgbehave renders one resolution per writer")
        for p in products:
            if p._destroyed:
                raise ValueError(f"{self.name}.attach: render product {p.path} was destroyed")
        width, height = sizes.pop()
        options = dict(self._options, type=self.name)
        self._id = d.attach_writer(self._output_dir, options, [p.camera for p in products], width, height)

    def detach(self):
        if self._id is not None:
            _driver("Writer.detach").detach_writer(self._id)
            self._id = None

    def get_metadata(self):
        return {"name": self.name, "output_dir": self._output_dir, **self._options}


class _Writers(_Located):
    __slots__ = ()

    def get(self, name, init_params=None, render_products=None, trigger=None, **kwargs):
        _driver("writers.get")
        writer = Writer(str(name), init_params)
        if render_products is not None:
            writer.attach(render_products)
        return writer


writers = _Writers()
WriterRegistry = writers

_capture_on_play = True
_frames_to_run = None  # orchestrator.run(num_frames): frames left to capture


def _capture(d):
    if d.attached_writers:
        d.capture()


def _after_update():
    """After each app update: capture on play (_isaac_exec)."""
    global _frames_to_run
    d = _isaac_compat.driver
    if d is None or not d.playing or not d.attached_writers:
        return
    if _frames_to_run is not None:
        if _frames_to_run > 0:
            d.capture()
            _frames_to_run -= 1
        if _frames_to_run == 0:
            _frames_to_run = None
            d.pause()
    elif _capture_on_play:
        d.capture()


class _Orchestrator(_Located):
    __slots__ = ()

    def set_capture_on_play(self, value):
        global _capture_on_play
        _capture_on_play = bool(value)

    def get_capture_on_play(self):
        return _capture_on_play

    def step(self, num_steps=1, rt_subframes=-1, pause_timeline=True, delta_time=None, wait_for_render=True):
        """One frame per step: the timeline advances one update (delta_time None; it plays for the step when it
        does not already) or not at all (delta_time 0), then every attached writer takes the stage as its next
        frame. rt_subframes is not used (the renderers converge per frame: docs/isaac-scripts.md)."""
        d = _driver("orchestrator.step")
        for _ in range(int(num_steps)):
            if delta_time is None or float(delta_time) != 0.0:
                if delta_time is not None and abs(float(delta_time) * d.time_codes_per_second - 1.0) > 1e-9:
                    raise _unsupported(f"orchestrator.step(delta_time={delta_time})",
                                       "a step advances one update (delta_time=None) or none (delta_time=0.0)")
                was_playing = d.playing
                if not was_playing:
                    d.play()
                d.update()
                if pause_timeline or not was_playing:
                    d.pause()
            _capture(d)

    async def step_async(self, num_steps=1, rt_subframes=-1, pause_timeline=True, delta_time=None,
                         wait_for_render=True):
        self.step(num_steps, rt_subframes, pause_timeline, delta_time, wait_for_render)

    def run(self, num_frames=None, start_timeline=True):
        """Plays the timeline and captures on each update, num_frames times (then pauses), or until stop()."""
        global _frames_to_run
        d = _driver("orchestrator.run")
        _frames_to_run = None if num_frames is None else int(num_frames)
        if not d.playing:
            d.play()

    def run_until_complete(self, num_frames=None, start_timeline=True):
        if num_frames is None:
            raise _unsupported("orchestrator.run_until_complete() without num_frames", "give num_frames")
        d = _driver("orchestrator.run_until_complete")
        was_playing = d.playing
        if not was_playing:
            d.play()
        for _ in range(int(num_frames)):
            d.update()
            _capture(d)
        if not was_playing:
            d.pause()

    async def run_until_complete_async(self, num_frames=None, start_timeline=True):
        self.run_until_complete(num_frames, start_timeline)

    def stop(self):
        global _frames_to_run
        _frames_to_run = None
        d = _driver("orchestrator.stop")
        if d.playing:
            d.pause()

    pause = stop

    def wait_until_complete(self):
        """Frames are written as they are taken; a writer's dataset is finished when it is detached or the
        program ends."""
        _driver("orchestrator.wait_until_complete")

    async def wait_until_complete_async(self):
        self.wait_until_complete()

    def get_is_started(self):
        return _frames_to_run is not None


orchestrator = _Orchestrator()


def set_global_seed(seed):
    """The seed of the run: behaviors' streams on stages opened from now on, and the path tracer's samples of
    writers attached from now on."""
    _driver("set_global_seed").set_seed(int(seed))


def get_global_seed():
    raise _unsupported("omni.replicator.core.get_global_seed")
