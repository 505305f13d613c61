"""Counted checks for the script tests: check() prints each failed expectation, finish() reports and exits with 1 if
any failed."""
import importlib.util
import os
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


def run_study():
    """scripts/run-study.py loaded as a module (its name has a dash), for the tests of its functions."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scripts', 'run-study.py')
    specification = importlib.util.spec_from_file_location('run_study', path)
    module = importlib.util.module_from_spec(specification)
    specification.loader.exec_module(module)
    return module
