"""
The public API of python-ev3dev2, read from its source by parsing it (never importing it).

    python tests/ev3dev2/conformance/snapshot_api.py [SOURCE]    # write api_2.1.0.json
    python tests/ev3dev2/conformance/snapshot_api.py --compare   # compare our shim with it

SOURCE is the unpacked python-ev3dev2 2.1.0 sdist (the folder that holds ``ev3dev2/``) or
the sdist itself; without it, pip downloads the sdist into a temporary folder.

``describe_package`` turns a package's source into a plain description: per module its
public names (classes; functions with their signatures; constants with their values where
they can be worked out without running anything; imported names with what they refer
to), its star imports, and per class its bases, methods (signatures, defaults as source
text), properties (with or without a setter), class constants, ``__slots__`` and the
attributes its methods set on ``self``.  Module-level ``if`` blocks are read as they run
on an EV3 under CPython 3.11 (``platform == 'ev3'``, ``is_micropython()`` false).

``compare`` checks a description of our shim, made by the same function, against the
snapshot, member by member, looking members up through each class's bases (so a shim
class may inherit a method that upstream's defines itself) and names up through
imports.  Every upstream item counts once in the share; anything the shim adds is a
difference too, except extra imports (a star import then brings one more name).
"""

import argparse
import ast
import glob
import json
import os
import subprocess
import sys
import tarfile
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
SNAPSHOT = os.path.join(HERE, "api_2.1.0.json")
ALLOWLIST = os.path.join(HERE, "api_allowlist.yaml")
VERSION = "2.1.0"

# How module-level conditions evaluate on the brick we simulate.
PLATFORM = "ev3"
KNOWN_CALLS = {"get_current_platform": PLATFORM, "is_micropython": False}
PYTHON_VERSION = (3, 11)
UNKNOWN = object()

# Dunder names that are no one's API.
IGNORED_DUNDERS = {"__doc__", "__module__", "__qualname__", "__slots__"}


def is_public(name):
    if name.startswith("__") and name.endswith("__"):
        return name not in IGNORED_DUNDERS
    return not name.startswith("_")


# -- evaluating constants and conditions without running anything ----------------


class _Scope:
    """Values known so far: a module's constants, and a class body's on top of them."""

    def __init__(self, values=None, parent=None, classes=None):
        self.values = values if values is not None else {}
        self.parent = parent
        self.classes = classes if classes is not None else (parent.classes if parent else {})

    def get(self, name):
        if name in self.values:
            return self.values[name]
        return self.parent.get(name) if self.parent else UNKNOWN


def evaluate(node, scope):
    """The value of a literal-ish expression, or UNKNOWN."""
    try:
        return _evaluate(node, scope)
    except Exception:
        return UNKNOWN


def _evaluate(node, scope):
    if isinstance(node, ast.Constant):
        return node.value
    if isinstance(node, ast.Name):
        return scope.get(node.id)
    if isinstance(node, ast.Attribute):
        if isinstance(node.value, ast.Name):
            if node.value.id == "sys" and node.attr == "version_info":
                return PYTHON_VERSION
            if node.value.id in scope.classes:
                return scope.classes[node.value.id].get(node.attr, UNKNOWN)
        return UNKNOWN
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        items = [_evaluate(item, scope) for item in node.elts]
        if any(item is UNKNOWN for item in items):
            return UNKNOWN
        return tuple(items) if isinstance(node, ast.Tuple) else items
    if isinstance(node, ast.Dict):
        keys = [_evaluate(key, scope) for key in node.keys]
        values = [_evaluate(value, scope) for value in node.values]
        if any(item is UNKNOWN for item in keys + values):
            return UNKNOWN
        return dict(zip(keys, values, strict=True))
    if isinstance(node, ast.UnaryOp):
        operand = _evaluate(node.operand, scope)
        if operand is UNKNOWN:
            return UNKNOWN
        return {ast.Not: lambda v: not v, ast.USub: lambda v: -v, ast.UAdd: lambda v: +v}[type(node.op)](
            operand
        )
    if isinstance(node, ast.BinOp):
        left, right = _evaluate(node.left, scope), _evaluate(node.right, scope)
        if left is UNKNOWN or right is UNKNOWN:
            return UNKNOWN
        return _BINARY[type(node.op)](left, right)
    if isinstance(node, ast.BoolOp):
        values = [_evaluate(value, scope) for value in node.values]
        if any(value is UNKNOWN for value in values):
            return UNKNOWN
        return all(values) if isinstance(node.op, ast.And) else any(values)
    if isinstance(node, ast.Compare):
        left = _evaluate(node.left, scope)
        for op, comparator in zip(node.ops, node.comparators, strict=True):
            right = _evaluate(comparator, scope)
            if left is UNKNOWN or right is UNKNOWN:
                return UNKNOWN
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        name = node.func.id
        if name in KNOWN_CALLS and not node.args:
            return KNOWN_CALLS[name]
        if name in ("OrderedDict", "dict") and not node.args and not node.keywords:
            return {}
        if name == "ord" and len(node.args) == 1:
            return ord(_evaluate(node.args[0], scope))
    return UNKNOWN


