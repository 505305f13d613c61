#!/usr/bin/env python3
"""Property-based input test: every scene made invalid by one mutation is rejected cleanly.

Starting from the scenes of an xml folder, a fixed-seed generator makes N scenes, each with exactly one mutation that
makes it invalid by construction (a missing attribute, a wrong type, a value out of range, a duplicate, an unknown or
misplaced key, ...). The keys, types, ranges and allowed strings come from `spatula --print-parameters`. For each
mutated scene, `spatula <scene> --validate-only`, run in an empty working directory, must

  * exit with code 2,
  * name the mutated key on stderr by its full path in quotes, e.g. 'Geometry/l_p' or 'Loading/Rotation Steps',
  * print no crash text (uncaught exceptions, signals, MPI aborts, Teuchos stack traces),
  * write nothing into the working directory.

A scene the program rejects as it is (e.g. one whose restart file is not in the empty directory) is skipped, with a
note: it has no valid state to mutate. The mutated scene files lie in a temporary folder apart from the working
directories; --keep-failures copies the failing ones, each headed by a comment naming its mutation.

usage: mutated_scenes.py <spatula executable> <xml folder> [--cases N] [--seed S] [--jobs J] [--keep-failures DIR]
Exit code 0 when every case passes, 1 otherwise.
"""
import argparse
import collections
import concurrent.futures
import copy
import dataclasses
import math
import os
import pathlib
import random
import re
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ElementTree

TIMEOUT_SECONDS = 20
# A single-process MPI start without the helper daemon and network transports: 0.13 s a run instead of 0.4. Each
# run gets its own session folder (isolated singletons sharing one race on it), outside the working directory.
FAST_SINGLETON = {"OMPI_MCA_ess_singleton_isolated": "1", "OMPI_MCA_btl": "self", "OMPI_MCA_pml": "ob1"}
HUGE_LENGTH = 100_000
TYPES = ("double", "int", "bool", "string")
OTHER_TYPES = ("Array(double)", "complex")   # a Teuchos type no key has; a type Teuchos does not know
CRASH_TEXTS = ("terminate called", "segmentation", "aborted", "core dumped", "bad_alloc", "std::",
               "throw test that evaluated to true", "mpi_abort", "stack trace")
INT_OVERFLOWS = ("2147483648", "4294967298", "-2147483649")
FREE_STRINGS_THAT_MUST_NOT_BE_EMPTY = {"Output/directory"}
FREE_STRINGS_WITH_A_LENGTH_LIMIT = {"Output/directory", "Loading/restart file", "Loading/checkpoints at theta_y"}
INVENTED_NAMES = ("frobnicate", "l_q", "levels", "tolerence", "colour", "extra", "Meshing", "max iterations")
INT_LITERAL = re.compile(r"\s*[+-]?\d+\s*")
PARAMETER_LINE = re.compile(r"^(?P<indent> *)(?P<name>.+?) : (?P<type>double|int|bool|string) = (?P<value>.*)$")
ALLOWED = re.compile(r"\((?P<allowed>(?:double|int) in [\[(][^,()]+, [^,()]+[\])]|one of: [^()]*|true or false"
                     r"|any string)\)\s*$")
RANGE = re.compile(r"(?:double|int) in (?P<open>[\[(])(?P<lower>[^,]+), (?P<upper>[^\])]+)(?P<close>[\])])")


def join(path, name):
    return f"{path}/{name}" if path else name


def parent_of(path):
    return path.rpartition("/")[0]


@dataclasses.dataclass
class Key:
    """A declared parameter: its full path, type, default and allowed values."""
    path: str
    type: str
    default: str
    lower: float = -math.inf
    upper: float = math.inf
    lower_open: bool = True
    upper_open: bool = True
    choices: tuple = ()

    def __post_init__(self):
        self.list_path, _, self.name = self.path.rpartition("/")


