"""Locations of the workbench's resources, in the source tree and in an installed copy alike."""

import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESOURCES = os.path.join(ROOT, "Resources")


def icon(name):
    """Path of Resources/icons/<name> (add .svg when no extension is given)."""
    if not os.path.splitext(name)[1]:
        name += ".svg"
    return os.path.join(RESOURCES, "icons", name)


def ui(name):
    """Path of Resources/ui/<name>."""
    return os.path.join(RESOURCES, "ui", name)