_BINARY = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.FloorDiv: lambda a, b: a // b,
    ast.Mod: lambda a, b: a % b,
    ast.Pow: lambda a, b: a**b,
    ast.LShift: lambda a, b: a << b,
    ast.RShift: lambda a, b: a >> b,
    ast.BitOr: lambda a, b: a | b,
    ast.BitAnd: lambda a, b: a & b,
}
_COMPARE = {
    ast.Eq: lambda a, b: a == b,
    ast.NotEq: lambda a, b: a != b,
    ast.Lt: lambda a, b: a < b,
    ast.LtE: lambda a, b: a <= b,
    ast.Gt: lambda a, b: a > b,
    ast.GtE: lambda a, b: a >= b,
    ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b,
    ast.Is: lambda a, b: a is b,
    ast.IsNot: lambda a, b: a is not b,
}


class _Reference(str):
    """A constant defined as another module's or class's constant, e.g. ``Sensor.SYSTEM_CLASS_NAME``."""


def _value_text(value):
    if isinstance(value, _Reference):
        return "@ref:" + value  # resolved once every module has been read
    return None if value is UNKNOWN else repr(value)


# -- describing source ---------------------------------------------------------------


def signature(function):
    """'(self, speed, brake=True, *args, **kwargs)': parameter names, kinds and defaults as source."""
    arguments = function.args
    positional = arguments.posonlyargs + arguments.args
    defaults = [None] * (len(positional) - len(arguments.defaults)) + arguments.defaults
    parts = []
    for index, (argument, default) in enumerate(zip(positional, defaults, strict=True)):
        parts.append(argument.arg if default is None else f"{argument.arg}={ast.unparse(default)}")
        if arguments.posonlyargs and index == len(arguments.posonlyargs) - 1:
            parts.append("/")
    if arguments.vararg:
        parts.append("*" + arguments.vararg.arg)
    elif arguments.kwonlyargs:
        parts.append("*")
    for argument, default in zip(arguments.kwonlyargs, arguments.kw_defaults, strict=True):
        parts.append(argument.arg if default is None else f"{argument.arg}={ast.unparse(default)}")
    if arguments.kwarg:
        parts.append("**" + arguments.kwarg.arg)
    return "(" + ", ".join(parts) + ")"


def _decorator_names(function):
    return [ast.unparse(decorator) for decorator in function.decorator_list]


def _is_shim_attribute(node):
    """The shim writes upstream's one-attribute properties as ``name = _attribute(...)`` descriptors."""
    return isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "_attribute"


def _attribute_has_setter(call):
    for keyword in call.keywords:
        if keyword.arg == "writable":
            return not (isinstance(keyword.value, ast.Constant) and keyword.value.value is False)
    return True


