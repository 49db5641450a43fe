"""The workbench's import structure, read from the sources with ``ast`` (nothing is imported).

Every ``import`` and ``from ... import`` at any depth (inside functions too) counts: an import
hidden in a function still ties the modules together. Relative imports are resolved to module
names, and ``from . import x`` (or ``from .a import x``) to the submodule ``x`` where it is one.

- no import cycle among HexDomWorkbench modules (the failure names one);
- document-object proxies (objects/) stay free of the layers above them: no api, task panels,
  commands, view providers, FreeCADGui or Qt, directly or through what they import;
- task panels do not import commands (nor api, make and the other object builders);
- the FreeCAD-free logic (logic/) imports neither FreeCAD nor Qt, directly or through what it
  imports, and loads in a plain Python.
"""

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PACKAGE = "HexDomWorkbench"
ROOT = REPO / PACKAGE

# Modules that need FreeCAD or a GUI (top-level names).
FREECAD_MODULES = {"FreeCAD", "FreeCADGui", "Part", "MeshPart", "Mesh", "Fem", "FemGui",
                   "ObjectsFem", "femtools"}
GUI_MODULES = {"FreeCADGui", "FemGui", "PySide", "PySide2", "PySide6", "PyQt5", "pivy"}
# Layers above the document objects (module name prefixes).
ABOVE_OBJECTS = ("api", "taskpanels", "commands", "viewproviders", "guiutils", "make",
                 "document", "part_meshing", "fileio")
# What task panels must not import (module name prefixes).
ABOVE_PANELS = ("commands", "api", "make", "document", "part_meshing", "fileio")


