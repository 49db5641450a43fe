"""Proxy classes of HexDom's document objects, one module per object type; no GUI imports.

Module and class names are stored in saved documents: do not rename them (see STYLE.md)."""