class Declarations:
    """What `--print-parameters` declares: keys by path, and sublists by path ('' is the top level)."""

    def __init__(self, text):
        self.keys, self.free_form, self.lists = {}, set(), [""]
        stack, last_key, last_list = [(-1, "")], None, ""
        for line in text.splitlines():
            stripped, indent = line.strip(), len(line) - len(line.lstrip(" "))
            if stripped.startswith("#"):
                match = ALLOWED.search(stripped)
                if last_key and match:
                    self._read_allowed(last_key, match.group("allowed"))
                last_key = None
                continue
            if stripped == "[empty list]":
                self.free_form.add(last_list)
                continue
            match = PARAMETER_LINE.match(line)
            if not match and not stripped.endswith(" ->"):
                continue
            while stack[-1][0] >= indent:
                stack.pop()
            if match:
                default = match["value"]
                if match["type"] == "bool":   # printed as 1 or 0
                    default = {"1": "true", "0": "false"}.get(default, default)
                last_key = Key(join(stack[-1][1], match["name"]), match["type"], default)
                self.keys[last_key.path] = last_key
            else:
                last_list = join(stack[-1][1], stripped[:-3])
                self.lists.append(last_list)
                stack.append((indent, last_list))
                last_key = None

    @staticmethod
    def _read_allowed(key, allowed):
        if allowed.startswith("one of: "):
            key.choices = tuple(allowed[len("one of: "):].split(", "))
        elif match := RANGE.fullmatch(allowed):
            key.lower, key.upper = float(match["lower"]), float(match["upper"])
            key.lower_open, key.upper_open = match["open"] == "(", match["close"] == ")"

    def names_in(self, list_path):
        """The names declared in a list, in a fixed order (the generated cases depend on it)."""
        return [path.rpartition("/")[2] for path in [*self.keys, *self.lists] if path and parent_of(path) == list_path]


def scene_entries(root):
    """{path: (element, parent)} for every Parameter and ParameterList of a scene."""
    entries = {}

    def walk(element, path):
        for child in element:
            if child.tag in ("Parameter", "ParameterList") and "name" in child.attrib:
                entries[join(path, child.get("name"))] = (child, element)
                if child.tag == "ParameterList":
                    walk(child, join(path, child.get("name")))
    walk(root, "")
    return entries


def ensure_list(root, list_path):
    """The scene's ParameterList at list_path, added (empty, hence valid) where missing."""
    element = root
    for name in filter(None, list_path.split("/")):
        found = [child for child in element if child.tag == "ParameterList" and child.get("name") == name]
        element = found[0] if found else ElementTree.SubElement(element, "ParameterList", name=name)
    return element


def pick_from(random_generator, present, absent):
    """One of the targets the scene has or one it leaves out, each half the time where both exist."""
    pools = [pool for pool in (present, absent) if pool]
    return random_generator.choice(random_generator.choice(pools)) if pools else None


def pick_parameter(random_generator, root, declarations, accept=lambda key: True):
    """(key, element, parent) of a declared Parameter; one the scene leaves out is added with its default."""
    entries = scene_entries(root)
    candidates = [key for key in declarations.keys.values() if accept(key)]
    present = [key for key in candidates if key.path in entries and entries[key.path][0].tag == "Parameter"]
    key = pick_from(random_generator, present, [key for key in candidates if key.path not in entries])
    if key is None:
        return None
    if key.path in entries:
        return (key, *entries[key.path])
    parent = ensure_list(root, key.list_path)
    return key, ElementTree.SubElement(parent, "Parameter", name=key.name, type=key.type, value=key.default), parent


def pick_sublist(random_generator, root, declarations):
    """(path, element, parent) of a declared sublist (not the top level); one the scene leaves out is added."""
    entries = scene_entries(root)
    candidates = [path for path in declarations.lists if path]
    present = [path for path in candidates if path in entries and entries[path][0].tag == "ParameterList"]
    path = pick_from(random_generator, present, [path for path in candidates if path not in entries])
    parent = ensure_list(root, parent_of(path))
    return path, ensure_list(root, path), parent


def shown(value):
    return repr(value) if len(value) <= 24 else f"'{value[:12]}...' ({len(value)} chars)"


def outside_values(key):
    """Values just outside the declared range (and, for int keys, outside int)."""
    values = []
    if key.type == "int":
        if math.isfinite(key.lower):
            values.append(str(math.floor(key.lower) if key.lower_open else math.ceil(key.lower) - 1))
        if math.isfinite(key.upper):
            values.append(str(math.ceil(key.upper) if key.upper_open else math.floor(key.upper) + 1))
        return values + list(INT_OVERFLOWS)
    for bound, is_open, direction in ((key.lower, key.lower_open, -1), (key.upper, key.upper_open, 1)):
        if math.isfinite(bound):
            values += [repr(bound + direction * 1e-6 * max(1.0, abs(bound)))] + ([repr(bound)] if is_open else [])
    return values


def must_not_be_empty(key):
    if key.type != "string":
        return True
    return "" not in key.choices if key.choices else key.path in FREE_STRINGS_THAT_MUST_NOT_BE_EMPTY