class _ModuleReader:
    """Walks one module's top level (and its class bodies) as it would run."""

    def __init__(self, module_name, is_package):
        self.module_name = module_name
        self.package = module_name if is_package else module_name.rpartition(".")[0]
        self.names = {}
        self.star_imports = []
        self.classes = {}
        self.scope = self.scope_module = _Scope(classes={})
        self.class_path = None

    # statements that may be conditional
    def walk(self, statements, define):
        for statement in statements:
            self.statement(statement, define)

    def statement(self, node, define):
        if isinstance(node, ast.If):
            condition = evaluate(node.test, self.scope)
            if condition is UNKNOWN:
                self.walk(node.body, define)
                self.walk(node.orelse, self._only_new(define))
            else:
                self.walk(node.body if condition else node.orelse, define)
        elif isinstance(node, ast.Try):
            self.walk(node.body, define)
            for handler in node.handlers:
                self.walk(handler.body, self._only_new(define))
            self.walk(node.orelse, define)
            self.walk(node.finalbody, define)
        else:
            define(node)

    def _only_new(self, define):
        """Fallback branches (except ImportError, an undecidable else) only add names."""
        known = dict(self.names)

        def define_new(node):
            define(node)
            for name, entry in known.items():
                self.names[name] = entry

        return define_new

    # the module's own statements
    def module_statement(self, node):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.asname:
                    self._set(alias.asname, {"kind": "import", "target": alias.name})
                else:
                    top = alias.name.split(".")[0]
                    self._set(top, {"kind": "import", "target": top})
        elif isinstance(node, ast.ImportFrom):
            source = self._absolute(node)
            for alias in node.names:
                if alias.name == "*":
                    if source not in self.star_imports:
                        self.star_imports.append(source)
                else:
                    self._set(
                        alias.asname or alias.name, {"kind": "import", "target": source + "." + alias.name}
                    )
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            self._set(node.name, {"kind": "function", "signature": signature(node)})
        elif isinstance(node, ast.ClassDef):
            self._set(node.name, {"kind": "class"})
            self.classes[node.name] = self._class(node)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            if node.value is None:
                return
            for target in targets:
                self._assign(target, node.value, self.scope, self._set_constant)

    def _absolute(self, node):
        if not node.level:
            return node.module
        base = self.package.split(".")
        if node.level > 1:
            base = base[: -(node.level - 1)]
        return ".".join(base + ([node.module] if node.module else []))

    def _set(self, name, description):
        self.names[name] = description
        self.scope.values.pop(name, None)

    def _set_constant(self, name, value):
        self.names[name] = {"kind": "constant", "value": _value_text(value)}
        self.scope.values[name] = UNKNOWN if isinstance(value, _Reference) else value

    def reference(self, node, scope):
        """The dotted name a Name or Attribute expression refers to, through imports; or None."""
        if isinstance(node, ast.Attribute):
            base = self.reference(node.value, scope)
            return base + "." + node.attr if base else None
        if not isinstance(node, ast.Name):
            return None
        if scope.values is not self.scope_module.values and node.id in scope.values:
            return self.class_path + "." + node.id
        entry = self.names.get(node.id)
        if entry and entry["kind"] == "import":
            return entry["target"]
        if entry or node.id in self.classes:
            return self.module_name + "." + node.id
        return None

    def _assign(self, target, value_node, scope, set_constant):
        if isinstance(target, ast.Name):
            value = evaluate(value_node, scope)
            if value is UNKNOWN:
                reference = self.reference(value_node, scope)
                value = _Reference(reference) if reference else UNKNOWN
            set_constant(target.id, value)
        elif isinstance(target, (ast.Tuple, ast.List)):
            values = value_node.elts if isinstance(value_node, (ast.Tuple, ast.List)) else None
            for index, element in enumerate(target.elts):
                if values is not None and len(values) == len(target.elts):
                    self._assign(element, values[index], scope, set_constant)
                elif isinstance(element, ast.Name):
                    set_constant(element.id, UNKNOWN)
        elif isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name):
            # LEDS['red_left'] = '...' after LEDS = OrderedDict()
            container = scope.get(target.value.id)
            key = evaluate(target.slice, scope)
            value = evaluate(value_node, scope)
            if isinstance(container, dict) and key is not UNKNOWN and value is not UNKNOWN:
                container[key] = value
                set_constant(target.value.id, container)
            elif container is not UNKNOWN and target.value.id in scope.values:
                set_constant(target.value.id, UNKNOWN)

    # classes
    def _class(self, node):
        description = {
            "bases": [self.qualify(ast.unparse(base)) for base in node.bases],
            "methods": {},
            "properties": {},
            "constants": {},
            "slots": None,
            "attributes": [],
        }
        values = {}
        scope = _Scope(values, parent=self.scope)

        def set_constant(name, value):
            values[name] = value
            description["constants"][name] = _value_text(value)

        def define(member):
            if isinstance(member, (ast.FunctionDef, ast.AsyncFunctionDef)):
                decorators = _decorator_names(member)
                if "property" in decorators:
                    description["properties"][member.name] = "read-only"
                    description["methods"].pop(member.name, None)
                elif any(d == member.name + ".setter" for d in decorators):
                    description["properties"][member.name] = "read-write"
                elif any(d == member.name + ".deleter" for d in decorators):
                    pass
                else:
                    kind = next((d for d in decorators if d in ("staticmethod", "classmethod")), "method")
                    description["methods"][member.name] = f"{kind} {signature(member)}"
                    description["properties"].pop(member.name, None)
            elif isinstance(member, ast.ClassDef):
                description["constants"][member.name] = "class"
            elif isinstance(member, (ast.Assign, ast.AnnAssign)) and member.value is not None:
                targets = member.targets if isinstance(member, ast.Assign) else [member.target]
                for target in targets:
                    if isinstance(target, ast.Name) and target.id == "__slots__":
                        slots = evaluate(member.value, scope)
                        description["slots"] = sorted(s for s in slots if is_public(s)) if slots else []
                    elif isinstance(target, ast.Name) and _is_shim_attribute(member.value):
                        writable = _attribute_has_setter(member.value)
                        description["properties"][target.id] = "read-write" if writable else "read-only"
                    elif (
                        isinstance(target, ast.Name)
                        and isinstance(member.value, ast.Call)
                        and ast.unparse(member.value.func) == "property"
                    ):
                        setter = len(member.value.args) > 1 or any(
                            k.arg == "fset" for k in member.value.keywords
                        )
                        description["properties"][target.id] = "read-write" if setter else "read-only"
                    else:
                        self._assign(target, member.value, scope, set_constant)

        reader_scope, self.scope = self.scope, scope
        outer_path, self.class_path = self.class_path, self.module_name + "." + node.name
        try:
            self.walk(node.body, define)
        finally:
            self.scope, self.class_path = reader_scope, outer_path
        self.scope.classes[node.name] = values
        description["attributes"] = sorted(_self_attributes(node))
        for kind in ("methods", "properties", "constants"):
            description[kind] = {name: value for name, value in description[kind].items() if is_public(name)}
        return description

    def qualify(self, name):
        """A base class's dotted name as what it refers to (through this module's imports)."""
        head, _, rest = name.partition(".")
        if head in self.classes or (head in self.names and self.names[head]["kind"] == "class"):
            target = self.module_name + "." + head
        elif head in self.names and self.names[head]["kind"] == "import":
            target = self.names[head]["target"]
        else:
            target = head
        return target + ("." + rest if rest else "")


