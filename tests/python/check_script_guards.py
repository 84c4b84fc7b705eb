#!/usr/bin/python3
"""A script can neither hang a run nor end it silently: a hook that runs
past the hook timeout (a Python loop, a sleep, an event callback) stops the
run with exit 1 soon after the timeout, naming the prim, behavior, hook,
frame and the script's file:line; code that cannot be interrupted (a C loop,
a script that catches the interruption) ends the process after a grace
period with the same message; SIGTERM and SIGINT print where the run was
and exit 143 and 130; sys.exit() and os._exit() are errors naming the
script (exit 1 in a hook, 2 at load).

usage: check_script_guards.py SDGBEHAVE SCRIPTS_DIR"""
import os
import signal
import subprocess
import sys
import tempfile
import time

from checklib import check, finish


def line_of(path, text):
    """The 1-based number of the line of `path` that contains `text`."""
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if text in line:
                return number
    raise ValueError(f"{text!r} is not in {path}")


# What the run needs besides the timeout: its start, the renderer's bring-up
# and the frames before the stuck one. Under the sanitizers (SDG_SANITIZED,
# set by tests/CMakeLists.txt in an ASan build) every step is several times
# slower, and the suite runs beside other tests, so it gets more.
SLACK = 8.0 if os.environ.get("SDG_SANITIZED") else 3.0


def run(binary, args, stop_after=None, stop_signal=None):
    """(exit code, stderr, seconds); with stop_after, sends stop_signal then."""
    start = time.monotonic()
    proc = subprocess.Popen([binary] + args, stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    if stop_after is not None:
        time.sleep(stop_after)
        proc.send_signal(stop_signal)
    try:
        _, stderr = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        _, stderr = proc.communicate()
        return None, stderr, time.monotonic() - start
    return proc.returncode, stderr, time.monotonic() - start


def main():
    binary, scripts = sys.argv[1:3]
    scene = os.path.join(scripts, "misbehaves.yaml")  # run.hook_timeout: 2
    script = os.path.join(scripts, "misbehaves.py")
    where = "/World/Box: misbehaves.on_update() at frame 2"

    def mode(name):
        return ["--set", f"/World/Box.exposedVar:misbehaves:mode={name}"]

    with tempfile.TemporaryDirectory() as tmp:
        # A Python loop in on_update, with rendering: interrupted at its line
        # right after the scene's 2 s.
        code, err, seconds = run(binary, ["run", scene, "--out", os.path.join(tmp, "loop"), "-q"] + mode("loop"))
        loop_line = line_of(script, "while True:  # a Python loop that never ends")
        # The loop's line or its body's, wherever the interruption finds it.
        at_loop = [f"misbehaves.py:{n}:" for n in (loop_line, loop_line + 1)]
        check(code == 1, f"loop: exit {code}, expected 1\n{err}")
        check(seconds < 2 + SLACK, f"loop: took {seconds:.1f} s with a 2 s hook timeout")
        check(any(a in err for a in at_loop) and where in err and "did not return within 2 s" in err,
              f"loop: the message lacks the file:line {loop_line}, prim, behavior, hook or frame:\n{err}")

        # --hook-timeout beats run.hook_timeout.
        code, err, seconds = run(binary, ["run", scene, "--no-render", "--hook-timeout", "1"] + mode("loop"))
        check(code == 1 and "did not return within 1 s" in err and seconds < 1 + SLACK,
              f"--hook-timeout 1: exit {code} after {seconds:.1f} s:\n{err}")

        # A sleep ends early; an event callback is watched like a hook.
        code, err, seconds = run(binary, ["run", scene, "--no-render"] + mode("sleep"))
        check(code == 1 and f"misbehaves.py:{line_of(script, 'time.sleep(3600)')}:" in err and where in err
              and seconds < 2 + SLACK, f"sleep: exit {code} after {seconds:.1f} s:\n{err}")
        code, err, _ = run(binary, ["run", scene, "--no-render"] + mode("callback_loop"))
        check(code == 1 and f"misbehaves.py:{line_of(script, 'the callback never returns')}:" in err
              and "/World/Box: misbehaves: the callback for event 'misbehaves.ping' at frame 3" in err,
              f"callback: exit {code}:\n{err}")

        # Code that cannot be interrupted: the process ends after the grace
        # period (as long as the timeout, 1 to 5 s), still saying where.
        for name, text in [("native", "sum(itertools.repeat(1))"), ("swallow", "except BaseException:")]:
            code, err, seconds = run(binary, ["run", scene, "--no-render"] + mode(name))
            check(code == 1 and where in err and "did not stop when interrupted" in err and seconds < 2 + 2 + SLACK,
                  f"{name}: exit {code} after {seconds:.1f} s:\n{err}")
            check("misbehaves.py:" in err, f"{name}: the message names no script line:\n{err}")
        code, err, _ = run(binary, ["run", scene, "--no-render"] + mode("catch"))
        check(code == 1 and where in err and "caught the interruption" in err, f"catch: exit {code}:\n{err}")

        # Stop signals while a hook is stuck (no timeout): where, then 143 / 130.
        for sig, status in [(signal.SIGTERM, 143), (signal.SIGINT, 130)]:
            code, err, _ = run(binary, ["run", scene, "--no-render", "--hook-timeout", "0"] + mode("loop"),
                               stop_after=1.5, stop_signal=sig)
            check(code == status, f"{sig.name}: exit {code}, expected {status}\n{err}")
            check(any(f"{a} {where}: stopped by {sig.name} (exit {status})" in err for a in at_loop),
                  f"{sig.name}: the message does not say where the run was:\n{err}")

        # Exits from a hook are errors naming the script's line, never a silent 0.
        for name, call in [("sys_exit", "sys.exit(0)"), ("os_exit", "os._exit(0)")]:
            code, err, _ = run(binary, ["run", scene, "--out", os.path.join(tmp, name), "-q"] + mode(name))
            check(code == 1 and f"misbehaves.py:{line_of(script, call)}:" in err and f"{where} called {call}" in err,
                  f"{name}: exit {code}:\n{err}")

    # ... and at load time, exit 2 at the script's line.
    plain = os.path.join(scripts, "scene_with_script.yaml")
    for name, call in [("exits_at_load.py", "sys.exit(0)"), ("os_exit_at_load.py", "os._exit(0)")]:
        code, err, _ = run(binary, ["validate", plain, "--script", os.path.join(scripts, name)])
        check(code == 2 and f"{name}:4:1: error: loading the script failed: its top-level code called {call}" in err,
              f"{name}: exit {code}:\n{err}")
    return finish("hooks are watched; stop signals and exits from scripts say where")


if __name__ == "__main__":
    sys.exit(main())
