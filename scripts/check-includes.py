#!/usr/bin/env python3
"""Include cycles and layering of rbsf's libraries.

A unit is a header with its source (model.h and model.cpp are one unit: the class and its
definitions). Unit A depends on unit B when a file of A includes B's header. The check fails
(exit 1) when
  - units form a cycle (A needs B and B needs A, through any chain): a header that
    forward-declares a class whose own header includes it back is a cycle of this kind,
    since the source of the one includes the other;
  - a module includes a module that is not below it in LAYERS.
It prints each cycle and each illegal include. Exit 0: no cycle, every include one-way.

  check-includes.py [ROOT]     check ROOT (default: the repository holding this script)
  check-includes.py --self-test
                               plant a cycle and a backwards include into a copy of the
                               tree and require both to be found (CI runs this too)
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

# Module -> its folder in the tree, in dependency order: a module may include only the
# modules listed before it (and not every one of those: ALLOWED says which).
MODULES = {
    "dynamics/core": "dynamics",
    "dynamics/control": "dynamics",
    "dynamics/io": "dynamics",
    "plan": "plan",
    "trajopt": "trajopt",
    "executor": "executor",
    "planner/base": "planner",
    "planner/support": "planner",
    "planner/kinodynamic": "planner",
    "planner/pipeline": "planner",
    "controller": "controller",
    "tools": "tools/common",
    "bench": "tools/bench",
}
DYNAMICS = {"dynamics/core", "dynamics/control", "dynamics/io"}
PLANNER = {"planner/base", "planner/support", "planner/kinodynamic", "planner/pipeline"}
ALLOWED = {
    "dynamics/core": set(),
    "dynamics/control": {"dynamics/core"},
    "dynamics/io": {"dynamics/core"},
    "plan": DYNAMICS,
    "trajopt": DYNAMICS | {"plan"},
    "executor": DYNAMICS | {"plan"},
    "planner/base": DYNAMICS | {"plan"},
    "planner/support": DYNAMICS | {"plan", "planner/base"},
    "planner/kinodynamic": DYNAMICS | {"plan", "planner/base"},
    "planner/pipeline": DYNAMICS | {"plan", "trajopt"} | PLANNER - {"planner/pipeline"},
    "controller": DYNAMICS | PLANNER | {"plan", "trajopt", "executor"},
    "tools": DYNAMICS | PLANNER | {"plan", "trajopt", "executor"},
    "bench": DYNAMICS | PLANNER | {"plan", "trajopt", "executor", "tools"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def part_of(module, path):
    """A module in parts ("dynamics/core"): whether `path` lies in the part's subfolder of
    include/rbsf/<x>/ or src/; the part "base" holds the files beside the subfolders."""
    if "/" not in module:
        return True
    part = module.split("/", 1)[1]
    if part == "base":
        return re.search(r"/(include/rbsf/[^/]+|src)/[^/]+$", path) is not None
    return re.search(r"/(include/rbsf/[^/]+|src)/" + re.escape(part) + "/", path) is not None


def sources(root):
    """(module, path) of every header and source of the libraries."""
    for module, folder in MODULES.items():
        base = os.path.join(root, folder)
        for dirpath, dirnames, filenames in os.walk(base):
            dirnames[:] = [d for d in dirnames if d not in ("build", "CMakeFiles")]
            for name in sorted(filenames):
                path = os.path.join(dirpath, name)
                if name.endswith((".h", ".cpp")) and part_of(module, path):
                    yield module, path


def unit_of(module, path):
    """The unit of a file: its module and its path below include/rbsf/<x>/ or src/, less
    the extension (so the header and the source of one class share it)."""
    stem = os.path.splitext(path)[0]
    m = re.search(r"/include/rbsf/[^/]+/(.+)$", stem)
    if m:
        return module + ":" + m.group(1)
    m = re.search(r"/src/(.+)$", stem)
    if m:
        return module + ":" + m.group(1)
    return module + ":" + os.path.basename(stem)


def graph(root):
    """unit -> {unit: (file, include)} and the modules' illegal includes."""
    headers = {}  # "rbsf/<x>/<path>.h" -> (module, unit)
    files = list(sources(root))
    for module, path in files:
        m = re.search(r"/include/(rbsf/[^/]+/.+)$", path)
        if m:
            headers[m.group(1)] = (module, unit_of(module, path))
    edges, illegal = {}, []
    for module, path in files:
        unit = unit_of(module, path)
        edges.setdefault(unit, {})
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
        for inc in INCLUDE.findall(text):
            if inc in headers:
                target_module, target = headers[inc]
            else:
                local = os.path.normpath(os.path.join(os.path.dirname(path), inc))
                if not os.path.exists(local):
                    continue  # a test's or a system header
                target_module, target = module, unit_of(module, local)
            if target == unit:
                continue
            edges[unit].setdefault(target, (os.path.relpath(path, root), inc))
            if target_module != module and target_module not in ALLOWED[module]:
                illegal.append((os.path.relpath(path, root), inc, module, target_module))
    return edges, illegal