def _self_attributes(class_node):
    """Names every method of the class (nested functions included) assigns on its first parameter."""
    names = set()
    for member in class_node.body:
        if not isinstance(member, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        parameters = member.args.posonlyargs + member.args.args
        if not parameters or "staticmethod" in _decorator_names(member):
            continue
        this = parameters[0].arg
        for node in ast.walk(member):
            targets = []
            if isinstance(node, ast.Assign):
                targets = node.targets
            elif isinstance(node, (ast.AugAssign, ast.AnnAssign)):
                targets = [node.target]
            for target in targets:
                for element in target.elts if isinstance(target, ast.Tuple) else [target]:
                    if (
                        isinstance(element, ast.Attribute)
                        and isinstance(element.value, ast.Name)
                        and element.value.id == this
                    ):
                        names.add(element.attr)
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Name)
                and node.func.id == "setattr"
                and len(node.args) >= 2
                and isinstance(node.args[0], ast.Name)
                and node.args[0].id == this
                and isinstance(node.args[1], ast.Constant)
            ):
                names.add(node.args[1].value)
    return {name for name in names if is_public(name)}


def describe_module(path, module_name):
    with open(path, encoding="utf-8") as file:
        tree = ast.parse(file.read(), filename=path)
    reader = _ModuleReader(module_name, os.path.basename(path) == "__init__.py")
    reader.walk(tree.body, reader.module_statement)
    names = {name: entry for name, entry in reader.names.items() if is_public(name)}
    return {"names": names, "star_imports": reader.star_imports, "classes": reader.classes}


