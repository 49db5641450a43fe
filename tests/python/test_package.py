"""`make package`'s Debian package (CPack, configured in CMakeLists.txt), built from the build tree
under test: dpkg lists the program, the module for Debian's python3 and every workbench file the
repository tracks under FreeCAD's system Mod folder; dpkg's control fields declare the OpenCASCADE
libraries the binaries link (dpkg-shlibdeps) and python3-numpy. Installing it is
scripts/check-package.sh's job (it changes the machine)."""

import shutil
import subprocess

import pytest

from hexdom_test_support import BUILD_DIR, REPO

pytestmark = pytest.mark.skipif(shutil.which("cpack") is None or shutil.which("dpkg-deb") is None,
                                reason="cpack or dpkg-deb missing")


@pytest.fixture(scope="module")
def deb(tmp_path_factory):
    if not (BUILD_DIR / "CPackConfig.cmake").exists():
        pytest.skip(f"{BUILD_DIR} has no CPackConfig.cmake (configured before packaging existed?)")
    out = tmp_path_factory.mktemp("deb")
    r = subprocess.run(["cpack", "-G", "DEB", "-B", str(out)], cwd=BUILD_DIR, capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    debs = list(out.glob("hexdom_*.deb"))
    assert len(debs) == 1, debs
    return debs[0]


def test_package_holds_program_module_and_every_workbench_file(deb):
    listing = subprocess.run(["dpkg-deb", "-c", str(deb)], capture_output=True, text=True, check=True).stdout
    files = {line.split()[-1].lstrip(".") for line in listing.splitlines() if not line.endswith("/")}
    assert "/usr/bin/hexdom" in files
    assert any(f.startswith("/usr/lib/python3/dist-packages/_hexdom.cpython-3") and f.endswith(".so") for f in files)
    tracked = subprocess.run(["git", "ls-files", "Init.py", "InitGui.py", "package.xml", "HexDomWorkbench", "Resources"],
                             cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    if not tracked:
        pytest.skip("not a git checkout")
    wanted = {"/usr/share/freecad/Mod/HexDom/" + t for t in tracked if t.endswith((".py", ".ui", ".svg", ".xml"))}
    assert wanted - files == set()
    assert not any("__pycache__" in f for f in files)


def test_package_declares_what_it_needs(deb):
    fields = subprocess.run(["dpkg-deb", "-f", str(deb), "Package", "Depends", "Recommends"], capture_output=True,
                            text=True, check=True).stdout
    assert "Package: hexdom" in fields
    for need in ("python3-numpy", "libocct-data-exchange-7.6", "libocct-modeling-algorithms-7.6", "zlib1g"):
        assert need in fields, fields
    assert "freecad" in fields.split("Recommends:")[1]
