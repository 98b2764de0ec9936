#!/usr/bin/env python3
"""Writes small glTF files for the command-line tests of glTF scenes (tests/gltf_cli.sh) and the
fuzzer's seeds (scripts/fuzz.sh):

  gltf_corpus.py bad DIR     malformed files, one per error class of docs/gltf.md, and DIR/expect.tsv:
                             FILE<TAB>the message clpt must print after "FILE: "
  gltf_corpus.py good DIR    a few valid files: lit.glb (a floor, a box, a point and a spot light,
                             a camera), lit.gltf (the same, buffer embedded), strip.gltf (a
                             triangle strip and a fan), sparse.glb (a sparse accessor)

Each file is built from a valid one by one change, so that a message names the change.
"""
import base64
import copy
import json
import math
import os
import struct
import sys


def glb(doc, bin_bytes=b"", magic=b"glTF", version=2, json_type=b"JSON", extra=b""):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    out = struct.pack("<I", len(text)) + json_type + text
    if bin_bytes:
        bin_bytes += b"\0" * (-len(bin_bytes) % 4)
        out += struct.pack("<I", len(bin_bytes)) + b"BIN\0" + bin_bytes
    out += extra
    return magic + struct.pack("<II", version, 12 + len(out)) + out


class Model:
    """A glTF document and its one buffer."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "nodes": []}
        self.bin = b""

    def view(self, data):
        self.bin += b"\0" * (-len(self.bin) % 4)
        self.doc.setdefault("bufferViews", []).append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, values, fmt, component, kind, **extra):
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        per = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[kind]
        a = {"bufferView": self.view(data), "componentType": component, "count": len(values) // per, "type": kind}
        a.update(extra)
        self.doc.setdefault("accessors", []).append(a)
        return len(self.doc["accessors"]) - 1

    def positions(self, xyz):
        lo = [min(xyz[i::3]) for i in range(3)]
        hi = [max(xyz[i::3]) for i in range(3)]
        return self.accessor(xyz, "f", 5126, "VEC3", min=lo, max=hi)

    def mesh(self, primitive):
        self.doc.setdefault("meshes", []).append({"primitives": [primitive]})
        return len(self.doc["meshes"]) - 1

    def node(self, node, root=True):
        self.doc["nodes"].append(node)
        if root:
            self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)
        return len(self.doc["nodes"]) - 1

    def buffers(self, uri=None):
        doc = copy.deepcopy(self.doc)
        buffer = {"byteLength": len(self.bin)}
        if uri is not None:
            buffer["uri"] = uri
        doc["buffers"] = [buffer]
        return doc

    def glb(self):
        return glb(self.buffers(), self.bin)

    def embedded(self):
        return json.dumps(self.buffers("data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()))


def lit_model():
    """A floor, a box on it, a point light, a spot light, a camera looking at the box."""
    m = Model()
    floor = [-2, 0, -2, -2, 0, 2, 2, 0, 2, 2, 0, -2]
    m.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
                                                    "roughnessFactor": 0.9}},
                          {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.3, 0.2, 1], "metallicFactor": 0.5,
                                                    "roughnessFactor": 0.4}}]
    m.node({"name": "floor", "mesh": m.mesh({"attributes": {"POSITION": m.positions(floor)},
                                             "indices": m.accessor([0, 1, 2, 0, 2, 3], "H", 5123, "SCALAR"),
                                             "material": 0})})
    box = [x for c in range(8) for x in ((c & 1) - 0.5, (c >> 1 & 1), (c >> 2 & 1) - 0.5)]
    faces = [0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5]
    m.node({"name": "box", "mesh": m.mesh({"attributes": {"POSITION": m.positions(box)},
                                           "indices": m.accessor(faces, "B", 5121, "SCALAR"), "material": 1}),
            "rotation": [0, math.sin(0.3), 0, math.cos(0.3)]})
    m.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    m.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.9, 0.8], "intensity": 683 * 20, "name": "bulb"},
        {"type": "spot", "intensity": 683 * 40, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}]}}
    m.node({"translation": [1, 3, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}})
    m.node({"translation": [-2, 3, 0], "rotation": [0, 0, math.sin(-math.pi / 8), math.cos(-math.pi / 8)],
            "extensions": {"KHR_lights_punctual": {"light": 1}}})
    m.doc["cameras"] = [{"type": "perspective", "name": "view",
                         "perspective": {"yfov": 0.8, "znear": 0.05, "aspectRatio": 4 / 3}}]
    m.node({"camera": 0, "translation": [0, 1.5, 5], "rotation": [math.sin(-0.1), 0, 0, math.cos(-0.1)]})
    return m


def triangle_model():
    m = Model()
    m.node({"mesh": m.mesh({"attributes": {"POSITION": m.positions([0, 0, 0, 1, 0, 0, 0, 1, 0])}})})
    return m


def bad_cases():
    """(file name, bytes or text, extra files {name: bytes}, expected message after 'FILE: ')."""
    t = triangle_model()
    good = t.glb()
    cases = []

    def json_case(name, change, expected, extra=None):
        doc = t.buffers("data:application/octet-stream;base64," + base64.b64encode(t.bin).decode())
        change(doc)
        # JSON has no infinity: a number too large for a double is how a file says it.
        cases.append((name + ".gltf", json.dumps(doc).replace("Infinity", "1e999"), extra or {}, expected))

    # The GLB container.
    cases += [
        ("glb_magic.glb", b"glTX" + good[4:], {}, "GLB header: the magic is not 'glTF'"),
        ("glb_version.glb", good[:4] + struct.pack("<I", 1) + good[8:], {}, "GLB header: version 1 (clpt reads glTF 2)"),
        ("glb_length.glb", good + b"\0\0\0\0", {}, "GLB header: the header gives a length of"),
        ("glb_truncated.glb", good[:8] + struct.pack("<I", len(good) - 4) + good[12:-4], {},
         "GLB chunk 1: its length"),
        ("glb_bin_first.glb", glb(t.buffers(), t.bin, json_type=b"BIN\0"), {}, "GLB chunk 0: the first chunk must be JSON"),
        ("glb_short.glb", good[:10], {}, "GLB header: the file is 10 bytes, shorter than the 12-byte header"),
        ("glb_two_json.glb", glb(t.buffers(), t.bin, extra=struct.pack("<I", 4) + b"JSON" + b"{}  "), {},
         "GLB chunk 2: a second JSON chunk"),
    ]
    # JSON that is not glTF.
    cases.append(("not_json.gltf", "solid cube\nfacet normal 0 0 1\n", {}, "JSON: not valid JSON"))
    cases.append(("deep.gltf", "[" * 5000 + "]" * 5000, {}, "JSON: nested deeper than 64 levels"))
    json_case("no_asset", lambda d: d.pop("asset"), "asset: missing")
    json_case("version_1", lambda d: d["asset"].update(version="1.0"), "asset.version: '1.0': clpt reads glTF 2.x")
    json_case("draco_required", lambda d: d.update(extensionsRequired=["KHR_draco_mesh_compression"]),
              "extensionsRequired[0]: the file requires KHR_draco_mesh_compression, which clpt does not implement")
    # Indices, accessors and byte ranges.
    json_case("accessor_out_of_range", lambda d: d["meshes"][0]["primitives"][0]["attributes"].update(POSITION=7),
              "meshes[0].primitives[0].attributes.POSITION: accessor 7 is out of range")
    json_case("view_past_buffer", lambda d: d["bufferViews"][0].update(byteLength=4000),
              "bufferViews[0]: bytes 0 to 4000 run past the end of buffers[0]")
    json_case("accessor_past_view", lambda d: d["accessors"][0].update(count=4),
              "accessors[0]: 4 elements of 12 bytes")
    json_case("huge_count", lambda d: (d["accessors"][0].pop("bufferView"), d["accessors"][0].update(count=4000000000)),
              "accessors[0].count: 4000000000 elements without a buffer view")
    json_case("bad_mode", lambda d: d["meshes"][0]["primitives"][0].update(mode=7),
              "meshes[0].primitives[0].mode: 7 is not a glTF primitive mode")
    json_case("scene_out_of_range", lambda d: d.update(scene=2), "scene: 2 is out of range")
    idx = copy.deepcopy(t)
    idx.doc["meshes"][0]["primitives"][0]["indices"] = idx.accessor([0, 1, 3], "I", 5125, "SCALAR")
    cases.append(("index_out_of_range.glb", idx.glb(), {},
                  "meshes[0].primitives[0].indices: index 2 is 3, out of range (the primitive has 3 vertices)"))
    nan = copy.deepcopy(t)
    nan.bin = struct.pack("<f", float("nan")) + nan.bin[4:]
    cases.append(("nan_position.glb", nan.glb(), {}, "accessors[0]: element 0 is not finite"))
    # Values outside the schema's ranges.
    json_case("inf_matrix", lambda d: d["nodes"][0].update(matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e999, 0, 0, 1]),
              "JSON: not valid JSON: number overflow parsing '1e999'")
    json_case("singular_matrix", lambda d: d["nodes"][0].update(matrix=[1, 0, 0, 0, 2, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]),
              "nodes[0].matrix: the matrix is singular")
    json_case("zero_quaternion", lambda d: d["nodes"][0].update(rotation=[0, 0, 0, 0]),
              "nodes[0].rotation: a rotation quaternion must have length 1")
    json_case("long_quaternion", lambda d: d["nodes"][0].update(rotation=[0, 0, 0, 1.01]),
              "nodes[0].rotation: a rotation quaternion must have length 1")
    json_case("base_colour_above_1", lambda d: (d.update(materials=[{"pbrMetallicRoughness": {"baseColorFactor": [1.5, 0, 0, 1]}}]),
                                                d["meshes"][0]["primitives"][0].update(material=0)),
              "materials[0].pbrMetallicRoughness.baseColorFactor[0]: must be in [0, 1] (got 1.5)")
    json_case("metallic_below_0", lambda d: d.update(materials=[{"pbrMetallicRoughness": {"metallicFactor": -0.1}}]),
              "materials[0].pbrMetallicRoughness.metallicFactor: must be in [0, 1] (got -0.1)")
    json_case("alpha_cutoff_negative", lambda d: d.update(materials=[{"alphaMode": "MASK", "alphaCutoff": -0.5}]),
              "materials[0].alphaCutoff: must be in [0, inf] (got -0.5)")
    json_case("alpha_cutoff_not_a_number", lambda d: d.update(materials=[{"alphaMode": "MASK", "alphaCutoff": "half"}]),
              "materials[0].alphaCutoff: must be a number (got \"half\")")
    json_case("alpha_mode_unknown", lambda d: d.update(materials=[{"alphaMode": "CLIP"}]),
              "materials[0].alphaMode: 'CLIP' (expected OPAQUE, MASK or BLEND)")
    json_case("alpha_mode_not_a_string", lambda d: d.update(materials=[{"alphaMode": 1}]),
              "materials[0].alphaMode: must be a string (got 1)")

    def camera(**perspective):
        p = {"yfov": 0.8, "znear": 0.1}
        p.update(perspective)
        return lambda d: (d.update(cameras=[{"type": "perspective", "perspective": p}]), d["nodes"].append({"camera": 0}),
                          d["scenes"][0]["nodes"].append(1))
    json_case("yfov_0", camera(yfov=0), "cameras[0].perspective.yfov: must be in (0, pi) radians")
    json_case("yfov_pi", camera(yfov=math.pi), "cameras[0].perspective.yfov: must be in (0, pi) radians")
    json_case("znear_0", camera(znear=0), "cameras[0].perspective.znear: must be > 0")

    def light(**values):
        spec = {"type": "point"}
        spec.update(values)
        return lambda d: (d.update(extensions={"KHR_lights_punctual": {"lights": [spec]}}),
                          d["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}}),
                          d["scenes"][0]["nodes"].append(1))
    json_case("negative_intensity", light(intensity=-5), "KHR_lights_punctual.lights[0].intensity: must be >= 0")
    json_case("negative_colour", light(color=[1, -1, 1]), "KHR_lights_punctual.lights[0].color[1]: must be in [0, 1]")
    json_case("negative_range", light(range=-1), "KHR_lights_punctual.lights[0].range: must be > 0")
    json_case("spot_cones", light(type="spot", spot={"innerConeAngle": 0.8, "outerConeAngle": 0.4}),
              "KHR_lights_punctual.lights[0].spot: the cone angles must satisfy")
    # The node graph.
    json_case("cycle", lambda d: (d["nodes"].extend([{"children": [2]}, {"children": [1]}])),
              "nodes[2]: the node is its own ancestor")
    json_case("two_parents", lambda d: (d["nodes"].extend([{"children": [0]}])),
              "scenes[0].nodes[0]: nodes[0] is not a root node (it is a child of nodes[1])")
    json_case("two_parents_below", lambda d: (d["nodes"].extend([{"children": [0]}, {"children": [0]}])),
              "nodes[2].children[0]: nodes[0] has two parents, nodes[1] and nodes[2]")
    # Buffers and URIs.
    ext = copy.deepcopy(t)
    cases.append(("missing_bin.gltf", json.dumps(ext.buffers("missing.bin")), {},
                  "buffers[0].uri: cannot open 'missing.bin': No such file or directory"))
    cases.append(("uri_parent.gltf", json.dumps(ext.buffers("../tri.bin")), {},
                  "buffers[0].uri: '../tri.bin' leaves the glTF file's folder ('..')"))
    cases.append(("uri_absolute.gltf", json.dumps(ext.buffers("/etc/hostname")), {},
                  "buffers[0].uri: '/etc/hostname' is not a relative path inside the glTF file's folder"))
    cases.append(("uri_scheme.gltf", json.dumps(ext.buffers("http://example.com/tri.bin")), {},
                  "buffers[0].uri: 'http://example.com/tri.bin' is not a relative path inside the glTF file's folder"))
    cases.append(("data_not_base64.gltf", json.dumps(ext.buffers("data:application/octet-stream,abcd")), {},
                  "buffers[0].uri: a data: URI must be base64"))
    cases.append(("bin_short.gltf", json.dumps(ext.buffers("short.bin")), {"short.bin": ext.bin[:-4]},
                  "buffers[0].uri: 'short.bin' is %d bytes, byteLength says %d" % (len(ext.bin) - 4, len(ext.bin))))
    second = copy.deepcopy(t.buffers())
    second["buffers"].append({"byteLength": 4})
    cases.append(("glb_second_buffer.glb", glb(second, t.bin), {},
                  "buffers[1]: no 'uri' (only a GLB file's first buffer may refer to its BIN chunk)"))
    return cases


def write(path, data):
    with open(path, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("bad", "good"):
        sys.exit(__doc__)
    out = sys.argv[2]
    os.makedirs(out, exist_ok=True)
    if sys.argv[1] == "bad":
        with open(os.path.join(out, "expect.tsv"), "w") as manifest:
            for name, data, extra, expected in bad_cases():
                write(os.path.join(out, name), data)
                for extra_name, extra_data in extra.items():
                    write(os.path.join(out, extra_name), extra_data)
                manifest.write("%s\t%s\n" % (name, expected))
        return
    lit = lit_model()
    write(os.path.join(out, "lit.glb"), lit.glb())
    write(os.path.join(out, "lit.gltf"), lit.embedded())
    strip = Model()
    zigzag = [0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0]
    strip.node({"mesh": strip.mesh({"attributes": {"POSITION": strip.positions(zigzag)}, "mode": 5})})
    strip.node({"mesh": strip.mesh({"attributes": {"POSITION": strip.positions(zigzag)}, "mode": 6}),
                "translation": [0, 0, -1]})
    write(os.path.join(out, "strip.gltf"), strip.embedded())
    sparse = Model()
    indices = sparse.view(struct.pack("<2H", 1, 2))
    values = sparse.view(struct.pack("<6f", 1, 0, 0, 0, 1, 0))
    sparse.doc["accessors"] = [{"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
                                "sparse": {"count": 2, "indices": {"bufferView": indices, "componentType": 5123},
                                           "values": {"bufferView": values}}}]
    sparse.node({"mesh": sparse.mesh({"attributes": {"POSITION": 0}})})
    write(os.path.join(out, "sparse.glb"), sparse.glb())


if __name__ == "__main__":
    main()
