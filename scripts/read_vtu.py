#!/usr/bin/python3
"""Read the VTU files of rockdda (dda blocks-*.vtu and contacts-*.vtu, heat
temperature-*.vtu) with the Python standard library only.

The DataArrays may be ASCII (older rockdda outputs) or binary: base64
inline, zlib-compressed (compressor="vtkZLibDataCompressor") or not, with
a UInt32 (the default) or UInt64 header (header_type). One piece per file.

    import read_vtu
    arrays = read_vtu.read("out/blocks-00010.vtu")
    arrays["material"].values      # flat list, components interleaved
    arrays["stress"].components    # 6: XX YY ZZ XY YZ XZ
    read_vtu.polygons(arrays)      # [[(x, y), ...] per cell]

Usage as a script: read_vtu.py FILE.vtu prints each array's name, type,
number of components and first values."""
import base64
import re
import struct
import sys
import zlib

_TYPES = {"Float32": "f", "Float64": "d", "Int8": "b", "UInt8": "B",
          "Int16": "h", "UInt16": "H", "Int32": "i", "UInt32": "I",
          "Int64": "q", "UInt64": "Q"}


class Array:
    """One DataArray: name ("Points" for the points), VTK type, number of
    components and the values as a flat list."""

    def __init__(self, name, vtk_type, components, values, attributes):
        self.name = name
        self.type = vtk_type
        self.components = components
        self.values = values
        self.attributes = attributes

    def tuples(self):
        """The values grouped per point or cell."""
        c = self.components
        return [tuple(self.values[i:i + c])
                for i in range(0, len(self.values), c)]


def _decode(text, vtk_type, compressed, word, order):
    """The values of a binary DataArray's base64 content."""
    header = order + ("Q" if word == 8 else "I")
    text = "".join(text.split())
    if not compressed:
        raw = base64.b64decode(text)
        (n,) = struct.unpack(header, raw[:word])
        raw = raw[word:word + n]
    else:
        # The header (blocks, block size, last block size, compressed
        # sizes) is base64-encoded on its own, then the zlib streams.
        first = 4 * ((3 * word + 2) // 3)
        n_blocks = struct.unpack(header, base64.b64decode(text[:first])[:word])[0]
        chars = 4 * ((word * (3 + n_blocks) + 2) // 3)
        head = base64.b64decode(text[:chars])
        sizes = struct.unpack(order + ("Q" if word == 8 else "I") * (3 + n_blocks),
                              head[:word * (3 + n_blocks)])[3:]
        data = base64.b64decode(text[chars:])
        parts, at = [], 0
        for size in sizes:
            parts.append(zlib.decompress(data[at:at + size]))
            at += size
        raw = b"".join(parts)
    code = _TYPES[vtk_type]
    n = len(raw) // struct.calcsize(code)
    return list(struct.unpack(order + code * n, raw[:n * struct.calcsize(code)]))


def read(path):
    """The DataArrays of a VTU file by name (dict of Array)."""
    text = open(path, encoding="ascii", errors="replace").read()
    root = re.search(r"<VTKFile([^>]*)>", text)
    if root is None:
        raise ValueError(path + ": not a VTK XML file")
    head = root.group(1)
    compressed = "vtkZLibDataCompressor" in head
    word = 8 if 'header_type="UInt64"' in head else 4
    order = ">" if 'byte_order="BigEndian"' in head else "<"
    arrays = {}
    for m in re.finditer(r"<DataArray([^>]*)>(.*?)</DataArray>", text, re.S):
        attributes = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
        vtk_type = attributes.get("type", "Float32")
        components = int(attributes.get("NumberOfComponents", "1"))
        if attributes.get("format", "ascii") == "binary":
            values = _decode(m.group(2), vtk_type, compressed, word, order)
        else:
            convert = float if vtk_type.startswith("Float") else int
            values = [convert(v) for v in m.group(2).split()]
        name = attributes.get("Name", "Points")
        arrays[name] = Array(name, vtk_type, components, values, attributes)
    return arrays


def polygons(arrays):
    """The cells as lists of (x, y) points (connectivity and offsets)."""
    xyz = arrays["Points"].values
    conn = arrays["connectivity"].values
    out, start = [], 0
    for end in arrays["offsets"].values:
        out.append([(xyz[3 * k], xyz[3 * k + 1]) for k in conn[start:end]])
        start = end
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: read_vtu.py FILE.vtu")
    try:
        arrays = read(sys.argv[1])
    except (OSError, ValueError, KeyError, struct.error, zlib.error) as e:
        sys.exit("read_vtu.py: %s" % e)
    for a in arrays.values():
        print("%-14s %-8s %d  %s" % (a.name, a.type, a.components,
                                     " ".join(str(v) for v in a.values[:6])))


if __name__ == "__main__":
    main()