def describe_package(source, package="ev3dev2"):
    """{'modules': {dotted name: description}} for every module of the package in folder ``source``."""
    root = os.path.join(source, package)
    modules = {}
    for path in sorted(glob.glob(os.path.join(root, "**", "*.py"), recursive=True)):
        relative = os.path.relpath(path, source)[: -len(".py")].split(os.sep)
        if relative[-1] == "__init__":
            relative = relative[:-1]
        modules[".".join(relative)] = describe_module(path, ".".join(relative))
    _resolve_imports(modules)
    return {"package": package, "modules": modules}


def _resolve_imports(modules):
    """Imports from inside the package name the place where the thing is defined."""

    def resolve(target, seen=()):
        if target in modules:
            return target
        module, _, name = target.rpartition(".")
        entry = modules.get(module, {}).get("names", {}).get(name)
        if entry and entry["kind"] == "import" and target not in seen:
            return resolve(entry["target"], (*seen, target))
        return target

    for module in modules.values():
        for entry in module["names"].values():
            if entry["kind"] == "import":
                entry["target"] = resolve(entry["target"])
        for description in module["classes"].values():
            description["bases"] = [resolve(base) for base in description["bases"]]

    def constant(reference, depth=0):
        """The value (text) of the constant a reference names, or None."""
        reference = resolve(reference)
        owner, _, name = reference.rpartition(".")
        if depth > 20:
            return None
        if owner in modules:
            entry = modules[owner]["names"].get(name)
            value = entry.get("value") if entry and entry["kind"] == "constant" else None
        else:
            module, _, class_name = owner.rpartition(".")
            cls = modules.get(module, {}).get("classes", {}).get(class_name)
            if cls is None:
                return None
            value = cls["constants"].get(name)
            if value is None and name not in cls["constants"]:
                for base in cls["bases"]:
                    value = constant(base + "." + name, depth + 1)
                    if value is not None:
                        break
        if value is not None and value.startswith("@ref:"):
            return constant(value[5:], depth + 1)
        return value

    for module in modules.values():
        for entry in module["names"].values():
            if entry["kind"] == "constant" and (entry["value"] or "").startswith("@ref:"):
                entry["value"] = constant(entry["value"][5:])
        for description in module["classes"].values():
            for name, value in description["constants"].items():
                if (value or "").startswith("@ref:"):
                    description["constants"][name] = constant(value[5:])


# -- comparing -------------------------------------------------------------------------


