"""Reader for VTK XML unstructured grids (.vtu), which core writes but does not read.

Handles what core and common tools write uncompressed: DataArrays in ``ascii`` or inline
``binary`` (base64, UInt32 or UInt64 headers, either byte order). Compressed or appended data
raise core.InputError naming the file. FreeCAD-free.
"""

import base64
import os
import xml.etree.ElementTree as ET

import numpy as np

from .. import core

_DTYPES = {
    "Int8": "i1", "UInt8": "u1", "Int16": "i2", "UInt16": "u2", "Int32": "i4", "UInt32": "u4",
    "Int64": "i8", "UInt64": "u8", "Float32": "f4", "Float64": "f8",
}


def _fail(path, text):
    return core.InputError("{}: {}".format(os.fspath(path), text))


def _array(path, node, byte_order, header_type):
    name = node.get("Name", node.tag)
    vtype = node.get("type")
    if vtype not in _DTYPES:
        raise _fail(path, "DataArray '{}' has unsupported type '{}'".format(name, vtype))
    fmt = node.get("format", "ascii")
    dtype = np.dtype(_DTYPES[vtype]).newbyteorder("<" if byte_order == "LittleEndian" else ">")
    text = node.text or ""
    if fmt == "ascii":
        try:
            return np.array(text.split(), dtype=float).astype(dtype.newbyteorder("="))
        except ValueError as e:
            raise _fail(path, "DataArray '{}': {}".format(name, e)) from None
    if fmt == "binary":
        try:
            raw = base64.b64decode("".join(text.split()), validate=True)
        except ValueError as e:
            raise _fail(path, "DataArray '{}': bad base64 data ({})".format(name, e)) from None
        hdr = np.dtype(_DTYPES[header_type]).newbyteorder(dtype.byteorder)
        if len(raw) < hdr.itemsize:
            raise _fail(path, "DataArray '{}': truncated binary data".format(name))
        nbytes = int(np.frombuffer(raw[:hdr.itemsize], dtype=hdr)[0])
        body = raw[hdr.itemsize:hdr.itemsize + nbytes]
        if len(body) != nbytes or nbytes % dtype.itemsize:
            raise _fail(path, "DataArray '{}': header says {} bytes, found {}".format(
                name, nbytes, len(raw) - hdr.itemsize))
        return np.frombuffer(body, dtype=dtype).astype(dtype.newbyteorder("="))
    raise _fail(path, "DataArray '{}' uses format '{}' (only ascii and inline binary are "
                      "supported)".format(name, fmt))


def read_vtu(path):
    """Reads a .vtu file into a core.Mesh (cell data 'region' becomes Mesh.region if present)."""
    try:
        root = ET.parse(os.fspath(path)).getroot()
    except ET.ParseError as e:
        raise _fail(path, "not valid XML ({})".format(e)) from None
    except OSError as e:
        raise _fail(path, "cannot open ({})".format(e.strerror or e)) from None
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        raise _fail(path, "not a VTK UnstructuredGrid file")
    if root.get("compressor"):
        raise _fail(path, "compressed data ({}) is not supported".format(root.get("compressor")))
    byte_order = root.get("byte_order", "LittleEndian")
    header_type = root.get("header_type", "UInt32")
    pieces = root.findall("./UnstructuredGrid/Piece")
    if len(pieces) != 1:
        raise _fail(path, "expected one Piece, found {}".format(len(pieces)))
    piece = pieces[0]
    n_points = int(piece.get("NumberOfPoints", "0"))
    n_cells = int(piece.get("NumberOfCells", "0"))

    def find(section, name=None):
        nodes = piece.findall("./{}/DataArray".format(section))
        if name is not None:
            nodes = [n for n in nodes if n.get("Name") == name]
        return nodes[0] if nodes else None

    pts = find("Points")
    conn, offsets, types = (find("Cells", n) for n in ("connectivity", "offsets", "types"))
    if pts is None or conn is None or offsets is None or types is None:
        raise _fail(path, "Points or Cells (connectivity, offsets, types) missing")
    V = _array(path, pts, byte_order, header_type).astype(float)
    if V.size != 3 * n_points:
        raise _fail(path, "Points holds {} values for {} points".format(V.size, n_points))
    V = V.reshape(-1, 3)
    conn = _array(path, conn, byte_order, header_type).astype(np.int64)
    offsets = _array(path, offsets, byte_order, header_type).astype(np.int64)
    types = _array(path, types, byte_order, header_type).astype(np.int32)
    if len(offsets) != n_cells or len(types) != n_cells:
        raise _fail(path, "offsets / types do not have NumberOfCells={} entries".format(n_cells))
    cells = np.full((n_cells, 8), -1, dtype=np.int32)
    start = 0
    for c in range(n_cells):
        t = int(types[c])
        n = core.NODE_COUNT.get(t)
        if n is None:
            raise _fail(path, "cell {}: VTK cell type {} is not supported".format(c, t))
        end = int(offsets[c])
        if end - start != n or end > len(conn):
            raise _fail(path, "cell {}: type {} needs {} nodes, found {}".format(
                c, t, n, end - start))
        ids = conn[start:end]
        if ids.min() < 0 or ids.max() >= n_points:
            raise _fail(path, "cell {}: node index out of range".format(c))
        cells[c, :n] = ids
        start = end
    region = np.zeros(n_cells, dtype=np.int32)
    reg = find("CellData", "region")
    if reg is not None:
        values = _array(path, reg, byte_order, header_type)
        if len(values) == n_cells:
            region = values.astype(np.int32)
    return core.Mesh(V, cells, types, region)
