#!/usr/bin/env python3
"""Writes the malformed-input corpus (issue 15) into crates/obscura-cli/tests/corpus/: scene files
that are broken or degenerate in the ways real files are, and manifest.json with what `obscura
render --scene FILE` must do with each ("error" with a word the one-line message must contain, or
"ok"). tests/it/cli.rs runs every entry: the exit status, one line of message, no panic, no output
file on error, under 10 s. Python's standard library only; run again after changing it:

    python3 scripts/make-corpus.py
"""
import base64
import json
import os
import struct

OUT = os.path.join(os.path.dirname(__file__), "..", "crates", "obscura-cli", "tests", "corpus")
cases = []


def add(name, data, outcome, needle=""):
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    cases.append({"file": name, "outcome": outcome, "needle": needle})


def triangle_buffer(positions=((0, 0, 0), (1, 0, 0), (0, 1, 0)), indices=(0, 1, 2)):
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    idx = struct.pack(f"<{len(indices)}H", *indices)
    idx += b"\0" * (-len(idx) % 4)
    return pos + idx, len(pos), len(idx)


def gltf(mutate=None, positions=None, indices=(0, 1, 2)):
    buf, npos, nidx = triangle_buffer(positions or ((0, 0, 0), (1, 0, 0), (0, 1, 0)), indices)
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": npos},
                        {"buffer": 0, "byteOffset": npos, "byteLength": nidx}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
    }
    if mutate:
        mutate(doc)
    return json.dumps(doc)


def glb(doc_json, bin_chunk=b"", total=None, json_len=None):
    j = doc_json.encode()
    j += b" " * (-len(j) % 4)
    body = struct.pack("<I", json_len if json_len is not None else len(j)) + b"JSON" + j
    if bin_chunk:
        b = bin_chunk + b"\0" * (-len(bin_chunk) % 4)
        body += struct.pack("<I", len(b)) + b"BIN\0" + b
    length = total if total is not None else 12 + len(body)
    return b"glTF" + struct.pack("<II", 2, length) + body


