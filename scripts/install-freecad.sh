#!/usr/bin/env bash
# Installs the HexDom workbench into FreeCAD's user Mod folder as plain copies (no symlinks), with
# the compiled core _hexdom placed inside the HexDomWorkbench package so that FreeCAD's Python
# finds it without any build tree or environment variable.
#
#   scripts/install-freecad.sh BUILD_DIR [DEST]
#
# BUILD_DIR is the CMake build directory (holding python/_hexdom*.so); DEST defaults to
# ~/.local/share/FreeCAD/Mod/HexDom. An existing DEST is replaced.
set -euo pipefail

if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $0 BUILD_DIR [DEST]" >&2
  exit 2
fi
BUILD_DIR=$1
DEST=${2:-$HOME/.local/share/FreeCAD/Mod/HexDom}
REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

shopt -s nullglob
SO=("$BUILD_DIR"/python/_hexdom*.so)
shopt -u nullglob
if [ ${#SO[@]} -eq 0 ]; then
  echo "install-freecad: no _hexdom*.so in $BUILD_DIR/python (run 'make build' first)" >&2
  exit 1
fi
if [ ${#SO[@]} -gt 1 ]; then
  echo "install-freecad: several _hexdom modules in $BUILD_DIR/python: ${SO[*]}" >&2
  exit 1
fi

# Refuse to wipe anything that is not a previous HexDom install (or an empty folder).
if [ -e "$DEST" ] || [ -L "$DEST" ]; then
  if [ -L "$DEST" ]; then
    rm -f "$DEST"
  elif [ -f "$DEST/InitGui.py" ] && [ -d "$DEST/HexDomWorkbench" ]; then
    rm -rf "$DEST"
  elif [ -d "$DEST" ] && [ -z "$(ls -A "$DEST")" ]; then
    rmdir "$DEST"
  else
    echo "install-freecad: $DEST exists and does not look like a HexDom install; not replacing it" >&2
    exit 1
  fi
fi

# Build the copy beside the destination, then move it into place.
PARENT=$(dirname "$DEST")
mkdir -p "$PARENT"
STAGE=$(mktemp -d "$PARENT/.hexdom-install.XXXXXX")
trap 'rm -rf "$STAGE"' EXIT
chmod 755 "$STAGE"

cp "$REPO/Init.py" "$REPO/InitGui.py" "$REPO/package.xml" "$STAGE/"
cp -r "$REPO/Resources" "$STAGE/Resources"
mkdir "$STAGE/HexDomWorkbench"
# Python sources only: no caches, no compiled modules from elsewhere.
(cd "$REPO/HexDomWorkbench" && find . -type d -name __pycache__ -prune -o -type f \
   \( -name '*.py' -o -name '*.ui' -o -name '*.svg' \) -print) | while read -r f; do
  mkdir -p "$STAGE/HexDomWorkbench/$(dirname "$f")"
  cp "$REPO/HexDomWorkbench/$f" "$STAGE/HexDomWorkbench/$f"
done
cp "${SO[0]}" "$STAGE/HexDomWorkbench/"

mv "$STAGE" "$DEST"
trap - EXIT
echo "install-freecad: installed HexDom into $DEST ($(basename "${SO[0]}"))"