class Api:
    """A package description, with its classes looked up by qualified name."""

    def __init__(self, description):
        self.modules = description["modules"]
        self.classes = {
            module_name + "." + class_name: cls
            for module_name, module in self.modules.items()
            for class_name, cls in module["classes"].items()
        }

    def public_bases(self, qualified):
        """The direct bases as a user sees them: private bases replaced by their own bases."""
        result = []
        for base in self.classes[qualified]["bases"]:
            short = base.rpartition(".")[2]
            if base in self.classes and not is_public(short):
                result.extend(b for b in self.public_bases(base) if b not in result)
            elif base not in ("object", "builtins.object") and base not in result:
                result.append(base)
        return result

    def mro(self, qualified):
        """The class and its ancestors inside the package (C3 order)."""
        if qualified not in self.classes:
            return []
        bases = [self.mro(base) for base in self.classes[qualified]["bases"] if base in self.classes]
        sequences = [s for s in bases if s] + [
            [b for b in self.classes[qualified]["bases"] if b in self.classes]
        ]
        result = [qualified]
        while any(sequences):
            sequences = [s for s in sequences if s]
            for sequence in sequences:
                head = sequence[0]
                if not any(head in s[1:] for s in sequences):
                    break
            else:  # inconsistent: fall back to depth-first order
                head = sequences[0][0]
            result.append(head)
            sequences = [[c for c in s if c != head] for s in sequences]
        return result

    @staticmethod
    def own_members(cls):
        """{name: description} of what a class body defines itself (public names only)."""
        members = {}
        for name in cls["attributes"]:
            members[name] = "attribute"
        for name, value in cls["constants"].items():
            members[name] = (
                "class" if value == "class" else "constant" if value is None else f"constant = {value}"
            )
        for name, kind in cls["properties"].items():
            members[name] = f"property ({kind})"
        for name, kind in cls["methods"].items():
            members[name] = kind
        if cls["slots"] is not None:
            members["__slots__"] = "slots " + ", ".join(cls["slots"])
        return {name: value for name, value in members.items() if is_public(name) or name == "__slots__"}

    def lookup(self, qualified, name):
        """What ``Class.name`` is, looking through the bases; instance attributes last."""
        found_attribute = None
        for ancestor in self.mro(qualified):
            member = self.own_members(self.classes[ancestor]).get(name)
            if member == "attribute":
                found_attribute = found_attribute or member
            elif member is not None:
                return member
        return found_attribute

    def items(self):
        """{key: description} of every public item, each counted once (where it is defined)."""
        items = {}
        for module_name, module in self.modules.items():
            if not _module_is_public(module_name):
                continue
            items[module_name] = "module"
            for name, entry in module["names"].items():
                if is_public(name):
                    items[f"{module_name}:{name}"] = _name_text(entry)
            for source in module["star_imports"]:
                items[f"{module_name}:from {source} import *"] = "star import"
            for class_name, cls in module["classes"].items():
                if not is_public(class_name):
                    continue
                qualified = f"{module_name}.{class_name}"
                items[f"{module_name}:{class_name}.__bases__"] = "bases " + ", ".join(
                    self.public_bases(qualified)
                )
                for member, value in self.own_members(cls).items():
                    if value == "attribute":  # self.mode = ... sets an inherited property
                        value = self.lookup(qualified, member)
                        if value != "attribute":
                            continue
                    items[f"{module_name}:{class_name}.{member}"] = value
        return items

    def value_of(self, key):
        """An item's description in this API (members found through the bases), or None."""
        module_name, _, rest = key.partition(":")
        module = self.modules.get(module_name)
        if module is None:
            return None
        if not rest:
            return "module"
        if rest.startswith("from ") and rest.endswith(" import *"):
            return "star import" if rest[5:-9] in module["star_imports"] else None
        name, _, member = rest.partition(".")
        if not member:
            entry = module["names"].get(name)
            return _name_text(entry) if entry else None
        if name not in module["classes"]:
            return None
        qualified = f"{module_name}.{name}"
        if member == "__bases__":
            return "bases " + ", ".join(self.public_bases(qualified))
        return self.lookup(qualified, member)


def _module_is_public(module_name):
    return all(is_public(part) or part == "_platform" for part in module_name.split("."))


def _name_text(entry):
    kind = entry["kind"]
    if kind == "function":
        return "function " + entry["signature"]
    if kind == "constant":
        return "constant" if entry["value"] is None else "constant = " + entry["value"]
    if kind == "import":
        return "import " + entry["target"]
    return kind


def compare(upstream, shim):
    """(matched keys, differences): each difference is (key, upstream's description, the shim's)."""
    upstream_api, shim_api = Api(upstream), Api(shim)
    matched, differences = [], []
    upstream_items = upstream_api.items()
    for key, theirs in sorted(upstream_items.items()):
        ours = shim_api.value_of(key)
        if ours == theirs:
            matched.append(key)
        else:
            differences.append((key, theirs, ours))
    for key, ours in sorted(shim_api.items().items()):
        if key in upstream_items or ours.startswith("import "):
            continue
        theirs = upstream_api.value_of(key)
        if theirs != ours:
            differences.append((key, theirs, ours))
    differences.extend(_inherited_extras(upstream_api, shim_api, upstream_items))
    return matched, differences, len(upstream_items)


def _inherited_extras(upstream_api, shim_api, upstream_items):
    """Members a shim class gets from a private base where upstream's class has none or another."""
    found = []
    for module_name, module in shim_api.modules.items():
        if not _module_is_public(module_name):
            continue
        for class_name in filter(is_public, module["classes"]):
            qualified = f"{module_name}.{class_name}"
            visible = {
                name for c in shim_api.mro(qualified) for name in shim_api.own_members(shim_api.classes[c])
            }
            own = shim_api.own_members(shim_api.classes[qualified])
            for name in sorted(visible - set(own)):
                key = f"{module_name}:{class_name}.{name}"
                ours, theirs = shim_api.lookup(qualified, name), upstream_api.value_of(key)
                if key in upstream_items or ours == theirs:
                    continue
                public_bases = [b for b in shim_api.public_bases(qualified) if b in shim_api.classes]
                if any(shim_api.lookup(base, name) == ours for base in public_bases):
                    continue  # it comes from a public base, and is reported there
                found.append((key, theirs, ours))
    return found


