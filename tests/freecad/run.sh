#!/usr/bin/env bash
# FreeCAD test suites: installs the workbench (copies, as a user would) into a throw-away HOME,
# runs the App tests with pytest inside freecadcmd, then the GUI scripts under xvfb.
#
#   HEXDOM_BUILD_DIR=/abs/build tests/freecad/run.sh        (make test-freecad does this)
#
# Extra pytest arguments for the App tests: HEXDOM_FC_PYTEST_ARGS="-k fem -x".
# Only some GUI scripts: HEXDOM_FC_GUI="gui_test_build_polycube" (a glob); HEXDOM_FC_SKIP_APP=1 skips the App tests,
# HEXDOM_FC_SKIP_GUI=1 the GUI tests.
# Screenshots and logs go to tests/freecad/artifacts/ (ignored by git).
set -e

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
BUILD_DIR=${HEXDOM_BUILD_DIR:-$REPO/build}
ARTIFACTS=$HERE/artifacts

for tool in freecadcmd freecad xvfb-run; do
  if ! command -v "$tool" >/dev/null; then
    echo "tests/freecad: '$tool' not found (scripts/install-deps.sh installs it)" >&2
    exit 1
  fi
done

FC_HOME=$(mktemp -d "${TMPDIR:-/tmp}/hexdom-fc-home.XXXXXX")
cleanup() { rm -rf "$FC_HOME"; }
trap cleanup EXIT
mkdir -p "$ARTIFACTS"
rm -f "$ARTIFACTS"/*.png "$ARTIFACTS"/*.log "$ARTIFACTS"/*.txt

"$REPO/scripts/install-freecad.sh" "$BUILD_DIR" "$FC_HOME/.local/share/FreeCAD/Mod/HexDom"

# The workbench must find everything in the installed copy, not in the build tree; the tests that
# compare it with `hexdom mesh` get the program's path.
export HOME=$FC_HOME
if [ -x "$BUILD_DIR/bin/hexdom" ]; then export HEXDOM_CLI="$BUILD_DIR/bin/hexdom"; fi
unset HEXDOM_BUILD_DIR
export HEXDOM_FC_TEST_DIR=$HERE HEXDOM_FC_ARTIFACTS=$ARTIFACTS
export HEXDOM_DATA=${HEXDOM_DATA:-$(cd "$REPO/.." && pwd)/shared/data}
export PYTHONDONTWRITEBYTECODE=1
export QTWEBENGINE_DISABLE_SANDBOX=1 LIBGL_ALWAYS_SOFTWARE=1

declare -a NAMES RESULTS
record() { NAMES+=("$1"); RESULTS+=("$2"); }

# App tests. freecadcmd's own exit status is 0 after an uncaught exception, so the runner script
# exits with pytest's code, and a missing pytest summary line counts as a failure too.
if [ -z "${HEXDOM_FC_SKIP_APP:-}" ]; then
  echo "== App tests (freecadcmd + pytest) =="
  set +e
  (cd "$FC_HOME" && timeout 900 freecadcmd "$HERE/run_app_tests.py") 2>&1 | tee "$ARTIFACTS/app.log"
  rc=${PIPESTATUS[0]}
  set -e
  app_summary=$(grep -aE "^=+ .*(passed|failed|error|skipped).* =+$" "$ARTIFACTS/app.log" | tail -1 || true)
  if [ "$rc" -ne 0 ] || [ -z "$app_summary" ]; then
    record "App tests" "FAILED (exit $rc) ${app_summary//=/}"
  else
    record "App tests" "passed: ${app_summary//=/}"
  fi
fi

# GUI tests: each script ends with os._exit(code) after printing "GUI TEST PASSED".
shopt -s nullglob
GUI_SCRIPTS=("$HERE"/gui/${HEXDOM_FC_GUI:-gui_test_*}.py)
shopt -u nullglob
if [ -n "${HEXDOM_FC_SKIP_GUI:-}" ]; then
  GUI_SCRIPTS=()
  record "GUI tests" "skipped (HEXDOM_FC_SKIP_GUI)"
elif [ ${#GUI_SCRIPTS[@]} -eq 0 ]; then
  record "GUI tests" "FAILED (no tests/freecad/gui/gui_test_*.py found)"
fi
for script in "${GUI_SCRIPTS[@]}"; do
  name=$(basename "$script" .py)
  echo "== GUI test $name (freecad under xvfb) =="
  set +e
  (cd "$FC_HOME" && timeout 180 xvfb-run -a -s "-screen 0 1280x1024x24" freecad "$script") 2>&1 \
    | tee "$ARTIFACTS/$name.log"
  rc=${PIPESTATUS[0]}
  set -e
  if [ "$rc" -ne 0 ]; then
    record "GUI $name" "FAILED (exit $rc, log $ARTIFACTS/$name.log)"
  elif ! grep -aq "^GUI TEST PASSED" "$ARTIFACTS/$name.log"; then
    record "GUI $name" "FAILED (no pass line, log $ARTIFACTS/$name.log)"
  else
    skipped=$(grep -a "^SKIP " "$ARTIFACTS/$name.log" | sed 's/^SKIP /skipped: /' | paste -sd ';' - || true)
    record "GUI $name" "passed${skipped:+ ($skipped)}"
  fi
done

echo
echo "================ FreeCAD test summary ================"
status=0
for i in "${!NAMES[@]}"; do
  printf '  %-32s %s\n' "${NAMES[$i]}" "${RESULTS[$i]}"
  case "${RESULTS[$i]}" in FAILED*) status=1 ;; esac
done
if [ -f "$ARTIFACTS/fem_results.txt" ]; then
  echo "  CalculiX cantilever (tip displacement vs theory):"
  sed 's/^/    /' "$ARTIFACTS/fem_results.txt"
fi
echo "  screenshots and logs: $ARTIFACTS"
if [ "$status" -ne 0 ]; then
  echo "FreeCAD tests FAILED"
else
  echo "FreeCAD tests passed"
fi
exit $status
