"""GUI commands: manager.py (base class and helpers), commands.py (one small class per command,
then the addCommand block). Imported by InitGui.py only when the workbench is activated."""