# Mutations that give a key an invalid value: (the keys they apply to, the invalid values of such a key).
BAD_VALUES = {
    "out-of-range": (outside_values, outside_values),
    "nan": (lambda key: key.type == "double", lambda key: ["nan", "NaN"]),
    "inf": (lambda key: key.type == "double", lambda key: ["inf", "-inf", "1e999"]),
    "empty": (must_not_be_empty, lambda key: [""]),
    "huge-string": (lambda key: key.type == "string" and (key.choices or key.path in FREE_STRINGS_WITH_A_LENGTH_LIMIT),
                    lambda key: [(pattern * HUGE_LENGTH)[:HUGE_LENGTH] for pattern in ("x", "a/", "0123456789")]),
}


def bad_value(kind):
    applies, values = BAD_VALUES[kind]

    def mutate(random_generator, root, declarations):
        picked = pick_parameter(random_generator, root, declarations, applies)
        if picked:
            key, element, _ = picked
            element.attrib.update(type=key.type, value=random_generator.choice(values(key)))
            return key.path, f"value {shown(element.get('value'))}"
    return mutate


def missing(attribute):
    def mutate(random_generator, root, declarations):
        key, element, _ = pick_parameter(random_generator, root, declarations)
        element.attrib.pop(attribute, None)
        return key.path, f"{attribute} attribute removed"
    return mutate


def wrong_type(random_generator, root, declarations):
    key, element, _ = pick_parameter(random_generator, root, declarations)
    value = element.get("value", "")
    promoted = key.type == "double" and INT_LITERAL.fullmatch(value)   # an int is a valid double
    options = [("type", name) for name in TYPES + OTHER_TYPES if name != key.type and not (promoted and name == "int")]
    options += [("value", literal) for literal in {"double": ["abc"], "int": ["abc", "1.5"], "bool": ["maybe"]}
                .get(key.type, [])]
    attribute, new = random_generator.choice(options)
    element.set(attribute, new)
    return key.path, f"{attribute} changed: type {element.get('type')!r}, value {shown(element.get('value'))}"


def duplicate_key(random_generator, root, declarations):
    key, element, parent = pick_parameter(random_generator, root, declarations)
    twin = copy.deepcopy(element)
    other_values = [key.default, *key.choices] + (["true", "false"] if key.type == "bool" else [])
    twin.set("value", random_generator.choice([element.get("value", ""), *other_values]))
    parent.insert(list(parent).index(element) + random_generator.choice([1, len(parent)]), twin)
    return key.path, f"values {shown(element.get('value'))} and {shown(twin.get('value'))}"


def duplicate_sublist(random_generator, root, declarations):
    path, element, parent = pick_sublist(random_generator, root, declarations)
    parent.insert(list(parent).index(element) + random_generator.choice([1, len(parent)]), copy.deepcopy(element))
    return path, f"{len(element)} entries, twice"


def unknown_key(random_generator, root, declarations):
    list_path = random_generator.choice([path for path in declarations.lists if path not in declarations.free_form])
    declared = declarations.names_in(list_path)
    near_misses = [variant for name in declared for variant in (name.swapcase(), name + " ")]
    names = [name for name in [*INVENTED_NAMES, "", *near_misses] if name not in declared]
    name = random_generator.choice(names)
    parent = ensure_list(root, list_path)
    if random_generator.random() < 0.25:
        ElementTree.SubElement(parent, "ParameterList", name=name)
        return join(list_path, name), "unknown sublist"
    type_name, value = random_generator.choice([("double", "1"), ("int", "3"), ("bool", "true"), ("string", "yes")])
    ElementTree.SubElement(parent, "Parameter", name=name, type=type_name, value=value)
    return join(list_path, name), f"unknown {type_name} {value!r}"


def wrong_sublist(random_generator, root, declarations):
    variant = random_generator.choice(["moved", "value for a sublist", "sublist for a value"])
    if variant == "value for a sublist":
        path, element, parent = pick_sublist(random_generator, root, declarations)
        type_name, value = random_generator.choice([("string", "coarse"), ("int", "1"), ("bool", "true")])
        replacement = ElementTree.Element("Parameter", name=element.get("name"), type=type_name, value=value)
        parent[list(parent).index(element)] = replacement
        return path, f"{type_name} {value!r} where a sublist is declared"
    key, element, parent = pick_parameter(random_generator, root, declarations)
    if variant == "sublist for a value":
        replacement = ElementTree.Element("ParameterList", name=key.name)
        if random_generator.random() < 0.5:
            replacement.append(copy.deepcopy(element))
        parent[list(parent).index(element)] = replacement
        return key.path, f"sublist where a value ({key.type}) is declared"
    targets = [path for path in declarations.lists if path != key.list_path and path not in declarations.free_form
               and key.name not in declarations.names_in(path)]
    target = random_generator.choice(targets)
    parent.remove(element)
    ensure_list(root, target).append(element)
    return join(target, key.name), f"moved from {key.list_path or '/'!r} to {target or '/'!r}"


