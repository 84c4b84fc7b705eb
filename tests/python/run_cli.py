#!/usr/bin/python3
"""Runs a command and checks its exit code and output.

usage: run_cli.py [--exit N] [--stdout TEXT]... [--stderr TEXT]... [--no-stderr TEXT]... -- COMMAND...
TEXT must appear (or, for --no-stderr, must not appear) in that stream."""
import subprocess
import sys


def main():
    args = sys.argv[1:]
    split = args.index("--")
    opts, command = args[:split], args[split + 1:]
    want_exit, checks = 0, []
    i = 0
    while i < len(opts):
        if opts[i] == "--exit":
            want_exit = int(opts[i + 1])
        else:
            checks.append((opts[i], opts[i + 1]))
        i += 2
    result = subprocess.run(command, capture_output=True, text=True, timeout=300)
    failures = []
    if result.returncode != want_exit:
        failures.append(f"exit code {result.returncode}, expected {want_exit}")
    for kind, text in checks:
        stream = result.stdout if kind == "--stdout" else result.stderr
        present = text in stream
        if kind == "--no-stderr" and present:
            failures.append(f"stderr must not contain: {text}")
        elif kind != "--no-stderr" and not present:
            failures.append(f"{kind[2:]} lacks: {text}")
    if failures:
        print("\n".join(failures))
        print("--- stdout\n" + result.stdout + "--- stderr\n" + result.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
