"""Check the type hints (.pyi) python/rbsf/__init__.pyi against the live module rbsf, both ways: the
public names and their kinds, each class's members (read-only ones as @property, read-write
ones as annotations, static methods, constructors) and every signature's parameter names and
defaults as pybind11 reports them. Prints what differs and exits 1, else prints ok.

Run: PYTHONPATH=build/python /usr/bin/python3 python/tests/pyi_check.py [path/to/__init__.pyi]
"""

import ast
import inspect
import pathlib
import re
import sys

import rbsf

PYI = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parents[1] / "rbsf" / "__init__.pyi")
tree = ast.parse(PYI.read_text())
problems = []


def public(name):
    return not name.startswith("_")


def is_type_alias(node):
    return (isinstance(node, ast.AnnAssign) and isinstance(node.annotation, ast.Name)
            and node.annotation.id == "TypeAlias")


def defined(body):
    """Names a .pyi body defines: {name: [nodes]} (imports and type aliases left out)."""
    out = {}
    for node in body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            out.setdefault(node.name, []).append(node)
        elif isinstance(node, ast.AnnAssign) and not is_type_alias(node):
            out.setdefault(node.target.id, []).append(node)
        elif isinstance(node, ast.Assign):
            for t in node.targets:
                out.setdefault(t.id, []).append(node)
    return out


def decorators(node):
    return {d.id if isinstance(d, ast.Name) else ast.unparse(d) for d in node.decorator_list}


# 1. Top-level names, both ways, and their kind.
pyi_top = {n: v for n, v in defined(tree.body).items() if public(n)}
live_top = {n for n in dir(rbsf) if public(n)}
for n in sorted(live_top - pyi_top.keys()):
    problems.append(f"top level: {n} is in rbsf, not in the .pyi")
for n in sorted(pyi_top.keys() - live_top):
    problems.append(f"top level: {n} is in the .pyi, not in rbsf")
for n in sorted(live_top & pyi_top.keys()):
    obj, node = getattr(rbsf, n), pyi_top[n][0]
    kind = ("class" if isinstance(obj, type) else "function" if callable(obj) else "constant")
    pyi_kind = {ast.ClassDef: "class", ast.FunctionDef: "function"}.get(type(node), "constant")
    if kind != pyi_kind:
        problems.append(f"{n}: a {kind} in rbsf, a {pyi_kind} in the .pyi")


# 2. Signatures: parameter names and defaults as pybind11 (or inspect) reports them.
def split_top(text):
    parts, depth, cur = [], 0, ""
    for ch in text:
        if ch in "([{<":
            depth += 1
        elif ch in ")]}>":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        parts.append(cur.strip())
    return parts


def live_signatures(func, name):
    """[(param names, {name: default text})] of each overload, self left out."""
    doc = func.__doc__ or ""
    sigs = []
    for m in re.finditer(rf"(?:^|\n)(?:\d+\. )?{re.escape(name)}\(", doc):
        start = m.end()
        depth, i = 1, start
        while depth:
            depth += {"(": 1, ")": -1}.get(doc[i], 0)
            i += 1
        params, defaults = [], {}
        for p in split_top(doc[start:i - 1]):
            pname = p.split(":")[0].split("=")[0].strip()
            if pname in ("self", "*args", "**kwargs"):
                continue
            params.append(pname)
            if " = " in p:
                defaults[pname] = p.split(" = ", 1)[1]
        if params or defaults or "Overloaded function" not in doc:  # not the header line
            sigs.append((params, defaults))
    if not sigs:  # a Python function
        sig = inspect.signature(func)
        sigs.append(([p for p in sig.parameters if p != "self"],
                     {p.name: repr(p.default) for p in sig.parameters.values()
                      if p.default is not inspect.Parameter.empty}))
    return sigs


def pyi_signature(node):
    a = node.args
    positional = a.posonlyargs + a.args
    names = [x.arg for x in positional + a.kwonlyargs]
    if names and names[0] in ("self", "cls"):
        names = names[1:]
    defaults = {}
    for arg, d in zip(positional[len(positional) - len(a.defaults):], a.defaults):
        defaults[arg.arg] = d
    for arg, d in zip(a.kwonlyargs, a.kw_defaults):
        if d is not None:
            defaults[arg.arg] = d
    return names, defaults


def same_default(pyi_node, live_text):
    literal = True
    try:
        live_value = ast.literal_eval(live_text)
    except (ValueError, SyntaxError):
        literal = False
    if isinstance(pyi_node, ast.Constant) and pyi_node.value is Ellipsis:
        # `...`: an object default (pybind11 shows its repr) or a mutable one ([]).
        return not literal or isinstance(live_value, (list, dict, set))
    pyi_value = ast.literal_eval(pyi_node)
    return literal and type(pyi_value) is type(live_value) and pyi_value == live_value