def module_files():
    """{module name: path} of every .py under HexDomWorkbench (packages by their __init__)."""
    modules = {}
    for path in sorted(ROOT.rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        parts = list(path.relative_to(REPO).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        modules[".".join(parts)] = path
    return modules


def _is_package(name, modules):
    return modules.get(name, Path()).name == "__init__.py"


def imports_of(name, path, modules):
    """(internal, external): the HexDomWorkbench modules ``name`` imports, and the top-level names
    of the other modules it imports; each a dict {module: first line}."""
    tree = ast.parse(path.read_text(), filename=str(path))
    package = name if _is_package(name, modules) else name.rpartition(".")[0]
    internal, external = {}, {}

    def add(target, line):
        if target == PACKAGE or target.startswith(PACKAGE + "."):
            # the longest prefix that is a module of ours (import HexDomWorkbench.api.foo -> api)
            while target not in modules and "." in target:
                target = target.rpartition(".")[0]
            if target in modules and target != name:
                internal.setdefault(target, line)
        else:
            external.setdefault(target.partition(".")[0], line)

    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                add(alias.name, node.lineno)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                if node.level > 1:
                    base = base[:len(base) - (node.level - 1)]
                base = ".".join(base + ([node.module] if node.module else []))
            else:
                base = node.module
            submodules = [base + "." + a.name for a in node.names
                          if base + "." + a.name in modules]
            for sub in submodules:
                add(sub, node.lineno)
            if len(submodules) < len(node.names):  # names of the module itself
                add(base, node.lineno)
    return internal, external


def graph():
    modules = module_files()
    edges, external = {}, {}
    for name, path in modules.items():
        edges[name], external[name] = imports_of(name, path, modules)
    return modules, edges, external


def strong_components(edges):
    """Strongly connected components of more than one module (Tarjan), each sorted."""
    index, low, on_stack, stack, found = {}, {}, set(), [], []

    def visit(m):
        index[m] = low[m] = len(index)
        stack.append(m)
        on_stack.add(m)
        for n in sorted(edges[m]):
            if n not in index:
                visit(n)
                low[m] = min(low[m], low[n])
            elif n in on_stack:
                low[m] = min(low[m], index[n])
        if low[m] == index[m]:
            component = []
            while True:
                n = stack.pop()
                on_stack.discard(n)
                component.append(n)
                if n == m:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for m in sorted(edges):
        if m not in index:
            visit(m)
    return found


def shortest_cycle(component, edges):
    """A shortest import cycle through the first module of ``component`` (first == last)."""
    start = component[0]
    members = set(component)
    previous, frontier = {start: None}, [start]
    while frontier:
        nxt = []
        for m in frontier:
            for n in sorted(edges[m]):
                if n == start:
                    path = [m]
                    while previous[path[-1]] is not None:
                        path.append(previous[path[-1]])
                    return path[::-1] + [start]
                if n in members and n not in previous:
                    previous[n] = m
                    nxt.append(n)
        frontier = nxt
    return None


def closure(start, edges):
    """Modules reached from ``start`` (itself included)."""
    seen, todo = set(), [start]
    while todo:
        m = todo.pop()
        if m not in seen:
            seen.add(m)
            todo.extend(edges[m])
    return seen


def _short(m):
    return m[len(PACKAGE) + 1:] if m.startswith(PACKAGE + ".") else m


def _describe(path, edges):
    return " -> ".join("{} (line {})".format(_short(a), edges[a][b])
                       for a, b in zip(path, path[1:])) + " -> " + _short(path[-1])


def test_graph_reads_the_sources():
    modules, edges, _ = graph()
    assert PACKAGE + ".core" in modules and PACKAGE + ".api" in modules
    assert PACKAGE + ".core" in edges[PACKAGE]  # the package imports core


def test_no_import_cycle():
    _, edges, _ = graph()
    messages = ["{} modules import one another: {}\n  e.g. {}".format(
        len(c), ", ".join(_short(m) for m in c), _describe(shortest_cycle(c, edges), edges))
        for c in strong_components(edges)]
    assert not messages, "import cycle among HexDomWorkbench modules:\n" + "\n".join(messages)


def _in(module, prefixes):
    rel = _short(module)
    return any(rel == p or rel.startswith(p + ".") for p in prefixes)


def test_objects_do_not_import_the_layers_above():
    modules, edges, external = graph()
    objects = [m for m in modules if _in(m, ("objects",))]
    assert objects
    bad = []
    for m in objects:
        for n, line in edges[m].items():
            if _in(n, ABOVE_OBJECTS):
                bad.append("{} line {} imports {}".format(_short(m), line, _short(n)))
        for x, line in external[m].items():
            if x in GUI_MODULES:
                bad.append("{} line {} imports {}".format(_short(m), line, x))
        for n in closure(m, edges) - {m}:  # nor through what they import
            if _in(n, ABOVE_OBJECTS):
                bad.append("{} reaches {}".format(_short(m), _short(n)))
    assert not bad, "document objects import GUI layers:\n" + "\n".join(sorted(set(bad)))


def test_panels_do_not_import_commands():
    """Nor what builds document objects: a panel is handed the function that makes one."""
    modules, edges, _ = graph()
    bad = ["{} line {} imports {}".format(_short(m), line, _short(n))
           for m in modules if _in(m, ("taskpanels",))
           for n, line in edges[m].items() if _in(n, ABOVE_PANELS)]
    assert not bad, "\n".join(bad)


def test_logic_is_freecad_free():
    modules, edges, external = graph()
    logic = [m for m in modules if _in(m, ("logic",))]
    assert logic, "no HexDomWorkbench.logic package"
    bad = []
    for m in logic:
        for n in closure(m, edges):
            for x, line in external[n].items():
                if x in FREECAD_MODULES | GUI_MODULES:
                    via = "" if n == m else " (through {})".format(_short(n))
                    bad.append("{} imports {}{}".format(_short(m), x, via))
    assert not bad, "logic needs FreeCAD or Qt:\n" + "\n".join(sorted(set(bad)))


def test_logic_loads_in_plain_python():
    """The logic package and the api facade, imported in a fresh interpreter with no FreeCAD on
    sys.path: no FreeCAD or Qt module is loaded."""
    modules = [m for m in module_files() if _in(m, ("logic",))]
    code = ("import sys\n"
            "sys.path[:] = [p for p in sys.path if 'freecad' not in p.lower()]\n"
            "sys.path.insert(0, {!r})\n"
            "for m in {!r}:\n"
            "    __import__(m)\n"
            "import HexDomWorkbench\n"
            "import HexDomWorkbench.api\n"
            "HexDomWorkbench.labels_from_normals, HexDomWorkbench.mesh_part\n"
            "loaded = sorted(m for m in sys.modules if m.split('.')[0] in {!r})\n"
            "assert not loaded, loaded\n").format(str(REPO), modules,
                                                   sorted(FREECAD_MODULES | GUI_MODULES))
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    run = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         timeout=120)
    if run.returncode and "_hexdom was not found" in run.stderr:
        pytest.skip("no _hexdom build (HEXDOM_BUILD_DIR)")
    assert run.returncode == 0, run.stderr


def test_logic_imports_only_logic_and_core():
    modules, edges, _ = graph()
    allowed = {PACKAGE, PACKAGE + ".core"}
    bad = ["{} line {} imports {}".format(_short(m), line, _short(n))
           for m in modules if _in(m, ("logic",))
           for n, line in edges[m].items() if not (_in(n, ("logic",)) or n in allowed)]
    assert not bad, "\n".join(bad)


def test_no_submodule_hides_a_public_name():
    """A submodule named like a name the package serves (``tessellate``, ``mesh_part``) would
    replace that function on the package once imported."""
    modules = module_files()
    tree = ast.parse((ROOT / "__init__.py").read_text())
    public = set()
    for node in tree.body:  # the names the package itself holds, and those it serves from api
        if isinstance(node, ast.ImportFrom):
            public.update(a.asname or a.name for a in node.names)
        elif isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "_API_NAMES" for t in node.targets):
            public.update(ast.literal_eval(node.value))
    assert "mesh_part" in public and "tessellate" in public
    clash = sorted(m for m in modules if m.count(".") == 1 and m.split(".")[1] in public)
    assert not clash, clash
