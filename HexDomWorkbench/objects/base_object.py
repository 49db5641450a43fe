"""Boilerplate shared by HexDom document-object proxies."""

from ..version import __version__
from .chain import filling, restoring, stage_edited


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

    # Input properties of a stage object (Surface, Segmentation, Polycube) whose edit makes it an
    # ordinary stage again after Mesh Part's pipeline filled it (see add_pipeline_flag).
    STAGE_INPUTS = ()

    def add_pipeline_flag(self, obj):
        """Adds FromPipeline: the object holds what Mesh Part's pipeline (`hexdom mesh`, run by
        the HexDom Mesh downstream) made, and its recompute keeps it; editing one of its
        STAGE_INPUTS clears it, and the object (and the Mesh after it) then computes as a stage."""
        if not hasattr(obj, "FromPipeline"):
            obj.addProperty("App::PropertyBool", "FromPipeline", "Base",
                            "Filled by Mesh Part's pipeline (`hexdom mesh`, run by the HexDom Mesh "
                            "downstream): recompute keeps it; editing an input of this object "
                            "makes it (and the Mesh) compute stage by stage again")
        obj.setEditorMode("FromPipeline", 1)

    def onChanged(self, obj, prop):
        if (prop in self.STAGE_INPUTS and getattr(obj, "FromPipeline", False)
                and not filling.active() and not restoring(obj)):
            stage_edited(obj)

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
