"""Boilerplate shared by HexDom document-object proxies."""

from ..version import __version__


def _version():
    return __version__


class BaseHexDomObject:
    """Base Proxy: links itself to ``obj``, adds properties idempotently, stamps Version.

    Subclasses set ``Type`` ("HexDom::<Object>") and extend ``add_properties``; saved documents
    store only the module and class name, everything else lives in properties.
    """

    Type = "HexDom::Object"

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)
        obj.Version = _version()

    def add_properties(self, obj):
        """Adds missing properties; safe to call on every restore."""
        if not hasattr(obj, "Version"):
            obj.addProperty("App::PropertyString", "Version", "Base",
                            "HexDom version that last wrote this object")
        obj.setEditorMode("Version", 1)

    def onDocumentRestored(self, obj):
        self.add_properties(obj)
        self.migrate(obj)
        if obj.Version != _version():
            obj.Version = _version()

    def migrate(self, obj):
        """Converts properties written by older versions (obj.Version); nothing to do yet."""

    # Documents store no Proxy state: properties carry everything.
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    def dumps(self):
        return None

    def loads(self, state):
        return None


def is_of_type(obj, type_name):
    """True if ``obj`` has a Proxy whose Type is ``type_name``."""
    return getattr(getattr(obj, "Proxy", None), "Type", None) == type_name


def set_read_only(obj, names):
    for name in names:
        obj.setEditorMode(name, 1)
