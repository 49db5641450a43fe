"""The workbench's version (package.xml says the same; a test checks it), stamped on every object
it writes. A module of its own, so that the objects need not import the package."""

__version__ = "0.1.0"
