"""Counted checks for the script tests: check() prints each failed expectation, finish() reports and exits with 1 if
any failed."""
import sys

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print('FAIL', what)


def finish(success):
    """Prints `success` (or the number of failures) and ends the test."""
    print(success if not failures else f'{len(failures)} failures')
    sys.exit(1 if failures else 0)


