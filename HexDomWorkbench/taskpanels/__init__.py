"""Task panels (GUI only): task_<object>.py with _TaskPanel(obj), editing one object's
properties and recomputing. The meshing stages add theirs here."""
