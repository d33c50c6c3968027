#!/usr/bin/env python3
"""Generates GhostSpace's node model from the Web3D X3D Unified Object Model (X3DUOM).

    vrml/gen/gen_node_model.py [--uom X3dUnifiedObjectModel-4.0.xml] [--check]

Reads ../shared/spec/x3d/X3dUnifiedObjectModel-4.0.xml (ISO/IEC 19775-1:2023 as data) and
writes, beside this script's module:

  vrml/include/vrml/node_model_types.inc  the X3D abstract node and object types and the
                                          concrete node types, as X-macro lists
  vrml/src/node_model_data_K.cpp          one NodeModel per concrete node type: component,
                                          level, the closure of its abstract types, the
                                          containerField default and every field (name,
                                          type, access type, default, acceptableNodeTypes),
                                          in files of at most MAX_LINES lines
  vrml/src/node_model_chunks.cpp          the list of those files' arrays

GhostSpace's extension nodes (docs/vrml-extensions.md) are declared in EXTENSIONS below
with the same vocabulary, so every module decides a node's class from one place.
With --check nothing is written: the script exits 1 when a committed file differs from
what it would write (the ctest `node_model_generated`).
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.normpath(os.path.join(HERE, "..", ".."))
DEFAULT_UOM = os.path.normpath(
    os.path.join(TOP, "..", "shared", "spec", "x3d", "X3dUnifiedObjectModel-4.0.xml"))
TYPES_INC = os.path.join(TOP, "vrml", "include", "vrml", "node_model_types.inc")

# GhostSpace's extension nodes, in X3DUOM's terms. Their fields are node_table_data.cpp's
# interfaces (only the node-valued ones need acceptable types here).
EXTENSIONS = [
    {
        "name": "OutlineGroup",
        "component": "GhostSpace",
        "level": 1,
        "bases": ["X3DGroupingNode"],
        "containerField": "children",
        "fields": [
            ("addChildren", "MFNode", "inputOnly", "", "X3DChildNode"),
            ("removeChildren", "MFNode", "inputOnly", "", "X3DChildNode"),
            ("children", "MFNode", "inputOutput", "", "X3DChildNode"),
            ("appearance", "SFNode", "inputOutput", "NULL", "X3DAppearanceNode"),
            ("groupId", "SFInt32", "initializeOnly", "-1", ""),
            ("outline", "MFVec3f", "initializeOnly", "", ""),
            ("outlineLengths", "MFInt32", "initializeOnly", "", ""),
            ("bboxCenter", "SFVec3f", "initializeOnly", "0 0 0", ""),
            ("bboxSize", "SFVec3f", "initializeOnly", "-1 -1 -1", ""),
        ],
    },
    {
        "name": "QuantizedNormalVectors",
        "component": "GhostSpace",
        "level": 1,
        "bases": ["X3DChildNode", "X3DBoundedObject", "X3DUrlObject"],
        "containerField": "children",
        "fields": [
            ("url", "MFString", "inputOutput", "", ""),
            ("fraction", "SFFloat", "inputOutput", "1", ""),
            ("count", "SFInt32", "inputOutput", "-1", ""),
            ("opacityScale", "SFFloat", "inputOutput", "1", ""),
            ("mode", "SFString", "inputOutput", '""', ""),
            ("position", "MFVec3f", "initializeOnly", "", ""),
            ("direction", "MFVec3f", "initializeOnly", "", ""),
            ("magnitude", "MFFloat", "initializeOnly", "", ""),
            ("color", "MFColor", "initializeOnly", "", ""),
            ("bboxCenter", "SFVec3f", "initializeOnly", "0 0 0", ""),
            ("bboxSize", "SFVec3f", "initializeOnly", "-1 -1 -1", ""),
        ],
    },
    {
        "name": "Skin",
        "component": "GhostSpace",
        "level": 1,
        "bases": ["X3DChildNode"],
        "containerField": "children",
        "fields": [
            ("skeleton", "MFNode", "inputOutput", "", "X3DGroupingNode"),
            ("joints", "MFNode", "inputOutput", "", "X3DGroupingNode"),
            ("inverseBindMatrices", "MFFloat", "initializeOnly", "", ""),
            ("skinnedTransform", "SFNode", "inputOutput", "NULL", "X3DGroupingNode"),
            ("coord", "SFNode", "inputOutput", "NULL", "X3DCoordinateNode"),
            ("normal", "SFNode", "inputOutput", "NULL", "X3DNormalNode"),
            ("restPoint", "MFVec3f", "inputOutput", "", ""),
            ("restNormal", "MFVec3f", "inputOutput", "", ""),
            ("vertexJoints", "MFInt32", "initializeOnly", "", ""),
            ("vertexWeights", "MFFloat", "initializeOnly", "", ""),
        ],
    },
    # X3D 4.1's EnvironmentLight (clause 17.4.2 of the 4.1 draft; X_ITE and castle-engine
    # read it): image-based lighting from cube maps. X3DUOM 4.0 does not have it yet, so
    # it is declared here with 4.1's interface, in its own component (Lighting, level 4).
    {
        "name": "EnvironmentLight",
        "extension": False,
        "component": "Lighting",
        "level": 4,
        "bases": ["X3DLightNode"],
        "containerField": "children",
        "fields": [
            ("ambientIntensity", "SFFloat", "inputOutput", "0", ""),
            ("color", "SFColor", "inputOutput", "1 1 1", ""),
            ("diffuseCoefficients", "MFFloat", "inputOutput", "", ""),
            ("diffuseTexture", "SFNode", "inputOutput", "NULL", "X3DEnvironmentTextureNode"),
            ("global", "SFBool", "inputOutput", "false", ""),
            ("intensity", "SFFloat", "inputOutput", "1", ""),
            ("metadata", "SFNode", "inputOutput", "NULL", "X3DMetadataObject"),
            ("on", "SFBool", "inputOutput", "true", ""),
            ("rotation", "SFRotation", "inputOutput", "0 0 1 0", ""),
            ("shadowIntensity", "SFFloat", "inputOutput", "1", ""),
            ("shadows", "SFBool", "inputOutput", "false", ""),
            ("specularTexture", "SFNode", "inputOutput", "NULL", "X3DEnvironmentTextureNode"),
        ],
    },    # X_ITE's experimental GaussianSplats node (X3D 4.1 draft component "GaussianSplats",
    # create3000/x_ite src/x_ite/Components/GaussianSplats/GaussianSplats.js): one 3D
    # Gaussian splatting cloud as fields, the attributes of glTF's KHR_gaussian_splatting
    # (linear scales, linear opacities, quaternions x y z w, SH coefficients by degree).
    # X_ITE's `orientations` is an MFQuaternion, a 4.1 type: here MFVec4f, the same four
    # numbers per value in every encoding. GhostSpace adds `url` (a capture file, any
    # format of docs/splats.md) so that a world places a scene under a Transform.
    {
        "name": "GaussianSplats",
        "extension": False,
        "component": "GaussianSplats",
        "level": 1,
        "bases": ["X3DChildNode", "X3DBoundedObject"],
        "containerField": "children",
        "fields": [
            ("metadata", "SFNode", "inputOutput", "NULL", "X3DMetadataObject"),
            ("url", "MFString", "inputOutput", "", ""),
            ("colorSpace", "SFString", "inputOutput", "SRGB_REC709_DISPLAY", ""),
            ("positions", "MFVec3f", "inputOutput", "", ""),
            ("orientations", "MFVec4f", "inputOutput", "", ""),
            ("scales", "MFVec3f", "inputOutput", "", ""),
            ("opacities", "MFFloat", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree0Coef0", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree1Coef0", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree1Coef1", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree1Coef2", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree2Coef0", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree2Coef1", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree2Coef2", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree2Coef3", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree2Coef4", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree3Coef0", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree3Coef1", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree3Coef2", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree3Coef3", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree3Coef4", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree3Coef5", "MFVec3f", "inputOutput", "", ""),
            ("sphericalHarmonicsDegree3Coef6", "MFVec3f", "inputOutput", "", ""),
            ("visible", "SFBool", "inputOutput", "true", ""),
            ("bboxDisplay", "SFBool", "inputOutput", "false", ""),
            ("bboxCenter", "SFVec3f", "initializeOnly", "0 0 0", ""),
            ("bboxSize", "SFVec3f", "initializeOnly", "-1 -1 -1", ""),
        ],
    },
]

# castle-engine's extension fields on the X3D primitives (castle's "X3D extensions"
# documentation; castle-engine's src/scene/x3d node declarations): Box, Cone, Cylinder,
# Sphere and Text take a `texCoord` that replaces the primitive's own texture mapping
# (castle accepts TextureCoordinateGenerator there, and its own ProjectedTextureCoordinate
# and MultiGeneratedTextureCoordinate, which GhostSpace does not have), and Box a `ccw`
# (FALSE turns its faces inside out). They are appended to the X3D node's model, so X3D
# worlds accept them; VRML97 worlds read node_table_data.cpp's interfaces and never see
# them. docs/x3d.md ("castle-engine's primitive fields") describes them.
_CASTLE_TEX_COORD = ("texCoord", "SFNode", "inputOutput", "NULL", "TextureCoordinateGenerator")
CASTLE_PRIMITIVE_FIELDS = {
    "Box": [("ccw", "SFBool", "initializeOnly", "true", ""), _CASTLE_TEX_COORD],
    "Cone": [_CASTLE_TEX_COORD],
    "Cylinder": [_CASTLE_TEX_COORD],
    "Sphere": [_CASTLE_TEX_COORD],
    "Text": [_CASTLE_TEX_COORD],
}


# X3D 4.1 fields X_ITE 15 reads on X3D 4.0 nodes (the 4.1 draft's interfaces; X3DUOM 4.0
# lacks them): BoundedPhysicsModel's `damping` (clause 40.4.1 of the 4.1 draft: the factor
# a bounce keeps of the speed), which X_ITE's Waterfall test world sets.
# The 4.1 draft's sound fields X_ITE 15 plays (clause 16): OscillatorSource's
# `periodicWave` (its wave; 4.0 has no way to choose one) and WaveShaper's `curve` (its
# transfer curve; 4.0 has none, so a 4.0 WaveShaper could only pass its input on).
X3D41_FIELDS = {
    # X3D 4.1's `pointerEvents` (X3DShapeNode and X3DLayerNode): FALSE makes a shape (a
    # layer) transparent to the pointing device. X_ITE 15 has it; its PlayerControls test
    # world sets it on the shapes of its buttons.
    "Shape": [("pointerEvents", "SFBool", "inputOutput", "true", "")],
    "ParticleSystem": [("pointerEvents", "SFBool", "inputOutput", "true", "")],
    "Layer": [("pointerEvents", "SFBool", "inputOutput", "true", "")],
    "LayoutLayer": [("pointerEvents", "SFBool", "inputOutput", "true", "")],
    "BoundedPhysicsModel": [("damping", "SFFloat", "inputOutput", "1", "")],
    "OscillatorSource": [("periodicWave", "SFNode", "inputOutput", "", "PeriodicWave")],
    "WaveShaper": [("curve", "MFFloat", "inputOutput", "", "")],
}


def add_castle_fields(concrete, extra):
    """Appends castle-engine's extension fields `extra` (node name -> field rows) to the
    models in `concrete`; a field the standard already declares is an error."""
    by_name = {c["name"]: c for c in concrete}
    for node, rows in extra.items():
        have = {f[0] for f in by_name[node]["fields"]}
        for row in rows:
            assert row[0] not in have, "%s.%s is already X3D's" % (node, row[0])
            by_name[node]["fields"].append(row)


# XML-encoding attributes X3DUOM lists as fields of every node (inherited from X3DNode);
# not interface members. FontStyle's own `style` is a field.
XML_ONLY_FIELDS = {"DEF", "USE", "class", "id", "style", "IS"}


def bases_of(definition):
    out = []
    for tag in ("Inheritance", "AdditionalInheritance"):
        for e in definition.findall(tag):
            out.append(e.get("baseType"))
    return out


def read_uom(path):
    root = ET.parse(path).getroot()
    abstract = {}  # name -> direct bases
    for kind in ("AbstractNodeType", "AbstractObjectType"):
        for n in root.iter(kind):
            abstract[n.get("name")] = bases_of(n.find("InterfaceDefinition"))
    concrete = []
    for n in root.iter("ConcreteNode"):
        d = n.find("InterfaceDefinition")
        comp = d.find("componentInfo")
        fields = []
        for f in d.findall("field"):
            name = f.get("name")
            if name in ("DEF", "USE", "IS") or (name in XML_ONLY_FIELDS and
                                                 f.get("inheritedFrom") == "X3DNode"):
                continue
            fields.append((f.get("name"), f.get("type"), f.get("accessType"),
                           f.get("default", ""), f.get("acceptableNodeTypes", "")))
        cf = d.find("containerField")
        concrete.append({
            "name": n.get("name"),
            "component": comp.get("name"),
            "level": int(comp.get("level")),
            "bases": bases_of(d),
            "containerField": cf.get("default") if cf is not None else "children",
            "fields": fields,
        })
    # X3DUOM 4.0 errata: ISO/IEC 19775-1 (X3D 4.0) clauses 18.4.8, 33.4.8 and 33.4.9 derive
    # TextureTransform, TextureTransformMatrix3D and TextureTransform3D from
    # X3DSingleTextureTransformNode, which MultiTextureTransform.textureTransform accepts;
    # X3DUOM gives them X3DTextureTransformNode only.
    for c in concrete:
        if c["name"] in SINGLE_TEXTURE_TRANSFORMS:
            c["bases"] = ["X3DSingleTextureTransformNode"]
    add_castle_fields(concrete, CASTLE_PRIMITIVE_FIELDS)
    add_castle_fields(concrete, X3D41_FIELDS)
    return abstract, concrete


SINGLE_TEXTURE_TRANSFORMS = ("TextureTransform", "TextureTransformMatrix3D", "TextureTransform3D")

# ---- castle-engine's extensions to X3D nodes (castle-model-viewer reads them) ----------------
# Fields castle-engine adds to standard X3D nodes (its "X3D extensions" documentation and the
# node declarations of castle-engine's src/scene/x3d), which its demo worlds
# (../shared/corpus/x3d/castle) use. They are appended to the X3D node's model only: X3D
# worlds accept them, VRML97 worlds read node_table_data.cpp's interfaces and never see
# them. docs/x3d.md ("castle-engine's extension fields") says what each one does here.
CASTLE_EXTENSION_FIELDS = {
    # X3DViewpointNode.autoCenterOfRotation: castle's Examine navigation picks the centre of
    # rotation from the world's bounding box; no effect on a snapshot (read and kept).
    "Viewpoint": [("autoCenterOfRotation", "SFBool", "inputOutput", "false", "")],
    "OrthoViewpoint": [("autoCenterOfRotation", "SFBool", "inputOutput", "false", "")],
    # X3DFogObject's volumetric fog: the fog amount follows the height along
    # volumetricDirection above volumetricVisibilityStart instead of the eye distance
    # (render/, docs/x3d.md "Volumetric fog").
    "Fog": [
        ("volumetric", "SFBool", "inputOutput", "false", ""),
        ("volumetricDirection", "SFVec3f", "inputOutput", "0 -1 0", ""),
        ("volumetricVisibilityStart", "SFFloat", "inputOutput", "0", ""),
    ],
    "LocalFog": [
        ("volumetric", "SFBool", "inputOutput", "false", ""),
        ("volumetricDirection", "SFVec3f", "inputOutput", "0 -1 0", ""),
        ("volumetricVisibilityStart", "SFFloat", "inputOutput", "0", ""),
    ],
    # castle's HAnimSegment is a transform like HAnimJoint and HAnimSite (translation,
    # rotation and scale place its children: scene/, vrml/transform.hpp placesChildren).
    "HAnimSegment": [
        ("rotation", "SFRotation", "inputOutput", "0 0 1 0", ""),
        ("scale", "SFVec3f", "inputOutput", "1 1 1", ""),
        ("translation", "SFVec3f", "inputOutput", "0 0 0", ""),
    ],
}

# Acceptable node types X3D 3.x allowed and X3D 4.0's model no longer lists, which castle's
# worlds (written for X3D 3.2) use: X3D 3.3 clause 26.3.2 gives HAnimJoint's children (and
# addChildren, removeChildren) as [HAnimJoint,HAnimSegment,HAnimSite], and H-Anim
# (ISO/IEC 19774:2006, 4.9 Site) places sites in joints too; X3D 4.0 (after ISO/IEC
# 19774-1:2019) lists HAnimJoint|HAnimSegment only.
CASTLE_X3D3_ACCEPTABLE = {
    ("HAnimJoint", "children"): "HAnimJoint|HAnimSegment|HAnimSite",
    ("HAnimJoint", "addChildren"): "HAnimJoint|HAnimSegment|HAnimSite",
    ("HAnimJoint", "removeChildren"): "HAnimJoint|HAnimSegment|HAnimSite",
}


def add_castle_extension_fields(concrete):
    """Appends CASTLE_EXTENSION_FIELDS to the models in `concrete` and widens the acceptable
    node types of CASTLE_X3D3_ACCEPTABLE; a field the standard already declares is an
    error."""
    by_name = {c["name"]: c for c in concrete}
    for node, rows in CASTLE_EXTENSION_FIELDS.items():
        have = {f[0] for f in by_name[node]["fields"]}
        for row in rows:
            assert row[0] not in have, "%s.%s is already X3D's" % (node, row[0])
            by_name[node]["fields"].append(row)
    for (node, field), acceptable in CASTLE_X3D3_ACCEPTABLE.items():
        fields = by_name[node]["fields"]
        for i, f in enumerate(fields):
            if f[0] == field:
                fields[i] = (f[0], f[1], f[2], f[3], acceptable)
                break
        else:
            raise AssertionError("%s has no field %s" % (node, field))


def closure(bases, abstract):
    seen = []
    stack = list(bases)
    while stack:
        b = stack.pop()
        if b in seen or b not in abstract:
            continue
        seen.append(b)
        stack.extend(abstract[b])
    return set(seen)


def cpp_string(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def words(indices):
    w = [0, 0]
    for i in indices:
        w[i // 64] |= 1 << (i % 64)
    return "AbstractTypeSet{0x%016xULL, 0x%016xULL}" % (w[0], w[1])


HEADER = "// Generated by vrml/gen/gen_node_model.py from the X3D Unified Object Model 4.0\n" \
         "// (../shared/spec/x3d/X3dUnifiedObjectModel-4.0.xml). Do not edit: run the script.\n"


def generate(uom):
    abstract, concrete = read_uom(uom)
    add_castle_extension_fields(concrete)
    abstract_names = sorted(abstract)
    assert len(abstract_names) <= 128, "AbstractTypeSet holds 128 types"
    index = {n: i for i, n in enumerate(abstract_names)}
    concrete_names = {c["name"] for c in concrete}
    for e in EXTENSIONS:
        e.setdefault("extension", True)
    models = sorted(concrete, key=lambda c: c["name"]) + EXTENSIONS
    ids = [m["name"] for m in models]

    types = [HEADER, "// X3D abstract node and object types (X3DUOM AbstractNodeType,\n"
             "// AbstractObjectType), alphabetical.\n#ifdef GS_ABSTRACT_TYPE\n"]
    types += ["GS_ABSTRACT_TYPE(%s)\n" % n for n in abstract_names]
    types.append("#endif\n// Concrete node types: X3D 4.0's, alphabetical, then GhostSpace's "
                 "extension nodes.\n#ifdef GS_NODE_TYPE\n")
    types += ["GS_NODE_TYPE(%s)\n" % n for n in ids]
    types.append("#endif\n")

    # One file per chunk of node types, each under MAX_LINES (the project keeps files
    # small); node_model.cpp joins the chunks' arrays (nodeModelChunks()).
    chunks = [[]]
    lines = 0
    for m in models:
        n = len(m["fields"]) + 3
        if chunks[-1] and lines + n > MAX_LINES:
            chunks.append([])
            lines = 0
        chunks[-1].append(m)
        lines += n
    files = {}
    for k, chunk in enumerate(chunks):
        files[chunk_path(k)] = chunk_source(k, chunk, index, concrete_names, ids, abstract)
    join = [HEADER, '#include "vrml/node_model.hpp"\n\n#include <array>\n\n'
            "// clang-format off\nnamespace gs::vrml {\n\n"]
    join += ["std::span<const NodeModel> nodeModelChunk%d();\n" % k for k in range(len(chunks))]
    join.append("\nstd::span<const std::span<const NodeModel>> nodeModelChunks() {\n"
                "  static const std::array<std::span<const NodeModel>, %d> kChunks = {\n" % len(chunks))
    join += ["      nodeModelChunk%d(),\n" % k for k in range(len(chunks))]
    join.append("  };\n  return kChunks;\n}\n\n}  // namespace gs::vrml\n// clang-format on\n")
    files[JOIN_CPP] = "".join(join)
    return "".join(types), files


MAX_LINES = 700
JOIN_CPP = os.path.join(TOP, "vrml", "src", "node_model_chunks.cpp")


def chunk_path(k):
    return os.path.join(TOP, "vrml", "src", "node_model_data_%d.cpp" % k)


def chunk_source(k, models, index, concrete_names, ids, abstract):
    data = [HEADER, '#include "vrml/node_model.hpp"\n\n// clang-format off\n'
            'namespace gs::vrml {\nnamespace {\n\n']
    data.append("using F = NodeFieldModel;\n\n")
    accept_arrays = {}
    body = []
    for m in models:
        rows = []
        for (name, ftype, access, default, acceptable) in m["fields"]:
            types_set, nodes = [], []
            for tok in filter(None, acceptable.split("|")):
                if tok in index:
                    types_set.append(index[tok])
                elif tok in concrete_names or tok in ids:
                    nodes.append(tok)
            nodes_ref = "{}"
            if nodes:
                key = "|".join(nodes)
                if key not in accept_arrays:
                    accept_arrays[key] = "kAccept%d" % len(accept_arrays)
                nodes_ref = accept_arrays[key]
            rows.append("    F{%s, %s, %s, %s, %s, %s, %s},\n" % (
                cpp_string(name), cpp_string(ftype), cpp_string(access), cpp_string(default),
                cpp_string(acceptable), words(types_set), nodes_ref))
        body.append("constexpr NodeFieldModel kFields%s[] = {\n%s};\n" % (m["name"], "".join(rows)))
    for key, var in accept_arrays.items():
        data.append("constexpr NodeTypeId %s[] = {%s};\n" % (
            var, ", ".join("NodeTypeId::" + n for n in key.split("|"))))
    data.append("\n")
    data += body
    data.append("\nconstexpr NodeModel kModels[] = {\n")
    for m in models:
        own = closure(m["bases"], abstract)
        data.append("    {%s, NodeTypeId::%s, %s, %d, %s, %s, kFields%s, %s},\n" % (
            cpp_string(m["name"]), m["name"], cpp_string(m["component"]), m["level"],
            words(sorted(index[t] for t in own)), cpp_string(m["containerField"]), m["name"],
            "true" if m.get("extension") else "false"))
    data.append("};\n\n}  // namespace\n\nstd::span<const NodeModel> nodeModelChunk%d() {\n"
                "  return kModels;\n}\n\n}  // namespace gs::vrml\n// clang-format on\n" % k)
    return "".join(data)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--uom", default=DEFAULT_UOM)
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    if not os.path.exists(args.uom):
        if os.environ.get("CI") or os.environ.get("GS_REQUIRE_ALL") == "1":
            print("missing fixture: X3DUOM: %s is absent" % args.uom)
            return 1
        print("GS_SKIP: X3DUOM: %s is absent" % args.uom)
        return 0
    types, files = generate(args.uom)
    outputs = {TYPES_INC: types}
    outputs.update(files)
    # A chunk file left from a larger model is stale too.
    k = 0
    while os.path.exists(chunk_path(k)):
        outputs.setdefault(chunk_path(k), None)
        k += 1
    status = 0
    for path, text in outputs.items():
        old = open(path).read() if os.path.exists(path) else None
        if args.check:
            if old != text:
                print("%s differs from what %s generates: run it" % (path, sys.argv[0]))
                status = 1
        elif text is None:
            os.remove(path)
        elif old != text:
            with open(path, "w") as f:
                f.write(text)
    if args.check and status == 0:
        print("node model matches X3DUOM (%s)" % args.uom)
    return status


if __name__ == "__main__":
    sys.exit(main())
