"""What the command-line test scripts of tests/cli (fuzz_cases.py, kill_mid_write.py,
output_failures.py, restart_die_filling.py) share: their options and their verdict."""
import argparse


def parse_args(*required, **defaults):
    """The options: --cgdem and --NAME for each name in `required` (strings, required), and
    --NAME for each keyword of `defaults`, of that default's type."""
    ap = argparse.ArgumentParser()
    for name in ("cgdem",) + required:
        ap.add_argument("--" + name, required=True)
    for name, value in defaults.items():
        ap.add_argument("--" + name, type=type(value), default=value)
    return ap.parse_args()


def print_failures(failures):
    """One line `FAIL ...` per failure; the exit status (1 when any)."""
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


def verdict(failures, passed="PASS"):
    """The failures, then `passed` or FAILED; the exit status (1 when any failed)."""
    status = print_failures(failures)
    print(passed if not failures else "FAILED")
    return status
