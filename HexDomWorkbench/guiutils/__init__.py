"""GUI helpers shared by commands and task panels."""
