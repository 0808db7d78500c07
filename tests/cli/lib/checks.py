"""The CLI tests' checks in Python (imported by their inline scripts; tests/cli/lib on PYTHONPATH).

check(cond, what) prints "ok: what" or "FAIL: what"; finish() exits non-zero when any check failed.
"""
import sys

_failed = False


def check(cond, what):
    global _failed
    print(("ok: " if cond else "FAIL: ") + what)
    _failed |= not cond


def finish():
    sys.exit(1 if _failed else 0)
