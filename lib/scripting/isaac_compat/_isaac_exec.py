"""Runs an Isaac Sim Script Editor program under `sdgbehave exec` (not an
Isaac module): its module-level code, then the asyncio tasks it scheduled.
Each `await omni.kit.app.get_app().next_update_async()` of the program is
one app update of the run (driver.update(): newly listed behavior scripts
start, events are delivered, behaviors update while the timeline plays),
taken when every task is waiting on it, so the program's interleaving is
the same in every run. A task's exception ends the program there."""
import asyncio as _asyncio
import sys as _sys
import time as _time
import types as _types

import _isaac_compat

# What a program's asyncio loop runs past, before it says it waits on
# something no update delivers.
_TIMER_LIMIT_SECONDS = 3600


class ProgramStalled(RuntimeError):
    """The program's tasks wait on something sdgbehave never delivers."""


def run(path, argv, driver):
    _isaac_compat.driver = driver
    loop = _isaac_compat.loop()
    tasks = []

    def factory(the_loop, coro, **kwargs):
        task = _asyncio.Task(coro, loop=the_loop, **kwargs)
        tasks.append(task)
        return task

    loop.set_task_factory(factory)
    _sys.argv = [path] + list(argv)
    with open(path, "rb") as f:
        code = compile(f.read(), path, "exec")
    module = _types.ModuleType("__main__")
    module.__file__ = path
    module.__builtins__ = __builtins__
    previous_main = _sys.modules.get("__main__")
    _sys.modules["__main__"] = module
    try:
        exec(code, module.__dict__)
        _drive(loop, driver, tasks)
    finally:
        if previous_main is not None:
            _sys.modules["__main__"] = previous_main
        _isaac_compat.driver = None


def _raise_failed(tasks):
    for task in tasks:
        if task.done() and not task.cancelled() and task.exception() is not None:
            exc = task.exception()
            tasks.clear()
            raise exc


def _one_update(driver):
    driver.update()
    rep = _sys.modules.get("omni.replicator.core")
    if rep is not None:
        rep._after_update()  # capture on play
    ready, _isaac_compat._waiting[:] = list(_isaac_compat._waiting), []
    for future in ready:
        if not future.done():
            future.set_result(None)


def _drive(loop, driver, tasks):
    while True:
        _isaac_compat.run_ready()
        _raise_failed(tasks)
        if all(t.done() for t in tasks):
            return
        if _isaac_compat._waiting:
            _one_update(driver)
            continue
        if loop._scheduled:  # asyncio.sleep and other timers: real time passes
            delay = loop._scheduled[0].when() - loop.time()
            if delay > _TIMER_LIMIT_SECONDS:
                break
            if delay > 0:
                _time.sleep(delay)
            loop.call_soon(loop.stop)
            loop.run_forever()
            continue
        break
    waiting = [t for t in tasks if not t.done()]
    names = ", ".join(sorted({t.get_coro().__qualname__ for t in waiting}))
    raise ProgramStalled(f"the program's tasks ({names}) wait on something sdgbehave never delivers: only "
                         f"omni.kit.app's next_update_async(), Replicator's step/wait calls and asyncio.sleep "
                         f"advance ({_isaac_compat.DOCS})")
