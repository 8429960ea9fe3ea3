#!/usr/bin/env python3
"""Writes the seed corpus and dictionary of fuzz_mesh_reader: small valid and broken files of every format (OBJ, PLY,
STL, OFF, glTF).

    fuzz/tools/make_mesh_seeds.py        (from the repository root; rewrites fuzz/corpus/mesh_reader/seed-*
                                          and fuzz/dict/mesh_reader.dict)
"""
import base64
import json
import os
import struct

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
corpus = os.path.join(root, "corpus", "mesh_reader")
os.makedirs(corpus, exist_ok=True)
for f in os.listdir(corpus):
    if f.startswith("seed-"):
        os.remove(os.path.join(corpus, f))

seeds = {}

# OBJ
seeds["obj-triangle"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
seeds["obj-features"] = (b"# comment\r\nmtllib a.mtl\r\no x\nv 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nv 0x1p-1 1 0\nv 0.1 \\\n 0.2 0.3\n"
                         b"vt 0 1\nvn 0 0 1\ns off\ng g\nusemtl m\nf 1 2 3\nf 1/1 2/1 3/1 4/1 # quad\nf -4//1 -3//1 -1//1\n"
                         b"f 4/1/1 3/1/1 2/1/1 1/1/1 2/1/1\nl 1 2\np 3\n")
seeds["obj-forward-refs"] = b"f 1 2 3\nv 0.1 -0 1e-320\nv 2 2 2\nv 4.9406564584124654e-324 3 3\n"
seeds["obj-octahedron"] = (b"v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                           b"f 1 3 5\nf 1 6 3\nf 1 5 4\nf 1 4 6\nf 2 5 3\nf 2 3 6\nf 2 4 5\nf 2 6 4\n")
seeds["obj-bad-index"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"
seeds["obj-zero-index"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"
seeds["obj-two-vertices"] = b"v 0 0 0\nv 1 0 0\nf 1 2\n"
seeds["obj-nan"] = b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"
seeds["obj-underflow"] = b"v 1e-400 0 0\n"
seeds["obj-overflow"] = b"v 1e400 0 0\n"
seeds["obj-unknown"] = b"vertex 1 2 3\n"
# Index extremes (a regression: -9223372036854775808 negated to itself and was taken as in range).
seeds["obj-int64-min"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n"
seeds["obj-int64-min-then-vertex"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\nv 0 0 1\n"
seeds["obj-int64-max"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9223372036854775807\n"
seeds["obj-index-2-32"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967297\nf -4294967296 1 2\n"
seeds["obj-relative"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf -4 -1 -2 +1\n"

# PLY
ply_head = (b"ply\nformat ascii 1.0\ncomment c\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            b"element face 1\nproperty list uchar int vertex_indices\nend_header\n")
seeds["ply-ascii"] = ply_head + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
seeds["ply-ascii-extras"] = (b"ply\r\nformat ascii 1.0\nobj_info x\nelement material 1\nproperty uchar red\nproperty list uchar float w\n"
                             b"element vertex 4\nproperty float nx\nproperty double z\nproperty list uchar int ring\nproperty float y\n"
                             b"property float x\nproperty uchar alpha\nelement face 2\nproperty uchar flags\n"
                             b"property list uchar int vertex_index\nproperty list int float uv\nend_header\n"
                             b"255 2 0.5 0.25\n9 3 2 7 7 1 -0.5 0\n9 0.1 0 2 0 255\n\n9 0x1p-2 1 5 1e-300 1e300 0\n9 -0 0 4 4 4\n"
                             b"1 3 0 1 2 0\n0 4 3 2 1 0 2 0.5 0.5\n")
seeds["ply-ascii-bad-index"] = ply_head + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"
seeds["ply-ascii-truncated"] = ply_head + b"0 0 0\n1 0 0\n"
seeds["ply-ascii-wrong-count"] = ply_head + b"0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n"
seeds["ply-ascii-int-min"] = ply_head + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 -2147483648\n"
seeds["ply-ascii-uint-max"] = ply_head.replace(b"uchar int", b"uchar uint") + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 4294967295\n"


def binary_ply(big, double, id_type="short"):
    e = ">" if big else "<"
    head = ("ply\nformat %s 1.0\nelement vertex 3\nproperty %s id\n" % ("binary_big_endian" if big else "binary_little_endian", id_type))
    t = "double" if double else "float"
    head += "property %s x\nproperty %s y\nproperty %s z\nproperty list uchar uchar extra\n" % (t, t, t)
    head += "element face 1\nproperty list ushort uint vertex_indices\nproperty int tag\nelement trailer 1\n"
    head += "property list int double junk\nend_header\n"
    out = head.encode()
    coords = [(0.1, 0.2, 0.3), (1e-40, -2, 3), (5, 6, 1e38)]
    for i, c in enumerate(coords):
        out += struct.pack(e + "h", i)
        out += struct.pack(e + ("ddd" if double else "fff"), *c)
        out += struct.pack(e + "BBB", 2, 9, 9)
    out += struct.pack(e + "H", 3) + struct.pack(e + "III", 2, 1, 0) + struct.pack(e + "i", -7)
    out += struct.pack(e + "i", 2) + struct.pack(e + "dd", 1.5, 2.5)
    return out


seeds["ply-binary-le-float"] = binary_ply(False, False)
seeds["ply-binary-be-float"] = binary_ply(True, False)
seeds["ply-binary-le-double"] = binary_ply(False, True)
seeds["ply-binary-be-double"] = binary_ply(True, True)
seeds["ply-binary-truncated"] = binary_ply(False, False)[:-20]
seeds["ply-binary-trailing"] = binary_ply(True, True) + b"x"
bad = bytearray(binary_ply(False, False))
body = bytes(bad).find(b"end_header\n") + 11
bad[body + 17 + 6:body + 17 + 10] = struct.pack("<f", float("nan"))
seeds["ply-binary-nan"] = bytes(bad)
seeds["ply-bad-header"] = b"ply\nformat ascii 2.0\nend_header\n"

# STL


def binary_stl(facets, header=b"binary"):
    out = header.ljust(80, b" ") + struct.pack("<I", len(facets))
    for f in facets:
        out += struct.pack("<3f", 0, 0, 0) + struct.pack("<9f", *f) + struct.pack("<H", 0)
    return out


seeds["stl-binary"] = binary_stl([(0, 0, 0, 1, 0, 0, 0, 1, 0), (1, 0, 0, 0.1, 1, 0, 0, 1, 0)])
seeds["stl-binary-solid-header"] = binary_stl([(0, 0, 0, 1, 0, 0, 0, 1, 0)], b"solid but binary")
seeds["stl-binary-truncated"] = binary_stl([(0, 0, 0, 1, 0, 0, 0, 1, 0)])[:120]
inf_stl = bytearray(binary_stl([(0, 0, 0, 1, 0, 0, 0, 1, 0)]))
inf_stl[84 + 28:84 + 32] = struct.pack("<f", float("inf"))
seeds["stl-binary-inf"] = bytes(inf_stl)
seeds["stl-ascii"] = (b"solid two parts\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n"
                      b"      vertex 0 1 0\n    endloop\n  endfacet\nendsolid two parts\r\nsolid second\n facet normal nan 0 0\n"
                      b" outer loop\n vertex 0.1 0 0\n vertex 1 0 0\n vertex 1 1 0\n vertex 0 1 0\n endloop\n endfacet\nendsolid\n")
seeds["stl-ascii-two-vertices"] = (b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n"
                                   b"endsolid\n")
seeds["stl-ascii-truncated"] = b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"

# OFF
seeds["off-colours"] = (b"# header comment\nCOFF 5 2 0\n0 0 0 255 0 0 255\n1 0 0\n\n# between\n1 1 0 # trailing\n0 1 0\n"
                        b"0x1p-1 0.5 1\n4 0 1 2 3 0.5 0.5 0.5 1\n3 4 3 2\n")
seeds["off-counts-apart"] = b"OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
seeds["off-bad-index"] = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"
seeds["off-wrong-count"] = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n"
seeds["off-4d"] = b"4OFF\n1 0 0\n0 0 0 0\n"
seeds["off-int64-min"] = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -9223372036854775808\n"
seeds["off-huge-count"] = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n9223372036854775807 0 1 2\n"

# glTF 2.0: a tetrahedron's float32 positions and uint16 indices, as JSON with a data: URI and as GLB
gltf_buffer = (b"".join(struct.pack("<3f", *p) for p in [(0.1, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1e-40)])
               + struct.pack("<6H", 0, 1, 2, 0, 2, 3))


def gltf_document(uri=True, **extra):
    d = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(gltf_buffer)}],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                         {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                       {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}]}
    if uri:
        d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(gltf_buffer).decode()
    d.update(extra)
    return json.dumps(d).encode()


seeds["gltf-json"] = gltf_document()
seeds["gltf-nodes"] = gltf_document(scene=0, scenes=[{"nodes": [0]}],
                                    nodes=[{"translation": [1, 0, 0], "children": [1]}, {"mesh": 0, "scale": [2, 4, 0.5]}])
seeds["gltf-strip-fan-lines"] = gltf_document(meshes=[{"primitives": [
    {"attributes": {"POSITION": 0}, "indices": 1, "mode": 5}, {"attributes": {"POSITION": 0}, "mode": 6},
    {"attributes": {"POSITION": 0}, "mode": 1}]}])
seeds["gltf-rotated"] = gltf_document(scenes=[{"nodes": [0]}], nodes=[{"mesh": 0, "rotation": [0, 0, 1, 0]}])
gltf_json = gltf_document(uri=False)
gltf_json += b" " * (-len(gltf_json) % 4)
seeds["gltf-glb"] = (b"glTF" + struct.pack("<II", 2, 12 + 8 + len(gltf_json) + 8 + len(gltf_buffer))
                     + struct.pack("<I", len(gltf_json)) + b"JSON" + gltf_json
                     + struct.pack("<I", len(gltf_buffer)) + b"BIN\0" + gltf_buffer)

# Neither
seeds["empty"] = b""
seeds["garbage"] = bytes(range(256))

for name, data in seeds.items():
    with open(os.path.join(corpus, "seed-" + name), "wb") as f:
        f.write(data)

words = [b"v ", b"vt ", b"vn ", b"f ", b"o ", b"g ", b"s ", b"l ", b"usemtl ", b"mtllib ", b"#", b"\\\n", b"\r\n", b"/", b"//",
         b"-1", b"0", b"ply\n", b"format ascii 1.0\n", b"format binary_little_endian 1.0\n", b"format binary_big_endian 1.0\n",
         b"comment ", b"obj_info ", b"element vertex ", b"element face ", b"element ", b"property float x\n",
         b"property double y\n", b"property int z\n", b"property list uchar int vertex_indices\n", b"property list ",
         b"vertex_index", b"uchar", b"ushort", b"uint", b"char", b"short", b"int", b"float", b"double", b"int8", b"uint32",
         b"float64", b"end_header\n", b"solid ", b"facet normal ", b"outer loop", b"vertex ", b"endloop", b"endfacet",
         b"endsolid", b"OFF\n", b"COFF", b"NOFF", b"STOFF", b"0x1p-1074", b"0x1.8p3", b"1e-400", b"1e400", b"4.9406564584124654e-324",
         b"1.7976931348623157e308", b"nan", b"inf", b"-0", b".5", b"5.", b"+1", b"\x00\x00\x80\x7f", b"\x00\x00\xc0\x7f",
         b"\xff\xff\xff\xff", b"\x03\x00\x00\x00", b"-9223372036854775808", b"9223372036854775807", b"-2147483648",
         b"4294967295", b"4294967296", b"18446744073709551615", b"\x00\x00\x00\x80",
         # glTF
         b'"asset"', b'"version"', b'"2.0"', b'"buffers"', b'"bufferViews"', b'"accessors"', b'"meshes"',
         b'"primitives"', b'"attributes"', b'"POSITION"', b'"indices"', b'"mode"', b'"nodes"', b'"scenes"', b'"scene"',
         b'"children"', b'"matrix"', b'"translation"', b'"rotation"', b'"scale"', b'"byteLength"', b'"byteOffset"',
         b'"byteStride"', b'"componentType"', b'"count"', b'"type"', b'"VEC3"', b'"SCALAR"', b'"uri"',
         b'"data:application/octet-stream;base64,"', b'"sparse"', b'"bufferView"', b'"buffer"', b'"mesh"', b"5126",
         b"5123", b"5125", b"5121", b"glTF", b"JSON", b"BIN\x00"]
with open(os.path.join(root, "dict", "mesh_reader.dict"), "w") as f:
    f.write("# libFuzzer dictionary for fuzz_mesh_reader: the keywords and numbers of OBJ, PLY, STL, OFF and glTF\n"
            "# (generated by fuzz/tools/make_mesh_seeds.py)\n")
    for i, w in enumerate(words):
        f.write('t%02d="%s"\n' % (i, "".join("\\x%02x" % b for b in w)))
print("wrote %d seeds and %d dictionary entries" % (len(seeds), len(words)))