def check_signatures(label, func, name, nodes):
    live = live_signatures(func, name)
    declared = [pyi_signature(n) for n in nodes]
    if len(live) != len(declared):
        problems.append(f"{label}: {len(live)} overload(s) in rbsf, {len(declared)} in the .pyi")
        return
    for k, ((lnames, ldefaults), (snames, sdefaults)) in enumerate(zip(live, declared)):
        where = f"{label}" + (f" (overload {k + 1})" if len(live) > 1 else "")
        if lnames != snames:
            problems.append(f"{where}: parameters {lnames} in rbsf, {snames} in the .pyi")
            continue
        if ldefaults.keys() != sdefaults.keys():
            problems.append(f"{where}: defaults of {sorted(ldefaults)} in rbsf, of "
                            f"{sorted(sdefaults)} in the .pyi")
            continue
        for p in ldefaults:
            if not same_default(sdefaults[p], ldefaults[p]):
                problems.append(f"{where}: {p} defaults to {ldefaults[p]} in rbsf, "
                                f"{ast.unparse(sdefaults[p])} in the .pyi")


for n in sorted(live_top & pyi_top.keys()):
    obj, nodes = getattr(rbsf, n), pyi_top[n]
    if callable(obj) and not isinstance(obj, type):
        check_signatures(n, obj, n, nodes)


# 3. Classes: bases, members both ways, read-only against read-write, methods, signatures.
checked_classes = 0
for n in sorted(live_top & pyi_top.keys()):
    cls, node = getattr(rbsf, n), pyi_top[n][0]
    if not isinstance(cls, type) or not isinstance(node, ast.ClassDef):
        continue
    checked_classes += 1
    live_bases = [b.__name__ for b in cls.__bases__ if b.__name__ != "pybind11_object"]
    pyi_bases = [ast.unparse(b) for b in node.bases]
    if live_bases != pyi_bases:
        problems.append(f"{n}: bases {live_bases} in rbsf, {pyi_bases} in the .pyi")
    inherited = set().union(*(dir(b) for b in cls.__mro__[1:]))
    live = {a for a in dir(cls) if public(a) and (a not in inherited or a in vars(cls))}
    body = defined(node.body)
    declared = {a for a in body if public(a)}
    for a in sorted(live - declared):
        problems.append(f"{n}.{a} is in rbsf, not in the .pyi")
    for a in sorted(declared - live):
        problems.append(f"{n}.{a} is in the .pyi, not in rbsf")
    # pybind11 gives a class without py::init a slot __init__ that raises TypeError.
    init = vars(cls).get("__init__")
    has_init = init is not None and type(init).__name__ != "wrapper_descriptor"
    if has_init and "__init__" not in body:
        problems.append(f"{n}: has a constructor in rbsf, none in the .pyi")
    if "__init__" in body and not has_init:
        problems.append(f"{n}: a constructor in the .pyi, none in rbsf")
    for a in sorted(live & declared):
        raw, snodes = inspect.getattr_static(cls, a), body[a]
        first = snodes[0]
        if isinstance(raw, property):
            read_only = raw.fset is None
            if read_only and not (isinstance(first, ast.FunctionDef)
                                  and "property" in decorators(first)):
                problems.append(f"{n}.{a}: read-only in rbsf, not a @property in the .pyi")
            if not read_only and not isinstance(first, ast.AnnAssign):
                problems.append(f"{n}.{a}: read-write in rbsf, not an annotation in the .pyi")
        elif isinstance(raw, staticmethod):
            if not (isinstance(first, ast.FunctionDef) and "staticmethod" in decorators(first)):
                problems.append(f"{n}.{a}: a staticmethod in rbsf, not in the .pyi")
            else:
                check_signatures(f"{n}.{a}", raw.__func__, a, snodes)
        elif callable(raw):
            if not isinstance(first, ast.FunctionDef) or decorators(first) - {"overload"}:
                problems.append(f"{n}.{a}: a method in rbsf, not a plain def in the .pyi")
            else:
                check_signatures(f"{n}.{a}", raw, a, snodes)
    if has_init and "__init__" in body:
        check_signatures(f"{n}.__init__", vars(cls)["__init__"], "__init__", body["__init__"])

if problems:
    print("\n".join(problems))
    sys.exit(1)
print(f"ok: {len(live_top)} public names, {checked_classes} classes, members and signatures "
      "match both ways")
