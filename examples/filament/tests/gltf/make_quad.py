#!/usr/bin/env python3
"""Writes the glTF test scenes of examples/filament/tests/ (run_test.sh's gltf-* cases) into this
folder: a 2x2 quad in the xz-plane facing +y, uv 0..2 (its maps repeat twice), with a base colour
map (a checker), a normal map (round bumps, OpenGL convention) and a metallic-roughness map (G
roughness in stripes, B metallic: the right half), all 32x32 PNGs. quad.gltf places a perspective
camera 1 unit above the quad looking straight down (the quad fills its view); quad_nocamera.gltf
is the same without it (the program frames the scene). Standard library only.
    python3 examples/filament/tests/gltf/make_quad.py"""
import base64, json, math, os, struct, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
N = 32


def png(path, pixels):  # pixels[y][x] = (r, g, b) bytes
    raw = b"".join(b"\0" + bytes(c for p in row for c in p) for row in pixels)
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))
    head = struct.pack(">IIBBBBB", len(pixels[0]), len(pixels), 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", head) + chunk(b"IDAT", zlib.compress(raw, 9))
                + chunk(b"IEND", b""))


def bump_normal(x, y):  # a round bump per 16x16 cell: height h = cos², slopes by differences
    def h(u, v):
        a, b = (u % 16) / 16 - 0.5, (v % 16) / 16 - 0.5
        return math.cos(math.pi * min(1.0, 2 * math.hypot(a, b))) ** 2 if math.hypot(a, b) < 0.5 else 0
    dx = (h(x + 0.5, y) - h(x - 0.5, y)) * 2
    dy = -(h(x, y + 0.5) - h(x, y - 0.5)) * 2  # +Y up the image (OpenGL convention)
    n = (-dx, -dy, 1)
    l = math.sqrt(sum(c * c for c in n))
    return tuple(round(255 * (0.5 + 0.5 * c / l)) for c in n)


png(os.path.join(HERE, "quad_basecolor.png"),
    [[(200, 60, 40) if (x // 8 + y // 8) % 2 else (230, 220, 200) for x in range(N)] for y in range(N)])
png(os.path.join(HERE, "quad_normal.png"), [[bump_normal(x, y) for x in range(N)] for y in range(N)])
png(os.path.join(HERE, "quad_metalrough.png"),
    [[(255, 60 if (y // 4) % 2 else 160, 255 if x >= N // 2 else 0) for x in range(N)] for y in range(N)])

# Geometry: 4 vertices (POSITION, NORMAL, TEXCOORD_0), 2 triangles counter-clockwise from +y.
positions = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1)]
normals = [(0, 1, 0)] * 4
uvs = [(0, 0), (2, 0), (2, 2), (0, 2)]
indices = [0, 2, 1, 0, 3, 2]
blob = (b"".join(struct.pack("<3f", *p) for p in positions) + b"".join(struct.pack("<3f", *n) for n in normals)
        + b"".join(struct.pack("<2f", *t) for t in uvs) + struct.pack("<6H", *indices) + b"\0\0")


def scene(camera):
    nodes = [{"mesh": 0, "name": "quad"}]
    gltf = {
        "asset": {"version": "2.0", "generator": "examples/filament/tests/gltf/make_quad.py"},
        "scene": 0, "scenes": [{"nodes": [0, 1] if camera else [0]}], "nodes": nodes,
        "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                      "indices": 3, "material": 0}]}],
        "materials": [{"name": "bumpy", "normalTexture": {"index": 1},
                       "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 2},
                                                "metallicFactor": 1.0, "roughnessFactor": 0.8}}],
        "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
        "images": [{"uri": "quad_basecolor.png"}, {"uri": "quad_normal.png"}, {"uri": "quad_metalrough.png"}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }
    if camera:
        # 1 unit above the origin, turned -90° about x: its -z looks down -y, its +y is -z.
        s = math.sqrt(0.5)
        nodes.append({"camera": 0, "name": "top", "translation": [0, 1, 0], "rotation": [-s, 0, 0, s]})
        gltf["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 100}}]
    return gltf


for name, camera in (("quad.gltf", True), ("quad_nocamera.gltf", False)):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(scene(camera), f, indent=1)
        f.write("\n")
