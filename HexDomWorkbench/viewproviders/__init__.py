"""View providers (GUI only), one module per object type: view_<object>.py with VP<Object>.

Module and class names are stored in saved documents: do not rename them (see STYLE.md)."""