def load_allowlist(path=ALLOWLIST):
    """{item: reason} from the allow-list (YAML mapping)."""
    import yaml

    with open(path, encoding="utf-8") as file:
        entries = yaml.safe_load(file) or {}
    return {str(key): str(reason) for key, reason in entries.items()}


def allowed_by(key, allowlist):
    """The allow-list entry that covers a difference's key (an entry covers everything under it)."""
    for entry in allowlist:
        if key == entry or (key.startswith(entry) and key[len(entry)] in ":."):
            return entry
    return None


class Report:
    """The shim against the snapshot: the share matched, and which differences are not allowed."""

    def __init__(self, snapshot_path=SNAPSHOT, shim_source=REPO, allowlist_path=ALLOWLIST):
        with open(snapshot_path, encoding="utf-8") as file:
            upstream = json.load(file)
        self.allowlist = load_allowlist(allowlist_path)
        self.matched, self.differences, self.total = compare(upstream, describe_package(shim_source))
        self.allowed = [d for d in self.differences if allowed_by(d[0], self.allowlist)]
        self.unexpected = [d for d in self.differences if not allowed_by(d[0], self.allowlist)]
        used = {allowed_by(d[0], self.allowlist) for d in self.allowed}
        self.stale = sorted(entry for entry in self.allowlist if entry not in used)

    def summary(self):
        share = 100 * len(self.matched) / self.total
        return (
            f"{len(self.matched)} of {self.total} public API items match ({share:.1f}%), "
            f"{len(self.allowed)} allowed differences"
        )

    def details(self):
        lines = [f"allow-list: {len(self.allowlist)} entries ({os.path.relpath(ALLOWLIST, REPO)})"]
        for key, theirs, ours in self.unexpected:
            lines.append(
                f"  not allowed: {key}\n      python-ev3dev2: {theirs}\n      shim:           {ours}"
            )
        for entry in self.stale:
            lines.append(f"  stale allow-list entry (no such difference any more): {entry}")
        return "\n".join(lines)


# -- the command line ---------------------------------------------------------------------


def download_source(folder):
    """Download and unpack the python-ev3dev2 sdist into ``folder``; returns the unpacked folder."""
    subprocess.run(
        [sys.executable, "-m", "pip", "download", "--no-deps", "--no-binary", ":all:", "--dest", folder,
         f"python-ev3dev2=={VERSION}"],
        check=True,
    )  # fmt: skip
    (archive,) = glob.glob(os.path.join(folder, "python-ev3dev2-*.tar.gz"))
    return unpack(archive, folder)


def unpack(archive, folder):
    with tarfile.open(archive) as tar:
        tar.extractall(folder, filter="data")
    return os.path.join(folder, f"python-ev3dev2-{VERSION}")


def write_snapshot(source, path=SNAPSHOT):
    description = describe_package(source)
    description["version"] = VERSION
    with open(path, "w", encoding="utf-8") as file:
        json.dump(description, file, indent=1, sort_keys=True)
        file.write("\n")
    return description


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].strip())
    parser.add_argument("source", nargs="?", help="python-ev3dev2 2.1.0 source folder or sdist")
    parser.add_argument("--compare", action="store_true", help="compare the shim with the snapshot")
    args = parser.parse_args(argv)

    if args.compare:
        report = Report()
        print(report.summary())
        print(report.details())
        return 1 if report.unexpected or report.stale else 0

    with tempfile.TemporaryDirectory() as folder:
        if args.source is None:
            source = download_source(folder)
        elif os.path.isfile(args.source):
            source = unpack(args.source, folder)
        else:
            source = args.source
        description = write_snapshot(source)
    print(f"wrote {os.path.relpath(SNAPSHOT)}: {len(description['modules'])} modules")
    return 0


if __name__ == "__main__":
    sys.exit(main())
