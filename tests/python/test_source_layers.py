"""The core's shape: src/hexdom's folders are stages in one order, and each includes only folders
before it (or itself); OpenCASCADE is included only in cad/. Read from the #include lines, so a
change that makes a stage reach up the order fails here, naming the file and line."""

import os
import re

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CORE = os.path.join(ROOT, "src", "hexdom")

# The stages, in dependency order (docs/architecture.md).
ORDER = ["common", "mesh", "io", "quality", "parametrization", "polycube", "segmentation", "optimize", "cad",
         "generation", "autopolycube", "overlay", "pipeline"]

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')
OCCT_HEADER = re.compile(r"^(Standard_|TopoDS|TopExp|TopAbs|BRep|Geom|gp_|STEP|IGES|Interface_|TopLoc|Poly_|TColgp|"
                         r"ShapeFix|ShapeAnalysis|BOPAlgo|IMeshTools|Bnd_|GCPnts|Precision|NCollection|TopTools|"
                         r"XSControl|Message_|OSD_)")


def source_files(folder):
    for dirpath, _, names in os.walk(folder):
        for name in sorted(names):
            if name.endswith((".h", ".cpp")):
                yield os.path.join(dirpath, name)


def includes(path):
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m:
                yield number, m.group(1)


def stage_of(path):
    return os.path.relpath(path, CORE).split(os.sep)[0]


def upward_includes(core_dir, order):
    """(file:line, what it includes, why) for every include that goes up the order or out of it."""
    rank = {name: i for i, name in enumerate(order)}
    problems = []
    for path in source_files(core_dir):
        stage = os.path.relpath(path, core_dir).split(os.sep)[0]
        where = os.path.relpath(path, ROOT)
        if stage not in rank:
            problems.append((where, "", f"folder {stage!r} is not a stage of the order"))
            continue
        for number, target in includes(path):
            if not target.startswith("hexdom/"):
                continue
            other = target.split("/")[1]
            if other not in rank:
                problems.append((f"{where}:{number}", target, f"{other!r} is not a stage"))
            elif rank[other] > rank[stage]:
                problems.append((f"{where}:{number}", target, f"{stage} includes {other}, a later stage"))
    return problems


# The automatic polycube's own steps, in order; its entry (autopolycube.h/.cpp) sits above them.
AUTOPOLYCUBE_STEPS = ["repair", "map", "blocks"]


def test_the_automatic_polycube_s_steps_include_only_steps_before_them():
    folder = os.path.join(CORE, "autopolycube")
    steps = sorted(d for d in os.listdir(folder) if os.path.isdir(os.path.join(folder, d)))
    assert steps == sorted(AUTOPOLYCUBE_STEPS), f"src/hexdom/autopolycube holds {steps}"
    rank = {name: i for i, name in enumerate(AUTOPOLYCUBE_STEPS)}
    problems = []
    for step in AUTOPOLYCUBE_STEPS:
        for path in source_files(os.path.join(folder, step)):
            for number, target in includes(path):
                parts = target.split("/")
                if parts[:2] != ["hexdom", "autopolycube"]:
                    continue
                other = parts[2] if len(parts) > 3 else "autopolycube.h (the entry)"
                if rank.get(other, len(rank)) > rank[step]:
                    problems.append(f"{os.path.relpath(path, ROOT)}:{number}: {target} ({step} includes {other})")
    assert not problems, "includes that go up the automatic polycube's steps:\n" + "\n".join(problems)


def test_the_stages_are_the_folders():
    folders = sorted(d for d in os.listdir(CORE) if os.path.isdir(os.path.join(CORE, d)))
    assert folders == sorted(ORDER), f"src/hexdom holds {folders}; the order names {ORDER}"


def test_each_stage_includes_only_stages_before_it():
    problems = upward_includes(CORE, ORDER)
    assert not problems, "includes that go up the order:\n" + "\n".join(f"  {w}: {t} ({why})" for w, t, why in problems)


def test_the_check_fails_on_an_include_up_the_order(tmp_path):
    # The check itself: a mesh/ file that includes generation/ must be reported, with its line.
    (tmp_path / "mesh").mkdir()
    (tmp_path / "generation").mkdir()
    (tmp_path / "mesh" / "bad.h").write_text('#pragma once\n\n#include "hexdom/generation/generate.h"\n')
    (tmp_path / "generation" / "generate.h").write_text('#include "hexdom/mesh/bad.h"\n')
    problems = upward_includes(str(tmp_path), ["mesh", "generation"])
    assert len(problems) == 1
    where, target, why = problems[0]
    assert where.endswith("bad.h:3") and target == "hexdom/generation/generate.h" and "later stage" in why


def test_only_cad_includes_opencascade():
    found = []
    for path in source_files(os.path.join(ROOT, "src")):
        if os.path.relpath(path, CORE).split(os.sep)[0] == "cad" and not path.endswith("without_occt.cpp"):
            continue
        found += [f"{os.path.relpath(path, ROOT)}:{n}: {t}" for n, t in includes(path) if OCCT_HEADER.match(t)]
    assert not found, "OpenCASCADE headers outside src/hexdom/cad:\n" + "\n".join(found)


@pytest.mark.parametrize("front", ["cli", "python"])
def test_the_program_and_the_module_include_the_core_only_through_its_stages(front):
    for path in source_files(os.path.join(ROOT, "src", front)):
        for number, target in includes(path):
            if target.startswith("hexdom/"):
                assert target.split("/")[1] in ORDER, f"{os.path.relpath(path, ROOT)}:{number}: {target}"