def main():
    os.makedirs(OUT, exist_ok=True)
    for f in os.listdir(OUT):
        os.remove(os.path.join(OUT, f))
    # --- glTF / GLB ---
    add("valid.gltf", gltf(), "ok")
    add("truncated.glb", glb(gltf())[:40], "error", "truncated.glb")
    add("glb-bad-total-length.glb", glb(gltf(), total=999999), "error", "glb-bad-total-length.glb")
    add("glb-bad-json-length.glb", glb(gltf(), json_len=4000), "error", "glb-bad-json-length.glb")
    add("glb-not-glb.glb", b"GLTF" + b"\0" * 40, "error", "glb-not-glb.glb")
    add("empty.gltf", "", "error", "empty.gltf")
    add("not-json.gltf", "{ this is not json", "error", "not-json.gltf")
    add("index-out-of-range.gltf", gltf(indices=(0, 1, 7)), "error", "index-out-of-range.gltf")
    add("accessor-view-out-of-range.gltf",
        gltf(lambda d: d["accessors"][0].update(bufferView=9)), "error", "accessor-view-out-of-range")
    add("view-past-buffer.gltf",
        gltf(lambda d: d["bufferViews"][0].update(byteLength=4096)), "error", "view-past-buffer")
    add("accessor-count-huge.gltf",
        gltf(lambda d: d["accessors"][0].update(count=2**31)), "error", "accessor-count-huge")
    add("position-wrong-type.gltf",
        gltf(lambda d: d["accessors"][0].update(type="VEC2")), "error", "position-wrong-type")
    add("required-extension.gltf",
        gltf(lambda d: d.update(extensionsRequired=["KHR_draco_mesh_compression"],
                                extensionsUsed=["KHR_draco_mesh_compression"])),
        "error", "KHR_draco_mesh_compression")
    add("missing-buffer-file.gltf",
        gltf(lambda d: d["buffers"][0].update(uri="nowhere.bin")), "error", "missing-buffer-file")
    add("bad-data-uri.gltf",
        gltf(lambda d: d["buffers"][0].update(uri="data:application/octet-stream;base64,@@@@")),
        "error", "bad-data-uri")
    add("nan-position.gltf", gltf(positions=((0, 0, 0), (float("nan"), 0, 0), (0, 1, 0))).replace(
        "NaN", "NaN"), "error", "nan-position")
    add("node-cycle.gltf",
        gltf(lambda d: d.update(nodes=[{"mesh": 0, "children": [1]}, {"children": [0]}])),
        "ok", "reached twice")
    add("no-scenes.gltf", gltf(lambda d: (d.pop("scenes"), d.pop("scene"))), "ok")
    add("scene-index-out-of-range.gltf", gltf(lambda d: d.update(scene=5)), "error",
        "scene-index-out-of-range")
    add("missing-image.gltf", gltf(lambda d: d.update(
        images=[{"uri": "missing.png"}], textures=[{"source": 0}],
        materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        meshes=[{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}])),
        "error", "missing-image")
    add("scaled-1e30.gltf", gltf(lambda d: d["nodes"][0].update(scale=[1e30, 1e30, 1e30])),
        "error", "spans")
    add("scaled-0.gltf", gltf(lambda d: d["nodes"][0].update(scale=[0, 0, 0])), "ok",
        "zero extent")
    # --- OBJ ---
    tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    add("valid.obj", tri + "f 1 2 3\n", "ok")
    add("index-zero.obj", tri + "f 0 1 2\n", "error", "index-zero.obj")
    add("index-out-of-range.obj", tri + "f 1 2 99\n", "error", "index-out-of-range.obj")
    add("index-negative-out-of-range.obj", tri + "f -1 -2 -9\n", "error",
        "index-negative-out-of-range.obj")
    add("index-not-a-number.obj", tri + "f 1 two 3\n", "error", "index-not-a-number.obj")
    add("nan-vertex.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "error", "nan-vertex.obj")
    add("overflow-vertex.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n", "error",
        "overflow-vertex.obj")
    add("binary.obj", bytes(range(256)) * 16, "error", "binary.obj")
    add("empty.obj", "", "error", "empty.obj")
    add("no-faces.obj", tri, "error", "no-faces.obj")
    fan = "".join(f"v {x} {y} -3\n" for x, y in
                  ((__import__("math").cos(6.283185307 * k / 5000),
                    __import__("math").sin(6.283185307 * k / 5000)) for k in range(5000)))
    add("polygon-fan-5000.obj", fan + "f " + " ".join(str(k) for k in range(1, 5001)) + "\n", "ok")
    add("self-mtllib.obj", "mtllib self-mtllib.obj\n" + tri + "f 1 2 3\n", "ok")
    add("missing-mtllib.obj", "mtllib nowhere.mtl\n" + tri + "f 1 2 3\n", "ok", "nowhere.mtl")
    with open(os.path.join(OUT, "missing-texture.mtl"), "w") as f:
        f.write("newmtl m\nmap_Kd nowhere.png\n")
    add("missing-texture.obj", "mtllib missing-texture.mtl\nusemtl m\n" + tri + "f 1 2 3\n",
        "ok", "nowhere.png")
    add("collapsed.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n", "ok", "zero extent")
    with open(os.path.join(OUT, "manifest.json"), "w") as f:
        json.dump(cases, f, indent=1)
    with open(os.path.join(OUT, "README.md"), "w") as f:
        f.write("# Malformed-input corpus\n\nMade by `scripts/make-corpus.py` (do not edit by hand); "
                "`tests/it/cli.rs` renders every file with `obscura render --scene FILE` and checks the "
                "outcome below: exit status 1 with one line of message containing the text (error), or "
                "success with the text in the warnings (ok); never a panic, nothing written on error, "
                "under 10 s each.\n\n| file | outcome | message contains |\n|---|---|---|\n")
        for c in cases:
            f.write(f"| `{c['file']}` | {c['outcome']} | {c['needle'] or '–'} |\n")
    print(f"{len(cases)} corpus files in {os.path.normpath(OUT)}")


main()
