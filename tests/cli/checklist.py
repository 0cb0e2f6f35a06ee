"""The pass/fail bookkeeping of the Python CLI tests in this folder.

    from checklist import check, finish
    check(value == expected, f"what was checked: {value}")
    finish()   # prints "all checks passed" (the tests' PASS_REGULAR_EXPRESSION) or exits 1

check() prints one "ok:" or "FAIL:" line per check and remembers the failures; finish()
ends the script with the count of failed checks, exit status 1, when there are any.
"""
import sys

failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def finish():
    if failures:
        sys.exit(f"{len(failures)} check(s) failed")
    print("all checks passed")
