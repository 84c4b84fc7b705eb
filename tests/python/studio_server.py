"""Starts `sdgbehave studio` on a free port for a test and talks to it."""
import json
import os
import re
import signal
import subprocess
import time
import urllib.error
import urllib.request


class Studio:
    def __init__(self, binary, scene, cwd=None):
        self.process = subprocess.Popen([binary, "studio", scene], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                        text=True, cwd=cwd)
        line = self.process.stdout.readline()
        match = re.search(r"(http://[^/]+)/\?token=([0-9a-f]+)", line)
        if not match:
            self.process.kill()
            raise RuntimeError(f"studio did not start: {line!r} {self.process.stderr.read()}")
        self.base, self.token = match.group(1), match.group(2)
        self.url = f"{self.base}/?token={self.token}"

    def request(self, path, body=None, headers=None, token=True, raw=False):
        """(status, parsed JSON | text | bytes)."""
        h = dict(headers or {})
        if token:
            h["X-Studio-Token"] = self.token
        data = None
        if body is not None:
            data = body if isinstance(body, bytes) else json.dumps(body).encode()
            h["Content-Type"] = "application/json"
        req = urllib.request.Request(self.base + path, data=data, headers=h, method="POST" if data is not None else "GET")
        try:
            with urllib.request.urlopen(req, timeout=60) as r:
                status, content, kind = r.status, r.read(), r.headers.get("Content-Type", "")
        except urllib.error.HTTPError as e:
            status, content, kind = e.code, e.read(), e.headers.get("Content-Type", "")
        if raw:
            return status, content
        if "json" in kind:
            return status, json.loads(content)
        return status, content.decode(errors="replace")

    def alive(self):
        return self.process.poll() is None

    def stop(self):
        if self.alive():
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.process.kill()
        return self.process.returncode
