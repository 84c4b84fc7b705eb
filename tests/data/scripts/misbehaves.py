"""A behavior that misbehaves on purpose, to test that a run never hangs or
ends silently because of a script: `mode` picks how, `atFrame` when (the
update of that frame; on_play for -1)."""
import itertools
import os
import sys
import time

import sdgbehave


class Misbehaves(sdgbehave.IntervalBehavior):
    """Hangs, sleeps or exits in apply(), as `mode` says."""

    BEHAVIOR_NS = "misbehaves"
    VARIABLES_TO_EXPOSE = [
        {"attr_name": "mode", "attr_type": "token", "default_value": "none",
         "allowed": ["none", "loop", "swallow", "catch", "native", "sleep", "sys_exit", "os_exit",
                     "callback_loop"],
         "doc": "What apply() does when the frame comes."},
        {"attr_name": "atFrame", "attr_type": "int", "default_value": 2, "doc": "The frame it happens on."},
    ]

    def setup(self):
        self.frame = -1
        self.mode = self.get_exposed_variable("mode")
        if self.mode == "callback_loop":
            self.subscribe("misbehaves.ping", self.on_ping)

    def on_ping(self, payload):
        while True:  # the callback never returns
            pass

    def apply(self):
        self.frame += 1
        if self.frame != self.get_exposed_variable("atFrame"):
            return
        if self.mode == "loop":
            n = 0
            while True:  # a Python loop that never ends
                n += 1
        elif self.mode == "swallow":
            while True:
                try:
                    while True:  # catches even the watchdog's interruption, and goes on
                        pass
                except BaseException:
                    pass
        elif self.mode == "catch":
            try:
                while True:  # catches the watchdog's interruption, then returns as if nothing happened
                    pass
            except BaseException:
                return
        elif self.mode == "native":
            sum(itertools.repeat(1))  # a C loop that holds the interpreter
        elif self.mode == "sleep":
            time.sleep(3600)
        elif self.mode == "sys_exit":
            sys.exit(0)
        elif self.mode == "os_exit":
            os._exit(0)
        elif self.mode == "callback_loop":
            self.publish("misbehaves.ping", {})