def cycles(edges):
    """Strongly connected components of more than one unit (Tarjan, iterative)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges.get(root, {}))))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(edges.get(w, {})))))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def check(root, quiet=False):
    edges, illegal = graph(root)
    found = cycles(edges)
    for comp in found:
        print("include cycle among " + ", ".join(comp) + ":")
        members = set(comp)
        for u in comp:
            for v, (path, inc) in sorted(edges[u].items()):
                if v in members:
                    print(f'  {path} includes "{inc}" ({u} -> {v})')
    for path, inc, module, target in illegal:
        print(f'{path}: includes "{inc}": {module} may not include {target} '
              f"(allowed: {', '.join(sorted(ALLOWED[module])) or 'none'})")
    if not quiet and not found and not illegal:
        print(f"check-includes: {len(edges)} units, no cycle, every include one-way")
    return 1 if found or illegal else 0


def fails_naming(root, needle):
    """The check of `root`, run as CI runs it, fails and its report holds `needle`."""
    result = subprocess.run([sys.executable, __file__, root], capture_output=True, text=True)
    return result.returncode != 0 and needle in result.stdout


def self_test():
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        for folder in sorted(set(MODULES.values())):
            shutil.copytree(os.path.join(here, folder), os.path.join(tmp, folder),
                            ignore=shutil.ignore_patterns("CMakeFiles"))
        if check(tmp, quiet=True) != 0:
            print("self-test: the unchanged copy already fails")
            return 1
        # A cycle inside a module: the plan's header includes one that includes it back.
        plan_h = os.path.join(tmp, "plan/include/rbsf/plan/plan.h")
        planted = os.path.join(tmp, "plan/include/rbsf/plan/planted_cycle.h")
        with open(planted, "w") as f:
            f.write('#pragma once\n#include "rbsf/plan/plan.h"\n')
        with open(plan_h, "a") as f:
            f.write('\n#include "rbsf/plan/planted_cycle.h"\n')
        if not fails_naming(tmp, "plan:planted_cycle"):
            print("self-test: a planted cycle plan.h <-> planted_cycle.h was not found")
            ok = False
        os.remove(planted)
        with open(plan_h) as f:
            text = f.read().replace('\n#include "rbsf/plan/planted_cycle.h"\n', "")
        with open(plan_h, "w") as f:
            f.write(text)
        # A backwards include across modules: the dynamics including the planner.
        model_h = os.path.join(tmp, "dynamics/include/rbsf/dynamics/core/model.h")
        with open(model_h, "a") as f:
            f.write('\n#include "rbsf/planner/planner_settings.h"\n')
        if not fails_naming(tmp, "dynamics/core may not include planner"):
            print("self-test: dynamics including the planner was not found")
            ok = False
    print("check-includes self-test: " + ("both planted faults found" if ok else "FAILED"))
    return 0 if ok else 1


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--self-test":
        sys.exit(self_test())
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(
        os.path.dirname(os.path.abspath(__file__)))
    sys.exit(check(root))
