"""Counted checks for the script tests: check() prints each failed expectation, finish() reports and exits with 1 if
any failed; xml_parameter() reads a parameter of a scene's text."""
import re
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




def xml_parameter(text, name):
    """(type, value) of the parameter `name` in a scene's XML text (the first with that name), or None."""
    match = re.search(rf'<Parameter name="{name}" type="(\w+)" value="([^"]*)"', text)
    return match.groups() if match else None