MUTATIONS = {"no-value": missing("value"), "no-type": missing("type"), "wrong-type": wrong_type,
             **{kind: bad_value(kind) for kind in BAD_VALUES}, "duplicate-key": duplicate_key,
             "duplicate-sublist": duplicate_sublist, "unknown-key": unknown_key, "wrong-sublist": wrong_sublist}


# Hostile files: bounds the program checks on a scene's text before the XML parser reads it (a parser that recurses
# per nesting level overflows its stack on sublists nested 20,000 deep). Each returns (expected text on stderr, detail,
# the file's text) for a valid scene's text.
def nested_too_deep(random_generator, text):
    depth = random_generator.choice([33, 100, 2000, 20000])
    inner = '<ParameterList name="x">' * depth + '</ParameterList>' * depth
    return "nested more than 32 deep", f"{depth} nested sublists", text.replace("</ParameterList>", inner + "</ParameterList>", 1)


def too_large(random_generator, text):
    size = random_generator.choice([(1 << 20) + 1, 3 << 20])
    return "bytes (at most 1048576", f"a comment of {size} bytes", text.replace(">", "><!--" + "x" * size + "-->", 1)


def too_many_elements(random_generator, text):
    count = random_generator.choice([10001, 15000])
    many = "".join(f'<Parameter name="p{k}" type="int" value="1"/>' for k in range(count))
    return "more than 10000 elements", f"{count} parameters", text.replace("</ParameterList>", many + "</ParameterList>", 1)


def value_too_long(random_generator, text):
    length = random_generator.choice([4097, 100000])
    long_value = f'<Parameter name="long" type="string" value="{"v" * length}"/>'
    return f"/long': a value of {length} characters", f"a value of {length} characters", \
        text.replace("</ParameterList>", long_value + "</ParameterList>", 1)


HOSTILE = {"hostile-depth": nested_too_deep, "hostile-size": too_large, "hostile-count": too_many_elements,
           "hostile-value": value_too_long}

Case = collections.namedtuple("Case", "number scene kind key detail xml")


def generate(count, seed, scenes, declarations):
    """`count` cases, each one scene with one mutation that makes it invalid (a kind without a target is redrawn)."""
    random_generator = random.Random(seed)
    cases = []
    while len(cases) < count:
        kind = random_generator.choice(list(MUTATIONS) + list(HOSTILE))
        scene, text = random_generator.choice(scenes)
        if kind in HOSTILE:
            cases.append(Case(len(cases) + 1, scene, kind, *HOSTILE[kind](random_generator, text)))
            continue
        root = ElementTree.fromstring(text)
        mutated = MUTATIONS[kind](random_generator, root, declarations)
        if mutated:
            ElementTree.indent(root)
            cases.append(Case(len(cases) + 1, scene, kind, *mutated, ElementTree.tostring(root, encoding="unicode")))
    return cases


def run(executable, xml, scene_file):
    """(exit code, stdout, stderr, files written) of `spatula <scene> --validate-only` in an empty directory."""
    scene_file.write_text(xml)
    with tempfile.TemporaryDirectory(prefix="spatula-mutated-work-") as work, \
            tempfile.TemporaryDirectory(prefix="spatula-mutated-mpi-") as session:
        environment = {**os.environ, **FAST_SINGLETON, "OMPI_MCA_orte_tmpdir_base": session}
        try:
            result = subprocess.run([executable, str(scene_file), "--validate-only"], cwd=work, env=environment,
                                    stdin=subprocess.DEVNULL, capture_output=True, timeout=TIMEOUT_SECONDS)
            exit_code, output, errors = result.returncode, result.stdout, result.stderr
        except subprocess.TimeoutExpired as timeout:
            exit_code, output, errors = f"timeout after {TIMEOUT_SECONDS} s", timeout.stdout, timeout.stderr
        except OSError as error:   # e.g. the program is being rebuilt
            exit_code, output, errors = f"cannot run: {error}", b"", b""
        written = sorted(os.listdir(work))
    return (exit_code, *(text.decode(errors="replace") if text else "" for text in (output, errors)), written)


def check(case, exit_code, output, errors, written):
    """What is wrong with the program's answer to a case (nothing when it passes)."""
    problems = [] if exit_code == 2 else [f"exit code {exit_code}"]
    if (case.key if case.kind in HOSTILE else f"'{case.key}'") not in errors:
        problems.append("bound not named" if case.kind in HOSTILE else "key not named")
    problems += [f"crash text {text!r}" for text in CRASH_TEXTS if text in (output + errors).lower()]
    if written:
        problems.append("wrote " + ", ".join(written[:5]))
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("executable", help="the spatula program")
    parser.add_argument("xml_folder", help="folder of valid scenes (searched recursively)")
    parser.add_argument("--cases", type=int, default=400)
    parser.add_argument("--seed", type=int, default=20261202)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--keep-failures", metavar="DIR", help="copy each failing mutated scene here")
    arguments = parser.parse_args()
    executable = os.path.abspath(arguments.executable)   # the cases run in other directories
    start = time.monotonic()
    printed = subprocess.run([executable, "--print-parameters"], capture_output=True, text=True,
                             timeout=TIMEOUT_SECONDS)
    declarations = Declarations(printed.stdout)
    if printed.returncode != 0 or not declarations.keys:
        sys.exit(f"cannot read the declared parameters from '{executable} --print-parameters' "
                 f"(exit code {printed.returncode}):\n{printed.stderr}")
    folder = pathlib.Path(arguments.xml_folder)
    scenes = [(str(path.relative_to(folder)), ElementTree.tostring(ElementTree.parse(path).getroot(), "unicode"))
              for path in sorted(folder.rglob("*.xml"))]

    tally = collections.defaultdict(lambda: [0, 0])
    with tempfile.TemporaryDirectory(prefix="spatula-mutated-scenes-") as scene_folder, \
            concurrent.futures.ThreadPoolExecutor(arguments.jobs) as pool:
        # The property needs valid scenes: one that the program rejects as it is has nothing to mutate.
        answers = pool.map(lambda numbered: run(executable, numbered[1][1], pathlib.Path(
            scene_folder, f"scene-{numbered[0]}.xml")), enumerate(scenes))
        valid = []
        for scene, (exit_code, _, errors, written) in zip(scenes, answers):
            if exit_code == 0 and not written:
                valid.append(scene)
            else:
                print(f"skipped {scene[0]}: not valid in an empty directory: {' '.join(errors[:200].split())}")
        if not valid:
            sys.exit(f"no valid scenes in {folder}")
        cases = generate(arguments.cases, arguments.seed, valid, declarations)
        print(f"{len(cases)} mutated scenes from {len(valid)} scenes, {len(declarations.keys)} declared keys, "
              f"seed {arguments.seed}, {arguments.jobs} jobs")
        answers = pool.map(lambda case: run(executable, case.xml, pathlib.Path(
            scene_folder, f"case-{case.number:04d}.xml")), cases)
        for case, (exit_code, output, errors, written) in zip(cases, answers):
            problems = check(case, exit_code, output, errors, written)
            tally[case.kind][0] += 1
            tally[case.kind][1] += bool(problems)
            if not problems:
                continue
            print(f"FAIL #{case.number} {case.scene} {case.kind} '{case.key[:80]}' ({case.detail}): "
                  f"{'; '.join(problems)}; exit code {exit_code}; stderr: {' '.join(errors[:300].split())}")
            if arguments.keep_failures:
                kept = pathlib.Path(arguments.keep_failures, f"{case.number:04d}-{case.kind}.xml")
                kept.parent.mkdir(parents=True, exist_ok=True)
                note = f"{case.scene}, {case.kind} '{case.key}': {case.detail}: {'; '.join(problems)}"
                kept.write_text(f"<!-- {note.replace('--', '- -')} -->\n{case.xml}\n")

    failures = sum(failed for _, failed in tally.values())
    print(f"\n{'mutation':<20}{'cases':>7}{'failures':>10}")
    for kind in list(MUTATIONS) + list(HOSTILE):
        print(f"{kind:<20}{tally[kind][0]:>7}{tally[kind][1]:>10}")
    print(f"{'total':<20}{len(cases):>7}{failures:>10}\ntime {time.monotonic() - start:.1f} s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
